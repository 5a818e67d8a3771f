"""trionet.ring's nodes (MotionCoordinator, Keypad), VR tables and the simulated ring."""

import pytest

import trionet
from trionet import ring


def test_a_key_pressed_on_a_keypad_reaches_get_3_as_its_defkey_code():
    # README's example: the keypad after the MC, its offset sent as SEND(10,2,10).
    mc, keypad = ring.MotionCoordinator(), ring.Keypad()
    sim = ring.Simulator([mc, keypad])
    assert mc.send_keypad_offset(10, 10)
    sim.run(10)
    assert keypad.network_mode and keypad.offset == 1
    assert keypad.press("up") is ring.KeyStatus.ok
    sim.run(10)
    assert mc.key(3)
    assert mc.get(3) == 10
    assert mc.get(3) is None and not mc.key(4)


def test_a_keypad_in_local_mode_sends_nothing():
    keypad = ring.Keypad()
    assert keypad.press(ring.Key.digit_7) is ring.KeyStatus.local_mode
    assert keypad.counters()["keys_lost"] == 1
    assert keypad.transmit() == b""
    with pytest.raises(ValueError):
        keypad.press("F1")


def test_send_writes_the_next_controllers_vr_and_print_reaches_get():
    a, b = ring.MotionCoordinator(), ring.MotionCoordinator(vr=ring.VrTable(512))
    sim = ring.Simulator([a, b])
    assert a.send(10, 200, 99.5)
    assert a.print(10, "HI") == 2
    sim.run_until_quiet()
    sim.run(5)
    assert b.vr[200] == 99.5 and memoryview(b.vr)[200] == 99.5
    assert b.vr.nonzero() == {200: 99.5}
    assert [b.get(4), b.get(4), b.get(4)] == [ord("H"), ord("I"), None]
    assert b.counters()["variables_written"] == 1
    assert a.forwarding_counters()["messages_sent"] == 2


def test_clear_counters_starts_every_count_again_from_zero_and_keeps_netstat():
    a, b, keypad = ring.MotionCoordinator(), ring.MotionCoordinator(), ring.Keypad()
    sim = ring.Simulator([a, b, keypad])
    assert keypad.press("up") is ring.KeyStatus.local_mode  # counted as a key lost
    assert a.send(10, 3, 2.5) and a.send(11, 4, 1.0)  # one for b, one that b forwards to the keypad
    while a.send(10, 1, 1.0):
        pass  # until the transmit queue refuses one: NETSTAT bit 0
    sim.run_until_quiet()
    sim.run(5)
    assert a.forwarding_counters()["messages_sent"] >= 2 and b.counters()["variables_written"] >= 1
    assert b.forwarding_counters()["messages_forwarded"] == 1 and keypad.counters()["keys_lost"] == 1
    assert a.netstat & 1
    for node in (a, b, keypad):
        node.clear_counters()
        assert not any(node.counters().values()), node.counters()
        assert not any(node.forwarding_counters().values()), node.forwarding_counters()
    assert a.netstat & 1
    assert a.send(10, 5, 3.0)
    sim.run_until_quiet()
    sim.run(5)
    assert a.forwarding_counters()["messages_sent"] == 1 and b.counters()["variables_written"] == 1


def test_a_message_for_a_node_further_on_is_forwarded():
    nodes = [ring.MotionCoordinator() for _ in range(4)]
    sim = ring.Simulator(nodes)
    assert nodes[0].send(12, 7, -1.25)  # 3 hops along
    sim.run(100)
    assert [n.vr[7] for n in nodes] == [0, 0, 0, -1.25]
    assert nodes[1].forwarding_counters()["messages_forwarded"] == 1


def test_the_write_policy_refuses_and_its_exception_comes_back():
    a = ring.MotionCoordinator()
    b = ring.MotionCoordinator(write_policy=lambda vr, value: vr < 100)
    sim = ring.Simulator([a, b])
    a.send(10, 5, 1.0)
    a.send(10, 500, 2.0)
    sim.run(60)
    assert (b.vr[5], b.vr[500]) == (1.0, 0.0)
    assert b.counters()["variables_refused"] == 1

    def explode(vr, value):
        raise RuntimeError("policy failed")

    b.vr.policy = explode
    a.send(10, 6, 3.0)
    with pytest.raises(RuntimeError, match="policy failed"):
        sim.run(60)
    assert b.vr[6] == 0.0


class FailingTruth:
    def __bool__(self):
        raise RuntimeError("bool failed")


@pytest.mark.parametrize("answer,written", [(True, True), (1, True), ("yes", True), ([1], True), (2.5, True),
                                            (False, False), (0, False), (None, False), ("", False), ([], False)])
def test_a_write_policy_answer_is_taken_as_python_truth(answer, written):
    mc = ring.MotionCoordinator(write_policy=lambda vr, value: answer)
    mc.receive(ring.encode_var(10, 1, 5))
    assert mc.vr[1] == (5.0 if written else 0.0)
    assert mc.counters()["variables_written" if written else "variables_refused"] == 1


def test_an_exception_in_bool_of_a_policy_answer_is_raised_not_lost():
    mc = ring.MotionCoordinator(write_policy=lambda vr, value: FailingTruth())
    with pytest.raises(RuntimeError, match="bool failed"):
        mc.receive(ring.encode_var(10, 1, 5))
    assert mc.vr[1] == 0.0 and mc.counters()["variables_refused"] == 1
    table = ring.VrTable(4, policy=lambda vr, value: FailingTruth())
    with pytest.raises(RuntimeError, match="bool failed"):
        table.write_from_network(1, 2.0)
    assert table[1] == 0.0


def test_misuse_of_a_node_raises_and_a_full_queue_returns_false():
    mc = ring.MotionCoordinator()
    for call, status in [(lambda: mc.send(9, 1, 1), ring.SendStatus.bad_address),
                         (lambda: mc.send(10, 16384, 1), ring.SendStatus.vr_out_of_range),
                         (lambda: mc.send(10, 1, float("nan")), ring.SendStatus.value_out_of_range),
                         (lambda: mc.print(10, ""), ring.SendStatus.empty_text),
                         (lambda: mc.print(10, b"\xff"), ring.SendStatus.character_out_of_range),
                         (lambda: mc.send_keypad_offset(10, 30), ring.SendStatus.offset_out_of_range),
                         (lambda: mc.send_keypad_mode(10, 5), ring.SendStatus.mode_out_of_range),
                         (lambda: mc.get(5), ring.GetStatus.bad_channel)]:
        with pytest.raises(trionet.StatusError) as raised:
            call()
        assert raised.value.status is status
    sent = 0
    while mc.send(10, 1, 1.0):
        sent += 1
    assert sent >= 1 and mc.netstat & 1
    assert mc.print(10, "X" * 500) < 500
    mc.clear_netstat()
    assert mc.netstat == 0


def test_a_keypad_shows_what_is_printed_to_it():
    mc, keypad = ring.MotionCoordinator(), ring.Keypad()
    sim = ring.Simulator([mc, keypad])
    mc.send_keypad_offset(10, 10)
    mc.print(10, "\x0cSPEED:\r\nLENGTH:")
    sim.run(100)
    assert keypad.display == ("SPEED:".ljust(20), "LENGTH:".ljust(20))
    assert keypad.counters()["display_messages"] >= 1


def test_nodes_take_and_give_bytes_directly():
    mc = ring.MotionCoordinator()
    mc.receive(ring.encode_var(10, 3, 4.5))
    assert mc.vr[3] == 4.5
    mc.receive(memoryview(ring.encode_var(11, 3, 1.0)))  # for the next node: forwarded
    assert mc.transmit() == ring.encode_var(10, 3, 1.0)
    mc.receive(ring.encode_print(10, "AB")[:-1])  # for this node, its end of message lost
    assert mc.in_message
    mc.line_idle()
    assert not mc.in_message and mc.counters()["frame_errors"] == 1 and mc.netstat & 8
    mc.receive(ring.encode_print(11, "AB")[:-1])  # passing through, its end of message lost
    mc.line_idle()
    assert mc.forwarding_counters()["forwards_ended_idle"] == 1


def test_the_simulator_traces_and_injects_faults():
    a, b = ring.MotionCoordinator(), ring.MotionCoordinator()
    sim = ring.Simulator([a, b])
    seen = []
    a.send(10, 1, 2.0)
    sim.flip_next(0, 0x01)
    sim.run(20, trace=seen.append)
    assert seen[0].sent != seen[0].received and seen[0].link == 0
    assert b.vr[1] == 0.0 and b.counters()["frame_errors"] + b.counters()["crc_errors"] >= 1
    with pytest.raises(ValueError):
        ring.Simulator([a]).run(1)
    with pytest.raises(TypeError):
        sim.add("mc")
    full = ring.Simulator([ring.MotionCoordinator() for _ in range(15)])
    with pytest.raises(ValueError):
        full.add(ring.MotionCoordinator())

    def stop(byte):
        raise KeyError("trace")

    with pytest.raises(KeyError):
        a.send(10, 1, 2.0)
        sim.run(20, trace=stop)


def test_a_vr_table_is_a_buffer_of_doubles():
    table = ring.VrTable(16)
    view = memoryview(table)
    assert (view.format, view.itemsize, len(view)) == ("d", 8, 16)
    table[3] = 1.5
    assert view[3] == 1.5
    assert table.write_from_network(4, 2.25) is ring.VrWriteStatus.ok
    assert table.write_from_network(16, 1) is ring.VrWriteStatus.out_of_range
    assert table.write_from_network(1, 2.0**40) is ring.VrWriteStatus.value_out_of_range
    with pytest.raises(IndexError):
        table[16]
    with pytest.raises(ValueError):
        ring.VrTable(0)
