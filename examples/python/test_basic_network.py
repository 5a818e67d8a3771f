"""A BASIC network test written as pytest: the programs of a ring run on the simulated ring (trionet.basic),
and the test asserts what a commissioning engineer would check on the real machine.

    python3 -m pytest examples/python/test_basic_network.py

The network: a master that hands out a part count and waits for each to be acknowledged, a feeder that
counts what it receives and acknowledges it, and the operator's keypad. Each result is the dict that
`trionet ring simulate --json` prints.
"""

from pathlib import Path

import pytest

from trionet import basic

EXAMPLES = Path(__file__).resolve().parents[1]

MASTER = """
' master: sends part numbers 1 to 10 to the feeder's VR(50) and waits for each in its own VR(51).
' First the keypad (two nodes on) gets its keypad offset, 1 hop back to here: a keypad in local mode
' forwards nothing, so the feeder's replies would never come round.
SEND(11,2,10)
FOR part = 1 TO 10
  SEND(10,1,50,part)
  WAIT UNTIL VR(51) = part
NEXT part
VR(60) = 1
PRINT "done"
"""

FEEDER = """
' feeder: acknowledges every new part number and keeps a running total in VR(52); the master is two
' nodes on round the ring (past the keypad): BASIC address 11
last = 0
WHILE last < 10
  WAIT UNTIL VR(50) <> last
  last = VR(50)
  VR(52) = VR(52) + last
  SEND(11,1,51,last)
WEND
"""


@pytest.fixture(scope="module")
def result():
    return basic.simulate([basic.Program(MASTER, "master.bas"), basic.Program(FEEDER, "feeder.bas"), "keypad"])


def test_the_run_settles(result):
    assert result["end"] == "settled"


def test_both_programs_end_without_error(result):
    master, feeder, _keypad = result["nodes"]
    assert (master["state"], master["error"]) == ("ended", None)
    assert (feeder["state"], feeder["error"]) == ("ended", None)


def test_every_part_was_counted_once(result):
    master, feeder, _keypad = result["nodes"]
    assert feeder["vr"]["52"] == sum(range(1, 11))
    assert master["vr"]["51"] == 10 and master["vr"]["60"] == 1


def test_the_ring_saw_no_errors(result):
    master, feeder, keypad = result["nodes"]
    assert (master["netstat"], feeder["netstat"], keypad["dropped"]) == (0, 0, 0)


def test_the_manuals_example_two_puts_the_keyed_values_in_place():
    events = []
    result = basic.simulate([f"mc:{EXAMPLES}/manual/example2_three_axis.bas",
                             f"mc:{EXAMPLES}/manual/example2_two_axis.bas", "keypad"],
                            keys="wait=1000 1:up 1:up 1:up 1:y 1:up 1:up 1:y 1:start", on_event=events.append)
    assert result["end"] == "settled"
    assert any(e.kind == "vr_from_ring" for e in events)
    built_in = basic.simulate_example("example2")  # the same programs, built into the package
    for mine, theirs in zip(result["nodes"], built_in["nodes"]):
        mine.pop("program", None)
        theirs.pop("program", None)
    assert result == built_in
