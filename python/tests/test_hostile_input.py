"""Bad input raises the documented exceptions (docs/python.md: TypeError for a wrong type, trionet.StatusError
or ValueError for a value out of range), and never crashes the interpreter: random calls and random bytes
run in a child interpreter that must exit normally."""

import subprocess
import sys
import textwrap

import pytest

import trionet
from trionet import basic, can as tcan, genius, learn, ring

HUGE = 10**30


@pytest.mark.parametrize("call,exception", [
    (lambda: ring.encode_print(HUGE, "A"), trionet.StatusError),
    (lambda: ring.encode_print(10, None), TypeError),
    (lambda: ring.encode_var(10, HUGE, 1), trionet.StatusError),
    (lambda: ring.encode_var(10, 1, "1"), TypeError),
    (lambda: ring.encode(ring.Message(ring.MessageType.character, HUGE, b"A")), trionet.StatusError),
    (lambda: ring.encode(ring.Message(99, 1, b"A")), ValueError),
    (lambda: ring.MotionCoordinator().send(HUGE, 1, 1), trionet.StatusError),
    (lambda: ring.MotionCoordinator().send(10, HUGE, 1), trionet.StatusError),
    (lambda: ring.MotionCoordinator().send("10", 1, 1), TypeError),
    (lambda: ring.MotionCoordinator().print(-HUGE, "A"), trionet.StatusError),
    (lambda: ring.MotionCoordinator().get(HUGE), trionet.StatusError),
    (lambda: ring.MotionCoordinator().receive(12), TypeError),
    (lambda: ring.MotionCoordinator(vr=HUGE), ValueError),
    (lambda: ring.Keypad().press(HUGE), ValueError),
    (lambda: ring.Keypad().press(None), (TypeError, ValueError)),
    (lambda: ring.Simulator(idle_byte_times=-1), ValueError),  # out of range (was pybind11's TypeError)
    (lambda: ring.Decoder().feed([1, 2, 3]), TypeError),
    (lambda: tcan.encode_vr(HUGE, 1), trionet.StatusError),
    (lambda: tcan.encode_vr(1, 1, byte_order=7), ValueError),
    (lambda: tcan.base_identifier(HUGE), trionet.StatusError),
    (lambda: tcan.route_of(10, nodes=HUGE), trionet.StatusError),
    (lambda: tcan.route_of("10"), TypeError),
    (lambda: tcan.decode_vr("0100"), TypeError),
    (lambda: genius.encode_character(HUGE), ValueError),
    (lambda: genius.decode_character(-1), ValueError),
    (lambda: genius.decode_character(1.5), TypeError),
    (lambda: genius.encode_transmission(genius.Transmission(HUGE, (genius.Segment(b"1"),))), trionet.StatusError),
    (lambda: genius.bus_scan_time("153.6s", [HUGE]), ValueError),
    (lambda: genius.analyse_turns([genius.Device(HUGE, 0)], "153.6s", 1), trionet.StatusError),
    (lambda: learn.learn_ring_crc([b"x" * 13]), ValueError),
    (lambda: learn.learn_ring_layout([], [(HUGE, 1.0)]), (ValueError, TypeError)),
    (lambda: basic.simulate(["mc", "mc"], keys=None), TypeError),
    (lambda: basic.simulate([basic.Program("\x00\xff" * 1000), "mc"]), ValueError),
    (lambda: trionet.Profile.from_json("[" * 100000), trionet.ProfileError),
    # An int or a list where text or bytes belong is a TypeError (bytes(5) would be five NUL bytes).
    (lambda: ring.encode_print(11, 5), TypeError),
    (lambda: ring.encode_print(11, [72, 73]), TypeError),
    (lambda: ring.encode_print(11, 10**12), TypeError),
    (lambda: ring.Message.characters(2, 5), TypeError),
    (lambda: genius.encode_transmission(genius.Transmission(1, (genius.Segment(3),))), TypeError),
    (lambda: learn.learn_genius_crc([(5, 1)]), TypeError),
    (lambda: learn.learn_ring_crc([14]), TypeError),
    # A float is not an address, a hop count or a byte count, even when it is whole.
    (lambda: ring.hops_from_basic_address(10.5), TypeError),
    (lambda: ring.hops_from_basic_address(12.0), TypeError),
    (lambda: ring.basic_address_from_hops(1.5), TypeError),
    (lambda: ring.encode_var(10.0, 200, 99), TypeError),
    (lambda: genius.bus_scan_time("153.6s", [1.5]), TypeError),
    (lambda: genius.device_scan_time_ns("153.6s", 1.5), TypeError),
    # Wrong types and ranges that reached the binding and came back as pybind11's generic message.
    (lambda: ring.Simulator(idle_byte_times=1.5), TypeError),
    (lambda: ring.MotionCoordinator().transmit(-1), ValueError),
    (lambda: ring.MotionCoordinator().transmit(2**64), ValueError),
    (lambda: ring.MotionCoordinator().transmit(None), TypeError),
    (lambda: ring.MotionCoordinator().transmit(1.5), TypeError),
    (lambda: ring.VrTable(4)[1.5], TypeError),
    (lambda: ring.q32_to_float(2**63), ValueError),
    (lambda: ring.q32_to_float(1.5), TypeError),
    (lambda: ring.q32_to_float(None), TypeError),
    (lambda: ring.Simulator([ring.MotionCoordinator(), ring.Keypad()]).run(1.5), TypeError),
    (lambda: ring.Simulator([ring.MotionCoordinator(), ring.Keypad()]).run(2**64), ValueError),
    (lambda: ring.Simulator([ring.MotionCoordinator(), ring.Keypad()]).drop_next(-1), ValueError),
    (lambda: ring.Simulator([ring.MotionCoordinator(), ring.Keypad()]).drop_next(2), ValueError),
    (lambda: ring.Simulator([ring.MotionCoordinator(), ring.Keypad()]).cut(0, "no"), TypeError),
    (lambda: ring.Keypad().press(None), TypeError),
    (lambda: ring.Keypad().press(3.0), TypeError),
    (lambda: ring.Keypad().press(True), TypeError),
    (lambda: ring.SerialLink(None, object()), TypeError),
    (lambda: ring.SerialLink(ring.MotionCoordinator(), None), TypeError),
    (lambda: trionet.Profile.from_json(None), TypeError),
    (lambda: trionet.Profile.from_json(5), TypeError),
    (lambda: setattr(trionet.Profile(), "name", None), TypeError),
    (lambda: trionet.Profile().header(None), TypeError),
    (lambda: basic.simulate("mc"), TypeError),
    (lambda: basic.simulate([basic.Program(None), "mc"]), TypeError),
    (lambda: basic.simulate(["mc", "keypad"], keys=5), TypeError),
    (lambda: basic.simulate(["mc", "mc"], byte_times=1.5), TypeError),
    (lambda: basic.simulate(["mc", "mc"], statements_per_byte_time=1.5), TypeError),
    (lambda: basic.simulate(["mc", "mc"], key_gap=1.5), TypeError),
    (lambda: basic.Network(["mc", "keypad"]).press(-1, "up"), ValueError),
    (lambda: basic.Network(["mc", "keypad"]).press(1, None), TypeError),
    (lambda: ring.VrTable(4).write_from_network(-1, 1), ValueError),
    (lambda: ring.VrTable(4).write_from_network(2**32, 1), ValueError),
    (lambda: ring.VrTable(4).write_from_network(1.5, 1), TypeError),
    (lambda: genius.encode_character(1.5), TypeError),
    (lambda: genius.encode_transmission(genius.Transmission(1.5, (genius.Segment(b"a"),))), TypeError),
    (lambda: genius.encode_transmission(genius.Transmission(1, (genius.Segment(b"a", True, 1.5),))), TypeError),
    (lambda: genius.TransmissionParser().push((1.5, True)), TypeError),
    (lambda: genius.analyse_turns([genius.Device(4, 0, 1.5)], "153.6s", 1), TypeError),
    (lambda: learn.learn_ring_crc([bytes(14)] * 3, max_classes=-1), ValueError),
    (lambda: learn.learn_ring_crc([bytes(14)] * 3, max_classes=2**64), ValueError),
    (lambda: learn.learn_genius_crc([(b"a", 1)], max_classes=1.5), TypeError),
    (lambda: learn.learn_ring_layout([bytes(14)], [(2**40, 1.0)]), ValueError),
    (lambda: learn.learn_ring_layout([bytes(14)], [(1, 1.0)], crc=learn.CrcParameters(2**20, 0, False, False, 0)),
     ValueError),
    (lambda: learn.learn_ring_layout([bytes(14)], [(1, 1.0)], crc=learn.CrcParameters(-1, 0, False, False, 0)),
     ValueError),
])
def test_bad_input_raises_the_documented_exception(call, exception):
    with pytest.raises(exception):
        call()


FUZZ = textwrap.dedent("""
    import random, sys
    import trionet
    from trionet import basic, can as tcan, genius, learn, ring

    rnd = random.Random(int(sys.argv[1]))
    values = [0, 1, -1, 2**31, -2**31, 2**63, 10**30, 255, 256, 65535, 16384, 10, 24, 25, 0.5, float("nan"),
              float("inf"), -1e300, None, "", "x" * 300, b"", b"\\x80" * 300, bytearray(20), "up", [], ()]
    def any_value():
        return rnd.choice(values) if rnd.random() < 0.8 else rnd.randbytes(rnd.randrange(40))
    calls = [ring.encode_print, ring.encode_var, ring.encode_offset, ring.encode_mode, ring.hops_from_basic_address,
             ring.q32_from_float, ring.q32_to_float, tcan.encode_vr, tcan.decode_vr, tcan.base_identifier,
             tcan.exchange_identifier, tcan.route_of, tcan.receive_identifier, tcan.transmit_identifier,
             genius.encode_character, genius.decode_character, genius.crc6, genius.device_scan_time_ns,
             genius.bus_scan_time, genius.rate_from_name, learn.learn_ring_crc, learn.variable_transfers,
             lambda *a: ring.Message.characters(*a), lambda *a: ring.VrTable(*a),
             lambda *a: genius.analyse_turns(*a), lambda *a: genius.simulate_scan(*a),
             lambda *a: learn.learn_genius_crc(*a), lambda *a: trionet.Profile.from_json(*a)]
    mc, keypad = ring.MotionCoordinator(), ring.Keypad()
    methods = [mc.print, mc.send, mc.send_keypad_offset, mc.send_keypad_mode, mc.get, mc.key, mc.receive,
               mc.transmit, keypad.press, keypad.release, keypad.receive]
    decoder = ring.Decoder()
    for i in range(20000):
        f = rnd.choice(calls + methods)
        args = [any_value() for _ in range(rnd.randrange(4))]
        try:
            f(*args)
        except (TypeError, ValueError, OverflowError, IndexError, KeyError, OSError):
            pass
        decoder.feed(rnd.randbytes(rnd.randrange(64)))
    sim = ring.Simulator([mc, keypad, ring.MotionCoordinator()])
    sim.run(2000)
    print("done")
""")


@pytest.mark.parametrize("seed", [1, 2])
def test_random_calls_never_crash_the_interpreter(seed):
    done = subprocess.run([sys.executable, "-c", FUZZ, str(seed)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.strip() == "done"


def test_numbers_too_large_for_any_field_are_refused_as_out_of_range():
    assert tcan.route_of(HUGE) is None
    assert genius.decode_character(HUGE).status is not genius.CharacterStatus.ok


def test_random_bytes_never_crash_a_node_or_the_decoder():
    import random

    rnd = random.Random(9)
    nodes = [ring.MotionCoordinator(), ring.Keypad(), ring.MotionCoordinator()]
    decoder = ring.Decoder()
    for _ in range(2000):
        data = rnd.randbytes(rnd.randrange(100))
        for node in nodes:
            node.receive(data)
            node.transmit()
            if rnd.random() < 0.1:
                node.line_idle()
        for event in decoder.feed(data):
            assert event.event in ("message", "frame_error", "crc_error", "no_room")
            event.to_dict()
    assert decoder.position > 0


NEW_WITHOUT_INIT = textwrap.dedent("""
    import can
    import trionet
    from trionet import _trionet, basic, can as tcan, genius, ring

    d = ring.Decoder.__new__(ring.Decoder)         # a working decoder with the default profile
    assert [(e.event, e.vr) for e in d.feed(ring.encode_var(10, 1, 1))] == [("message", 1)]
    v = ring.VrTable.__new__(ring.VrTable)         # a table of 1024 VRs
    assert len(v) == 1024 and v[0] == 0.0 and v.policy is None
    assert ring.MotionCoordinator(v).vr is v
    for make in [lambda: _trionet.ring.MotionCoordinator(None),
                 lambda: _trionet.can.VrExchangeNode(5, 1, print, None, 0)]:
        try:
            make()
        except TypeError:
            pass
        else:
            raise AssertionError("no TypeError")
    # The package's other classes hold their C++ object in an attribute: an AttributeError, not a crash.
    for cls, call in [(ring.MotionCoordinator, lambda o: o.receive(b"\\x88")), (ring.Keypad, lambda o: o.press(1)),
                      (ring.Simulator, lambda o: o.run(1)), (tcan.VrExchangeNode, lambda o: o.send(1, 1, 1)),
                      (genius.TransmissionParser, lambda o: o.push((1, True))), (trionet.Profile, lambda o: o.name)]:
        try:
            call(cls.__new__(cls))
        except (AttributeError, TypeError):
            pass
    print("done")
""")


def test_instances_made_with_new_alone_raise_or_work_never_crash():
    done = subprocess.run([sys.executable, "-c", NEW_WITHOUT_INIT], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.strip() == "done"


def test_a_node_keeps_its_vr_table_and_says_so():
    mc = ring.MotionCoordinator(4)
    with pytest.raises(AttributeError):
        mc.vr = ring.VrTable(4)
    mc.receive(ring.encode_var(10, 1, 5))
    assert mc.vr[1] == 5.0
    can = pytest.importorskip("can")
    with can.Bus(interface="virtual", channel="trionet-vr-table") as bus:
        node = tcan.VrExchangeNode(bus, 4, vr=8)
        with pytest.raises(AttributeError):
            node.vr = ring.VrTable(8)
        node.receive(tcan.to_message(1, 4, 1, 5.0))
        assert node.vr[1] == 5.0


def test_bus_scan_time_reads_an_iterator_once():
    listed = genius.bus_scan_time("153.6s", [4, 8, 16])
    assert listed.total_ns == 4831000
    assert genius.bus_scan_time("153.6s", (n for n in [4, 8, 16])) == listed
    assert genius.bus_scan_time("153.6s", range(3)) == genius.bus_scan_time("153.6s", [0, 1, 2])


@pytest.mark.parametrize("call,words", [
    (lambda: ring.encode_var(10, 200.0, 99), "vr is an int, not float"),
    (lambda: ring.encode_var(10.0, 200, 99), "a BASIC address is an int, not float"),
    (lambda: ring.encode(ring.Message.keypad_mode(1, 1.5)), "mode is an int, not float"),
    (lambda: tcan.encode_vr(1.0, 2), "vr is an int, not float"),
])
def test_a_wrong_type_is_named_by_its_argument(call, words):
    with pytest.raises(TypeError, match=words):
        call()
