"""trionet.can: identifiers, the VR codec with python-can messages, and VrExchangeNode on python-can buses
and log files."""

import os
import subprocess
import threading
import time
import uuid

import can
import pytest

import trionet
from trionet import can as tcan


# The note's tables for 5 nodes (docs/protocol.md 2.1).
RECEIVE = {1: [10, 11, 12, 13], 2: [20, 21, 22, 23], 3: [30, 31, 32, 33], 4: [40, 41, 42, 43], 5: [50, 51, 52, 53]}
TRANSMIT = {1: [20, 30, 40, 50], 2: [31, 41, 51, 10], 3: [42, 52, 11, 21], 4: [53, 12, 22, 32], 5: [13, 23, 33, 43]}


def test_identifiers_are_the_notes_tables():
    for node in range(1, 6):
        assert tcan.base_identifier(node) == 10 * node
        assert [tcan.receive_identifier(node, r) for r in range(1, 5)] == RECEIVE[node]
        assert [tcan.transmit_identifier(node, c) for c in range(5, 9)] == TRANSMIT[node]
        for channel, identifier in zip(range(5, 9), TRANSMIT[node]):
            destination = tcan.destination_of(node, channel)
            assert tcan.exchange_identifier(node, destination) == identifier
            assert tcan.transmit_channel_to(node, destination) == channel
            route = tcan.route_of(identifier)
            assert (route.sender, route.receiver) == (node, destination)
    assert tcan.route_of(14) is None and tcan.route_of(0x800) is None


@pytest.mark.parametrize("call,status", [
    (lambda: tcan.base_identifier(6), tcan.SchemeStatus.bad_node),
    (lambda: tcan.base_identifier(1, nodes=12), tcan.SchemeStatus.bad_node_count),
    (lambda: tcan.exchange_identifier(2, 2), tcan.SchemeStatus.same_node),
    (lambda: tcan.receive_identifier(1, 5), tcan.SchemeStatus.bad_channel),
    (lambda: tcan.transmit_identifier(1, 9), tcan.SchemeStatus.bad_channel),
    (lambda: tcan.route_of(10, nodes=1), tcan.SchemeStatus.bad_node_count),
])
def test_identifier_questions_without_an_answer_raise(call, status):
    with pytest.raises(trionet.StatusError) as raised:
        call()
    assert raised.value.status is status


@pytest.mark.parametrize("sender,receiver,vr,value", [(1, 4, 1, 2.345), (3, 1, 255, -1000.5), (5, 2, 0, 0.0),
                                                      (2, 3, 17, 4294967295.0)])
def test_a_message_is_what_the_tool_encodes(run_cli, sender, receiver, vr, value):
    line = run_cli(["can", "encode", "--nodes", "5", "--from", str(sender), "--to", str(receiver), "--vr", str(vr),
                    "--value", repr(value)]).strip()
    message = tcan.to_message(sender, receiver, vr, value)
    identifier, data = line.split("#")
    assert (message.arbitration_id, bytes(message.data).hex().upper()) == (int(identifier, 16), data)
    assert not message.is_extended_id
    decoded = tcan.from_message(message)
    assert decoded and decoded.vr == vr and decoded.value == pytest.approx(value, abs=5e-5)
    assert decoded.route == tcan.Route(sender, receiver, tcan.route_of(message.arbitration_id).receive_channel)


def test_the_codec_rounds_and_orders_bytes_as_the_note_says():
    assert tcan.encode_vr(1, 2.345).hex() == "0100000000020d7a"
    assert tcan.encode_vr(1, 2.345, tcan.ByteOrder.little_endian).hex() == "0100020000007a0d"
    assert tcan.encode_vr(1, 0.99995).hex() == "0100000000010000"
    assert tcan.encode_vr(2, -0.00004).hex() == "0200000000000000"
    d = tcan.decode_vr(bytes.fromhex("0101000000020d7a"))
    assert (d.status, d.vr, d.negative, d.integer_part, d.fraction, d.value) == \
        (tcan.DecodeStatus.ok, 1, True, 2, 3450, -2.345)
    for status, call in [(tcan.EncodeStatus.vr_out_of_range, lambda: tcan.encode_vr(256, 1)),
                         (tcan.EncodeStatus.not_a_number, lambda: tcan.encode_vr(1, float("nan"))),
                         (tcan.EncodeStatus.too_large, lambda: tcan.encode_vr(1, 2.0**32))]:
        with pytest.raises(trionet.StatusError) as raised:
            call()
        assert raised.value.status is status


def test_malformed_data_is_a_status_not_an_exception():
    assert tcan.decode_vr(bytes(7)).status is tcan.DecodeStatus.bad_dlc
    assert tcan.decode_vr(bytes.fromhex("0102000000000000")).status is tcan.DecodeStatus.bad_sign
    assert tcan.decode_vr(bytes.fromhex("010000000000ffff")).status is tcan.DecodeStatus.bad_fraction
    assert not tcan.decode_vr(b"")
    remote = can.Message(arbitration_id=40, is_remote_frame=True, dlc=8, is_extended_id=False)
    assert tcan.from_message(remote).status is tcan.DecodeStatus.bad_dlc
    extended = can.Message(arbitration_id=40, is_extended_id=True, data=tcan.encode_vr(1, 1))
    assert tcan.from_message(extended).route is None


def virtual_bus(channel):
    return can.Bus(interface="virtual", channel=channel, receive_own_messages=False)


def test_two_nodes_exchange_vrs_over_the_virtual_bus():
    channel = f"trionet-{uuid.uuid4()}"
    with virtual_bus(channel) as bus1, virtual_bus(channel) as bus2:
        got = []
        a = tcan.VrExchangeNode(bus1, node=1, nodes=3)
        b = tcan.VrExchangeNode(bus2, node=3, nodes=3, on_vr=got.append)
        a.send(3, 10, 1.5)
        a.send(3, 11, -2.25)
        assert b.poll(0.2) == 2
        assert (b.vr[10], b.vr[11]) == (1.5, -2.25)
        assert got == [tcan.ReceivedVr(1, 10, 1.5, 1), tcan.ReceivedVr(1, 11, -2.25, 1)]
        assert [r.vr for r in b.received(0)] == [10, 11]
        b.send(1, 5, 7.0)
        (received,) = list(a.received(0.5))
        assert (received.sender, received.vr, received.value) == (3, 5, 7.0)
        assert a.counters()["sent"] == 2 and a.counters()["written"] == 1
        assert b.counters()["written"] == 2
        b.clear_counters()
        assert b.counters()["written"] == 0


def test_a_node_in_its_own_thread_hands_vrs_to_an_iterator():
    channel = f"trionet-{uuid.uuid4()}"
    with virtual_bus(channel) as bus1, virtual_bus(channel) as bus2:
        a = tcan.VrExchangeNode(bus1, node=1, nodes=2)
        with tcan.VrExchangeNode(bus2, node=2, nodes=2) as b:
            b.start()
            for i in range(100):
                a.send(2, i % 256, float(i))
            values = [r.value for _, r in zip(range(100), b.received(10.0))]
            assert values == [float(i) for i in range(100)]
            with pytest.raises(RuntimeError):
                b.poll()
        assert b._notifier is None


def run_with_timeout(body, seconds=10.0):
    """Runs body() in a thread; fails (instead of hanging the suite) if it has not returned in time."""
    outcome = []
    thread = threading.Thread(target=lambda: outcome.append(body()), daemon=True)
    thread.start()
    thread.join(seconds)
    assert not thread.is_alive(), "the call did not return (deadlock)"
    return outcome[0]


def test_a_write_policy_may_call_its_own_node():
    # The node runs the policy while it holds its lock: a policy that sends, reads the counters or feeds the
    # node again must not deadlock (as a ring MotionCoordinator's policy may call mc.send).
    channel = f"trionet-{uuid.uuid4()}"
    with virtual_bus(channel) as bus1, virtual_bus(channel) as bus4:
        node1 = tcan.VrExchangeNode(bus1, 1)
        seen = []

        def echo_policy(vr, value):  # accept, and echo the value back to node 1
            seen.append(node4.counters()["written"])
            node4.send(1, vr, value)
            return True

        node4 = tcan.VrExchangeNode(bus4, 4, write_policy=echo_policy)
        node1.send(4, 10, 2.5)
        assert run_with_timeout(lambda: node4.poll(0.2)) == 1
        assert node4.vr[10] == 2.5 and seen == [0]
        assert node4.counters()["sent"] == 1 and node4.counters()["written"] == 1
        assert run_with_timeout(lambda: node1.poll(0.2)) == 1
        assert node1.vr[10] == 2.5

        # A policy that feeds its node another frame (a bus that loops back, a log replayed from the policy).
        inner = tcan.to_message(1, 4, 11, 7.0)
        fed = []

        def feeding_policy(vr, value):
            if vr == 12:
                fed.append(node4.receive(inner).status)
            return True

        node4.vr.policy = feeding_policy
        result = run_with_timeout(lambda: node4.receive(tcan.to_message(1, 4, 12, 3.0)))
        assert result.status is tcan.ReceiveStatus.ok and fed == [tcan.ReceiveStatus.ok]
        assert (node4.vr[11], node4.vr[12]) == (7.0, 3.0)
        assert [r.vr for r in node4.received(0)] == [10, 11, 12]


def test_frames_not_for_a_node_are_counted_not_raised():
    channel = f"trionet-{uuid.uuid4()}"
    with virtual_bus(channel) as bus:
        node = tcan.VrExchangeNode(bus, node=2, vr=128)
        results = [node.receive(m) for m in [
            can.Message(arbitration_id=10, is_extended_id=False, data=tcan.encode_vr(1, 1)),  # for node 1
            can.Message(arbitration_id=20, is_extended_id=False, data=bytes(7)),
            can.Message(arbitration_id=21, is_extended_id=False, data=bytes.fromhex("0105000000000000")),
            can.Message(arbitration_id=22, is_extended_id=False, data=bytes.fromhex("010000000000ffff")),
            can.Message(arbitration_id=20, is_extended_id=True, data=tcan.encode_vr(1, 1)),
            can.Message(arbitration_id=20, is_remote_frame=True, is_extended_id=False, dlc=8),
            can.Message(arbitration_id=20, is_error_frame=True),
            can.Message(arbitration_id=20, is_extended_id=False, data=tcan.encode_vr(200, 1)),  # past the table
        ]]
        # A remote frame is never an exchange frame: foreign, as an extended one (can/node.hpp).
        assert [r.status.name for r in results] == ["foreign", "bad_dlc", "bad_sign", "bad_fraction", "foreign",
                                                    "foreign", "foreign", "out_of_range"]
        counters = node.counters()
        assert (counters["foreign"], counters["bad_dlc"], counters["bad_sign"], counters["bad_fraction"],
                counters["out_of_range"]) == (3, 1, 1, 1, 1)


def test_an_identifier_that_does_not_fit_is_never_masked_into_a_vr_write():
    # 0x828 masked to 11 bits is 0x028 (node 1 to node 4): the tool says bad_identifier, the node foreign.
    data = bytes.fromhex("0100000000020d7a")
    message = can.Message(arbitration_id=0x828, data=data, is_extended_id=False)
    assert tcan.from_message(message).status is tcan.DecodeStatus.bad_identifier
    assert not tcan.from_message(message)
    too_wide = can.Message(arbitration_id=0x20000028, data=data, is_extended_id=True)
    assert tcan.from_message(too_wide).status is tcan.DecodeStatus.bad_identifier
    for identifier in (2**40, -1):  # from a log or a bus written by hand: classified, not raised
        odd = can.Message(arbitration_id=0x28, data=data, is_extended_id=False)
        odd.arbitration_id = identifier
        assert tcan.from_message(odd).status is tcan.DecodeStatus.bad_identifier
    with virtual_bus(f"trionet-{uuid.uuid4()}") as bus:
        node = tcan.VrExchangeNode(bus, 4)
        assert node.receive(message).status is tcan.ReceiveStatus.foreign
        odd = can.Message(arbitration_id=0x28, data=data, is_extended_id=False)
        odd.arbitration_id = 2**40 + 0x28
        assert node.receive(odd).status is tcan.ReceiveStatus.foreign
        assert node.vr[1] == 0.0
        assert (node.counters()["foreign"], node.counters()["written"]) == (2, 0)
        assert node.receive(can.Message(arbitration_id=0x28, data=data, is_extended_id=False))
        assert node.vr[1] == 2.345


def test_a_dlc_above_the_data_given_is_bad_dlc_not_zero_filled():
    # python-can makes Message(data=b"\x01", dlc=8) (check=False); the tool says bad_dlc of 028#01.
    short = can.Message(arbitration_id=0x28, data=b"\x01", dlc=8, is_extended_id=False)
    assert tcan.from_message(short).status is tcan.DecodeStatus.bad_dlc
    negative = can.Message(arbitration_id=0x28, data=tcan.encode_vr(1, 1), is_extended_id=False)
    negative.dlc = -1
    assert tcan.from_message(negative).status is tcan.DecodeStatus.bad_dlc
    with virtual_bus(f"trionet-{uuid.uuid4()}") as bus:
        node = tcan.VrExchangeNode(bus, 4)
        assert node.receive(short).status is tcan.ReceiveStatus.bad_dlc
        assert node.receive(negative).status is tcan.ReceiveStatus.bad_dlc
        assert (node.counters()["bad_dlc"], node.counters()["written"]) == (2, 0)
        assert node.vr[1] == 0.0


def test_misuse_of_a_node_raises():
    channel = f"trionet-{uuid.uuid4()}"
    with virtual_bus(channel) as bus:
        with pytest.raises(trionet.StatusError) as raised:
            tcan.VrExchangeNode(bus, node=6, nodes=5)
        assert raised.value.status is tcan.SchemeStatus.bad_node
        node = tcan.VrExchangeNode(bus, node=1)
        for to, vr, value, status in [(1, 1, 1.0, tcan.SendStatus.own_node), (6, 1, 1.0, tcan.SendStatus.no_such_node),
                                      (2, 256, 1.0, tcan.SendStatus.vr_out_of_range),
                                      (2, 1, float("nan"), tcan.SendStatus.not_a_number),
                                      (2, 1, 1e10, tcan.SendStatus.too_large)]:
            with pytest.raises(trionet.StatusError) as raised:
                node.send(to, vr, value)
            assert raised.value.status is status
        assert node.counters()["sent"] == 0


def test_a_bus_that_fails_raises_its_own_error_and_is_counted():
    class FailingBus(can.BusABC):
        def __init__(self):
            super().__init__(channel="failing")

        def send(self, msg, timeout=None):
            raise can.CanOperationError("bus off")

        def _recv_internal(self, timeout):
            return None, False

    bus = FailingBus()
    node = tcan.VrExchangeNode(bus, node=1)
    with pytest.raises(can.CanOperationError, match="bus off"):
        node.send(2, 1, 1.0)
    assert node.counters()["send_failed"] == 1 and node.counters()["sent"] == 0
    bus.shutdown()


@pytest.mark.parametrize("writer,reader,suffix", [(can.ASCWriter, can.ASCReader, ".asc"),
                                                  (can.BLFWriter, can.BLFReader, ".blf")])
def test_frames_from_log_files_decode_to_the_vrs_written(tmp_path, writer, reader, suffix):
    sent = [(1, 4, 1, 2.345), (2, 4, 200, -17.5), (5, 4, 3, 1234567.8901), (4, 1, 9, 0.0001), (3, 4, 255, -0.5)]
    path = tmp_path / ("log" + suffix)
    log = writer(str(path))
    for i, (sender, receiver, vr, value) in enumerate(sent):
        message = tcan.to_message(sender, receiver, vr, value)
        message.timestamp = 1700000000.0 + i * 0.001
        log.on_message_received(message)
    log.on_message_received(can.Message(arbitration_id=0x123, is_extended_id=False, data=b"\x01\x02",
                                        timestamp=1700000000.01))
    log.stop()
    messages = list(reader(str(path)))
    assert len(messages) == len(sent) + 1
    decoded = [tcan.from_message(m) for m in messages[:-1]]
    assert [(d.route.sender, d.route.receiver, d.vr) for d in decoded] == [(s, r, v) for s, r, v, _ in sent]
    assert [d.value for d in decoded] == pytest.approx([x for *_, x in sent], abs=5e-5)
    # Node 4's view of the log: what it would have written.
    with can.Bus(interface="virtual", channel=f"trionet-{uuid.uuid4()}") as bus:
        node4 = tcan.VrExchangeNode(bus, node=4)
        results = [node4.receive(m) for m in messages]
        assert [r.status.name for r in results] == ["ok", "ok", "ok", "foreign", "ok", "foreign"]
        assert node4.vr.nonzero() == {1: 2.345, 200: -17.5, 3: 1234567.8901, 255: -0.5}


def vcan_interface():
    """A vcan interface to use, or None with the reason."""
    if not os.path.exists("/sys/class/net"):
        return None, "no /sys/class/net"
    for name in sorted(os.listdir("/sys/class/net")):
        try:
            with open(f"/sys/class/net/{name}/type") as f:
                if f.read().strip() == "280":  # ARPHRD_CAN
                    with open(f"/sys/class/net/{name}/operstate") as g:
                        if g.read().strip() in ("up", "unknown"):
                            return name, ""
        except OSError:
            continue
    return None, ("no CAN interface is up (the kernel needs vcan: `modprobe vcan; ip link add vcan0 type vcan; "
                  "ip link set vcan0 up`)")


def test_two_nodes_exchange_vrs_over_socketcan():
    interface, reason = vcan_interface()
    if interface is None:
        pytest.skip(reason)
    with can.Bus(interface="socketcan", channel=interface) as bus1, \
            can.Bus(interface="socketcan", channel=interface) as bus2:
        a = tcan.VrExchangeNode(bus1, node=1, nodes=2)
        b = tcan.VrExchangeNode(bus2, node=2, nodes=2)
        for i in range(50):
            a.send(2, i, i + 0.5)
        assert b.wait_for(lambda: b.counters()["written"] == 50, 5.0)
        assert [b.vr[i] for i in range(50)] == [i + 0.5 for i in range(50)]
