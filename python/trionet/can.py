"""Trio's CANbus VR exchange, application note TN20-17 (docs/protocol.md section 2), with python-can.

The identifier scheme (node k of N listens on 10k .. 10k + N - 2), the VR message codec (VR, sign, integer
part, four decimals) to and from :class:`can.Message`, and :class:`VrExchangeNode`: the library's node on any
python-can bus (SocketCAN, PEAK, Kvaser, Vector, IXXAT, the virtual bus ...), or fed from a log file read by
python-can (ASC, BLF, TRC, candump). Misuse raises :class:`trionet.StatusError`; frames that are not for a
node, or malformed, are classified and counted, never raised.
"""

from __future__ import annotations

import collections
import threading
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Deque, Dict, Iterator, Optional, Tuple, Union

from . import _trionet
from ._errors import StatusError, int_enum, number, small
from .ring import VrTable

if TYPE_CHECKING:
    import can as python_can

_core = _trionet.can
_e = _core.enums

SchemeStatus = int_enum("SchemeStatus", _e["SchemeStatus"], __name__,
                        "Why an identifier question has no answer (can::scheme_status).")
EncodeStatus = int_enum("EncodeStatus", _e["EncodeStatus"], __name__,
                        "Why a VR message could not be encoded (can::encode_status).")
DecodeStatus = int_enum("DecodeStatus", list(_e["DecodeStatus"]) + [("bad_identifier", len(_e["DecodeStatus"]))],
                        __name__,
                        "Whether 8 data bytes are a VR message (can::decode_status); ``bad_identifier`` (the "
                        "package's own, as the tool's record kind) is a message whose identifier does not fit its "
                        "format (a standard identifier above 0x7FF, an extended one above 0x1FFFFFFF).")
ByteOrder = int_enum("ByteOrder", _e["ByteOrder"], __name__,
                     "The byte order of a message's integer part and fraction (can::byte_order).")
SendStatus = int_enum("SendStatus", _e["SendStatus"], __name__, "What became of a send (can::send_status).")
ReceiveStatus = int_enum("ReceiveStatus", _e["ReceiveStatus"], __name__,
                         "What became of a received frame (can::receive_status).")

MIN_NODE_COUNT: int = _core.MIN_NODE_COUNT
MAX_NODE_COUNT: int = _core.MAX_NODE_COUNT
DEFAULT_NODE_COUNT: int = _core.DEFAULT_NODE_COUNT
MAX_MESSAGE_VR: int = _core.MAX_MESSAGE_VR


def _answer(result: Any, what: str) -> int:
    status, value = result
    if status != 0:
        raise StatusError(SchemeStatus(status), what)
    return int(value)


# ---- identifiers ----------------------------------------------------------------------------------------


def base_identifier(node: int, nodes: int = DEFAULT_NODE_COUNT) -> int:
    """Node ``node``'s base identifier, 10 * node (also its receive channel 1)."""
    return _answer(_core.base_identifier(small(nodes, 255), small(node, 255)), f"node {node} of {nodes}")


def receive_identifier(node: int, channel: int, nodes: int = DEFAULT_NODE_COUNT) -> int:
    """The identifier ``node`` listens on with receive channel ``channel`` (1..N-1): 10 * node + channel - 1."""
    return _answer(_core.receive_identifier(small(nodes, 255), small(node, 255), small(channel, 255)), f"node {node} channel {channel} of {nodes}")


def exchange_identifier(sender: int, receiver: int, nodes: int = DEFAULT_NODE_COUNT) -> int:
    """The identifier of a frame from ``sender`` to ``receiver``."""
    return _answer(_core.exchange_identifier(small(nodes, 255), small(sender, 255), small(receiver, 255)), f"{sender} to {receiver} of {nodes}")


def transmit_identifier(sender: int, channel: int, nodes: int = DEFAULT_NODE_COUNT) -> int:
    """The identifier ``sender``'s transmit channel (5..N+3) puts on the bus (the note's second table)."""
    return _answer(_core.transmit_identifier(small(nodes, 255), small(sender, 255), small(channel, 255)), f"node {sender} channel {channel} of {nodes}")


def destination_of(sender: int, channel: int, nodes: int = DEFAULT_NODE_COUNT) -> int:
    """The node ``sender``'s transmit channel (5..N+3) sends to."""
    return _answer(_core.destination_of(small(nodes, 255), small(sender, 255), small(channel, 255)), f"node {sender} channel {channel} of {nodes}")


def transmit_channel_to(sender: int, destination: int, nodes: int = DEFAULT_NODE_COUNT) -> int:
    """The transmit channel (5..N+3) with which ``sender`` reaches ``destination``."""
    return _answer(_core.transmit_channel_to(small(nodes, 255), small(sender, 255), small(destination, 255)), f"{sender} to {destination} of {nodes}")


@dataclass(frozen=True)
class Route:
    """What an exchange identifier means: who sends, who receives, on which receive channel."""

    sender: int
    receiver: int
    receive_channel: int


def route_of(identifier: int, nodes: int = DEFAULT_NODE_COUNT) -> Optional[Route]:
    """Who sends and who receives a frame with ``identifier``; None when no node of the exchange listens on it."""
    status, sender, receiver, channel = _core.route_of(small(nodes, 255), small(identifier, 0xFFFFFFFF))
    if status == SchemeStatus.not_exchange_identifier:
        return None
    if status != 0:
        raise StatusError(SchemeStatus(status), f"{nodes} nodes")
    return Route(sender, receiver, channel)


# ---- the VR message codec -------------------------------------------------------------------------------


@dataclass(frozen=True)
class DecodedVr:
    """A frame read as a VR message: ``status`` is DecodeStatus.ok, or why it is not one (then the other
    fields are 0); ``route`` is who sent it to whom (None for an identifier outside the exchange). The value
    is sign, integer part and fraction in ten-thousandths as they travel, and ``value`` as a float."""

    status: DecodeStatus
    vr: int = 0
    value: float = 0.0
    negative: bool = False
    integer_part: int = 0
    fraction: int = 0
    route: Optional[Route] = None

    def __bool__(self) -> bool:
        return self.status == DecodeStatus.ok


def encode_vr(vr: int, value: float, byte_order: ByteOrder = ByteOrder.big_endian) -> bytes:
    """The 8 data bytes of VR(vr) = value, rounded to 4 decimals (ties away from zero). StatusError
    (EncodeStatus) for a VR above 255, NaN or a magnitude of 2**32 or more."""
    status, data = _core.encode_vr(small(vr, what="vr"), number(value), int(ByteOrder(byte_order)))
    if data is None:
        raise StatusError(EncodeStatus(status), f"VR({vr}) = {value!r}")
    return bytes(data)


def decode_vr(data: Any, byte_order: ByteOrder = ByteOrder.big_endian) -> DecodedVr:
    """Reads 8 data bytes (any bytes-like object; its length is the frame's DLC) as a VR message."""
    status, vr, negative, integer_part, fraction, value = _core.decode_vr_message(data, int(ByteOrder(byte_order)))
    return DecodedVr(DecodeStatus(status), vr, value, negative, integer_part, fraction)


def to_message(sender: int, receiver: int, vr: int, value: float, *, nodes: int = DEFAULT_NODE_COUNT,
               byte_order: ByteOrder = ByteOrder.big_endian) -> "python_can.Message":
    """A python-can message carrying VR(vr) = value from ``sender`` to ``receiver``."""
    import can as python_can

    return python_can.Message(arbitration_id=exchange_identifier(sender, receiver, nodes), is_extended_id=False,
                              data=encode_vr(vr, value, byte_order))


def _identifier_fits(identifier: int, extended: bool) -> bool:
    return 0 <= identifier <= (0x1FFFFFFF if extended else 0x7FF)


def _frame_parts(message: "python_can.Message") -> Tuple[int, bool, bool, int, bytes]:
    """(identifier, extended, remote, dlc, data) of a message as the binding takes them: the identifier in
    0..2**32 - 1 (anything else does not fit its format either), the DLC in 0..15, at most 8 data bytes. A
    DLC above the number of data bytes is not trusted (the binding reads the data the message has)."""
    identifier = int(message.arbitration_id)
    if not 0 <= identifier <= 0xFFFFFFFF:
        identifier = 0xFFFFFFFF
    data = bytes(message.data)
    if message.is_fd and len(data) > 8:  # no CAN FD frame is a VR message
        return identifier, bool(message.is_extended_id), bool(message.is_remote_frame), 15, data[:8]
    dlc = min(max(int(message.dlc), 0), 15)
    return identifier, bool(message.is_extended_id), bool(message.is_remote_frame), dlc, data[:8]


def from_message(message: "python_can.Message", *, nodes: int = DEFAULT_NODE_COUNT,
                 byte_order: ByteOrder = ByteOrder.big_endian) -> DecodedVr:
    """Reads a python-can message as a VR message of the exchange: a remote frame, a DLC other than 8 (or
    more than the data bytes the message holds) is ``bad_dlc``; an identifier that does not fit its format
    (standard above 0x7FF) is ``bad_identifier``; an extended identifier has no route; the identifier gives
    the route."""
    identifier, extended, remote, dlc, data = _frame_parts(message)
    if not _identifier_fits(int(message.arbitration_id), extended):
        return DecodedVr(DecodeStatus.bad_identifier)
    status, vr, negative, integer_part, fraction, value = _core.decode_vr_frame(
        identifier, extended, remote, dlc, data, int(ByteOrder(byte_order)))
    route = None if extended else route_of(identifier, nodes)
    return DecodedVr(DecodeStatus(status), vr, value, negative, integer_part, fraction, route)


# ---- the node -------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ReceivedVr:
    """A VR that another node wrote into this node's VR table."""

    sender: int
    vr: int
    value: float
    receive_channel: int


@dataclass(frozen=True)
class ReceivedFrame:
    """What a node made of one frame: ``status`` (ReceiveStatus.ok when VR(vr) now holds ``value``), and
    for frames on its identifiers who sent it on which receive channel."""

    status: ReceiveStatus
    sender: int = 0
    receive_channel: int = 0
    vr: int = 0
    value: float = 0.0


class VrExchangeNode:
    """One controller of the VR exchange (can::vr_exchange_node) on a python-can bus.

    ``send(to, vr, value)`` puts VR(vr) = value for node ``to`` on the bus. Received frames come from
    :meth:`poll` (reads the bus), :meth:`receive` (one message you read yourself, e.g. from a log file) or a
    background thread (:meth:`start`); each VR written calls ``on_vr`` and is queued for iteration
    (``for received in node.received(timeout)``). ``vr`` is the node's VR table (a size or a
    :class:`trionet.ring.VrTable`, shared with a ring node if you like); ``write_policy`` may refuse writes.
    The bus is yours: closing the node stops its thread but leaves the bus open.
    """

    def __init__(self, bus: "python_can.BusABC", node: int, nodes: int = DEFAULT_NODE_COUNT, *,
                 byte_order: ByteOrder = ByteOrder.big_endian, vr: Union[int, VrTable] = 256,
                 write_policy: Optional[Callable[[int, float], bool]] = None,
                 on_vr: Optional[Callable[[ReceivedVr], None]] = None, send_timeout: Optional[float] = None,
                 queue_limit: int = 1 << 20) -> None:
        import can as python_can

        self._can = python_can
        self.bus = bus
        self.node = node
        self.nodes = nodes
        self.byte_order = ByteOrder(byte_order)
        self._vr = vr if isinstance(vr, VrTable) else VrTable(vr)
        if write_policy is not None:
            self._vr.policy = write_policy
        self.on_vr = on_vr
        self.send_timeout = send_timeout
        self._queue: Deque[ReceivedVr] = collections.deque(maxlen=queue_limit)
        # Re-entrant: the node runs the write policy while it holds the lock, and a policy may call the node
        # (send, counters, receive) from that thread; other threads wait as before.
        self._lock = threading.RLock()
        self._arrived = threading.Condition(self._lock)
        self._notifier: Optional[Any] = None
        self._dropped_from_queue = 0
        try:
            self._node = _core.VrExchangeNode(small(nodes, 255), small(node, 255), self._transmit, self._vr,
                                              int(self.byte_order))
        except ValueError as error:
            raise StatusError(SchemeStatus[str(error)], f"node {node} of {nodes}") from None

    @property
    def vr(self) -> VrTable:
        """The node's VR table, the one received frames write (read-only: the node keeps the table it was made
        with)."""
        return self._vr

    def _transmit(self, identifier: int, data: bytes) -> None:
        message = self._can.Message(arbitration_id=identifier, is_extended_id=False, data=data)
        self.bus.send(message, timeout=self.send_timeout)

    # ---- sending ----

    def send(self, to: int, vr: int, value: float) -> None:
        """Sends VR(vr) = value (rounded to 4 decimals) to node ``to``. StatusError (SendStatus) for a bad
        node, VR or value; the bus's own exception (can.CanError) if it fails to send (counted)."""
        with self._lock:
            status = self._node.send_to_node(small(to, 255, "to"), small(vr, what="vr"), number(value))
        if status != SendStatus.ok:
            raise StatusError(SendStatus(status), f"VR({vr}) = {value!r} to node {to} of {self.nodes}")

    # ---- receiving ----

    def receive(self, message: "python_can.Message") -> ReceivedFrame:
        """Feeds one received message to the node: a frame on one of its identifiers writes VR(); anything
        else is classified and counted (an identifier that does not fit its format is foreign, a DLC above
        the data bytes the message holds is bad_dlc). Error frames are ignored (not counted)."""
        if message.is_error_frame:
            return ReceivedFrame(ReceiveStatus.foreign)
        identifier, extended, remote, dlc, data = _frame_parts(message)
        with self._lock:
            status, sender, channel, vr, value = self._node.receive(identifier, extended, remote, dlc, data)
            result = ReceivedFrame(ReceiveStatus(status), sender, channel, vr, value)
            if result.status == ReceiveStatus.ok:
                received = ReceivedVr(sender, vr, value, channel)
                if len(self._queue) == self._queue.maxlen:
                    self._dropped_from_queue += 1
                self._queue.append(received)
                self._arrived.notify_all()
            else:
                received = None
        if received is not None and self.on_vr is not None:
            self.on_vr(received)
        return result

    def poll(self, timeout: float = 0.0) -> int:
        """Reads the bus until no message arrives within ``timeout`` seconds; feeds each to the node.
        Returns the number of messages read."""
        if self._notifier is not None:
            raise RuntimeError("the node's thread reads the bus (stop() it to poll)")
        count = 0
        message = self.bus.recv(timeout)
        while message is not None:
            self.receive(message)
            count += 1
            message = self.bus.recv(timeout)
        return count

    def received(self, timeout: Optional[float] = 0.0) -> Iterator[ReceivedVr]:
        """The VRs received, in order, as they arrive: from the queue, reading the bus (or waiting for the
        node's thread) when it is empty; ends when nothing arrives within ``timeout`` seconds (None: never)."""
        while True:
            with self._lock:
                if self._queue:
                    item = self._queue.popleft()
                else:
                    item = None
            if item is not None:
                yield item
                continue
            if self._notifier is not None:
                with self._lock:
                    if not self._queue and not self._arrived.wait(timeout):
                        return
                continue
            message = self.bus.recv(timeout)
            if message is None:
                return
            self.receive(message)

    def __iter__(self) -> Iterator[ReceivedVr]:
        """Every VR received, waiting for each as long as it takes."""
        return self.received(None)

    @property
    def pending(self) -> int:
        """VRs received and not yet taken by iteration."""
        with self._lock:
            return len(self._queue)

    # ---- a thread that reads the bus ----

    def start(self) -> None:
        """Reads the bus in a thread of its own (python-can's Notifier): VRs arrive without polling."""
        if self._notifier is None:
            node = self

            class _Listener(self._can.Listener):  # type: ignore[misc, name-defined]
                def on_message_received(self, msg: "python_can.Message") -> None:
                    node.receive(msg)

            self._notifier = self._can.Notifier(self.bus, [_Listener()], timeout=0.05)

    def stop(self) -> None:
        """Stops the node's thread (the bus stays open)."""
        if self._notifier is not None:
            self._notifier.stop()
            self._notifier = None

    def close(self) -> None:
        """Stops the node's thread; the bus is left open (it is the caller's)."""
        self.stop()

    def __enter__(self) -> "VrExchangeNode":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    # ---- counters ----

    def counters(self) -> Dict[str, int]:
        """The node's counts since it was made or cleared (can::node_counters): sent, send_busy,
        send_failed, written, refused, out_of_range, value_out_of_range, foreign, bad_dlc, bad_sign,
        bad_fraction."""
        with self._lock:
            return dict(self._node.counters())

    def clear_counters(self) -> None:
        """Starts every count again from 0."""
        with self._lock:
            self._node.clear_counters()

    def wait_for(self, condition: Callable[[], bool], timeout: float) -> bool:
        """Polls (or lets the thread run) until ``condition()`` is true or ``timeout`` seconds pass."""
        end = time.monotonic() + timeout
        while not condition():
            left = end - time.monotonic()
            if left <= 0:
                return False
            if self._notifier is None:
                self.poll(min(left, 0.01))
            else:
                time.sleep(min(left, 0.005))
        return True


__all__ = [
    "ByteOrder", "DEFAULT_NODE_COUNT", "DecodeStatus", "DecodedVr", "EncodeStatus", "MAX_MESSAGE_VR",
    "MAX_NODE_COUNT", "MIN_NODE_COUNT", "ReceiveStatus", "ReceivedFrame", "ReceivedVr", "Route", "SchemeStatus",
    "SendStatus", "VrExchangeNode", "base_identifier", "decode_vr", "destination_of", "encode_vr",
    "exchange_identifier", "from_message", "receive_identifier", "route_of", "to_message", "transmit_channel_to",
    "transmit_identifier",
]
