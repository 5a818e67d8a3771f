"""The example programs of examples/python/ do what their docstrings say."""

import json
import os
import subprocess
import sys
from collections import Counter
from pathlib import Path

import trionet
from trionet import ring

ROOT = Path(__file__).resolve().parents[2]
ENV = dict(os.environ, PYTHONPATH=str(Path(trionet.__file__).resolve().parents[1]))


def run(args):
    done = subprocess.run([sys.executable] + args, cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=600)
    return done.returncode, done.stdout, done.stderr


def test_the_capture_analysis_counts_what_the_tool_decodes(run_cli, tmp_path):
    capture = (ring.encode_var(10, 3, 1.5) * 3 + b"\x01\x02" + ring.encode_print(11, "HELLO") * 2
               + ring.encode_print(10, "CUT")[:-1])
    path = tmp_path / "capture.bin"
    path.write_bytes(capture)
    status, out, err = run(["examples/python/ring_capture_analysis.py", str(path)])
    assert status == 0, err
    tool = Counter((e["event"], e.get("type", e.get("reason", e["event"]))) for e in
                   map(json.loads, run_cli(["ring", "decode", "--raw"], stdin=capture).splitlines()))
    assert tool == Counter({("message", "var"): 3, ("frame_error", "stray_data"): 1, ("message", "char"): 2,
                            ("unfinished", "unfinished"): 1})
    assert out.splitlines() == [
        f"{len(capture)} bytes, 7 events",
        "  char         hops 2                2",
        "  frame_error  stray_data            1  (first at byte 48)",
        "  unfinished   unfinished            1  (first at byte 64)",
        "  var          hops 1                3",
        "last value of each VR: VR(3)=1.5",
    ]
    status, out, _ = run(["examples/python/ring_capture_analysis.py", "--json", str(path)])
    assert [json.loads(line) for line in out.splitlines()] == [e.to_dict() for e in ring.decode(capture)]


def test_the_can_bench_finds_nothing_lost():
    status, out, err = run(["examples/python/can_bench.py", "--count", "3000", "--nodes", "3", "--receiver", "2"])
    assert status == 0, err
    assert "3000 VRs sent, 3000 received, 0 lost, 0 wrong" in out


def test_the_examples_refuse_bad_arguments_with_a_message(tmp_path):
    """No traceback and no nonsense counts: each bad argument is named (s37 item 16)."""
    cases = [
        (["examples/python/can_bench.py", "--count", "-1"], 2, "--count is the number of VRs to send, at least 1"),
        (["examples/python/can_bench.py", "--sender", "4", "--receiver", "4"], 2, "a node does not send to itself"),
        (["examples/python/can_bench.py", "--nodes", "3", "--receiver", "9"], 2, "9"),
        (["examples/python/ring_capture_analysis.py", str(tmp_path / "none.bin")], 1,
         "cannot open " + str(tmp_path / "none.bin") + ": No such file or directory"),
        (["examples/python/ring_capture_analysis.py", str(tmp_path)], 1, "Is a directory"),
        (["examples/python/ring_capture_analysis.py", "--profile", str(tmp_path / "p.json")], 1,
         "profile " + str(tmp_path / "p.json") + ": No such file or directory"),
    ]
    (tmp_path / "bad.json").write_text("{")
    cases.append((["examples/python/ring_capture_analysis.py", "--profile", str(tmp_path / "bad.json")], 1,
                  "not_json"))
    for args, expected_status, words in cases:
        status, out, err = run(args)
        assert status == expected_status and words in err and "Traceback" not in err, (args, status, err)
        assert out == "", args


def test_the_examples_help_gives_the_whole_first_sentence():
    for script, end in (("can_bench.py", "with the value sent."),
                        ("ring_capture_analysis.py", "the last value of every VR written.")):
        status, out, _ = run([f"examples/python/{script}", "--help"])
        assert status == 0 and end in " ".join(out.split()), out
