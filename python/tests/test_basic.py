"""trionet.basic against `trionet ring simulate --json`: the same networks give the same result."""

import json

import pytest

from trionet import basic


def cli_summary(run_cli, args, status=0):
    return json.loads(run_cli(["ring", "simulate"] + args + ["--json"], status=status).splitlines()[-1])


@pytest.mark.parametrize("name", ["example1", "example2", "example3", "example3-fixed"])
def test_the_built_in_networks_give_the_tools_result(run_cli, name):
    assert basic.simulate_example(name) == cli_summary(run_cli, [name])


def test_the_examples_are_the_tools():
    assert basic.examples() == ["example1", "example2", "example3", "example3-fixed"]


def test_programs_from_files_give_the_tools_result(run_cli, root):
    nodes = [f"mc:{root}/examples/two_controllers/ping.bas", f"mc:{root}/examples/two_controllers/pong.bas"]
    result = basic.simulate(nodes)
    assert result == cli_summary(run_cli, ["--node", nodes[0], "--node", nodes[1]])
    assert result["end"] == "settled" and result["nodes"][0]["vr"] == {"21": 5}


def test_a_program_given_as_text_runs_with_keys_and_a_limit(run_cli, tmp_path):
    program = "WHILE TRUE\n  GET #4, k\n  VR(10)=VR(10)+k\nWEND\n"
    (tmp_path / "sum.bas").write_text(program)
    keys = "1:7 1:up 1:y"
    result = basic.simulate([basic.Program(program, name=str(tmp_path / "sum.bas")), "mc", "keypad"],
                            keys=keys, byte_times=20000)
    expected = cli_summary(run_cli, ["--node", "mc:" + str(tmp_path / "sum.bas"), "--node", "mc", "--node", "keypad",
                                     "--keys", keys, "--byte-times", "20000"], status=0)
    assert result == expected


def test_events_arrive_as_they_happen():
    events = []
    basic.simulate_example("example3", on_event=events.append)
    kinds = {e.kind for e in events}
    assert "dropped" in kinds and "ended" in kinds
    assert all(e.time >= 0 and e.node >= 1 for e in events)
    traced = []
    basic.simulate_example("example1", trace=True, on_event=traced.append)
    assert {"message", "display", "key"} <= {e.kind for e in traced}
    assert any(len(e.display) == 2 for e in traced if e.kind == "display")


def test_an_exception_in_the_event_callback_is_raised_after_the_run():
    def stop(event):
        raise LookupError("stop")

    network = basic.Network(["mc:examples/manual/example1.bas", "keypad", "keypad"], _builtin=True, on_event=stop,
                            keys="1:1")
    with pytest.raises(LookupError):
        network.run()


@pytest.mark.parametrize("nodes,match", [
    ([basic.Program("PRINT (")], "program.bas:1"),
    (["mc"], "2"),
    (["keypad", "keypad"], "Motion Coordinator"),
    (["mc"] * 16, "15"),
    (["mc", "robot"], "robot"),
])
def test_a_network_that_cannot_run_is_refused_with_the_reason(nodes, match):
    if len(nodes) == 1 and isinstance(nodes[0], basic.Program):
        nodes = nodes + ["mc"]
    with pytest.raises(ValueError, match=match):
        basic.simulate(nodes)


def test_bad_arguments_are_refused(tmp_path):
    with pytest.raises(ValueError, match="F1"):
        basic.simulate(["mc", "keypad"], keys="1:F1")
    with pytest.raises(IsADirectoryError):
        basic.simulate(["mc:" + str(tmp_path), "mc"])
    with pytest.raises(FileNotFoundError):
        basic.simulate(["mc:" + str(tmp_path / "missing.bas"), "mc"])
    big = tmp_path / "big.bas"
    big.write_bytes(b"' x\n" * (basic.MAX_PROGRAM_BYTES // 4 + 1))
    with pytest.raises(ValueError, match="longer"):
        basic.simulate(["mc:" + str(big), "mc"])
    for bad in [dict(byte_times=0), dict(bit_rate=0), dict(statements_per_byte_time=0), dict(key_gap=-1)]:
        with pytest.raises(ValueError):
            basic.simulate(["mc", "mc"], **bad)
    with pytest.raises(ValueError, match="unknown network"):
        basic.simulate_example("example9")
