"""The Trio Motion Coordinator fibre-optic ring (docs/protocol.md section 1).

Encoders give a frame as bytes (``encode_print`` and its siblings take BASIC addresses 10..24, as
``trionet ring encode`` does); :class:`Decoder` turns a stream of bytes into :class:`Event` objects with the
fields of ``trionet ring decode --raw``; :class:`MotionCoordinator` and :class:`Keypad` are the library's nodes
(bytes in, bytes out); :class:`Simulator` runs them on a simulated ring and :class:`SerialLink` on a serial
port. Misuse raises :class:`trionet.StatusError`; bad wire data comes back as events and counters.
"""

from __future__ import annotations

import decimal
import re
import time
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

from . import _trionet
from ._errors import StatusError, data_bytes, int_enum, number, small
from ._profile import Profile, _data_of

_core = _trionet.ring
_e = _core.enums

MessageType = int_enum("MessageType", _e["MessageType"], __name__, "The four ring messages (ring::message_type).")
EncodeStatus = int_enum("EncodeStatus", _e["EncodeStatus"], __name__,
                        "Why an encoder refused a message (ring::encode_status).")
DecodeStatus = int_enum("DecodeStatus", _e["DecodeStatus"], __name__,
                        "What a byte completed in the decoder (ring::decode_status).")
FrameError = int_enum("FrameError", _e["FrameError"], __name__, "Why a frame was discarded (ring::frame_error).")
SendStatus = int_enum("SendStatus", _e["SendStatus"], __name__,
                      "What became of a PRINT# or SEND (ring::send_status).")
GetStatus = int_enum("GetStatus", _e["GetStatus"], __name__, "What became of a GET# (ring::get_status).")
KeyStatus = int_enum("KeyStatus", _e["KeyStatus"], __name__,
                     "What became of a key press or release (ring::key_status).")
Key = int_enum("Key", _e["Key"], __name__, "The 18 keys of a membrane keypad (ring::key).")
VrWriteStatus = int_enum("VrWriteStatus", _e["VrWriteStatus"], __name__,
                         "What became of a write to VR() (trionet::vr_write_status).")
Q32Status = int_enum("Q32Status", _e["Q32Status"], __name__,
                     "Why a number has no Q32.32 value (trionet::q32_status).")

_core.set_event_enums(DecodeStatus, FrameError)

MIN_HOPS: int = _core.MIN_HOPS
MAX_HOPS: int = _core.MAX_HOPS
MAX_VR: int = _core.MAX_VR
MAX_CHARACTERS: int = _core.MAX_CHARACTERS
FIRST_BASIC_ADDRESS: int = _core.FIRST_BASIC_ADDRESS
LAST_BASIC_ADDRESS: int = _core.LAST_BASIC_ADDRESS

#: One event of a ring byte stream (made by :class:`Decoder`).
Event = _core.Event

Text = Union[str, bytes, bytearray, memoryview]


def _text_bytes(text: Text) -> Any:
    """Characters as bytes: a str must be ASCII (the ring carries 7-bit characters), bytes-like objects pass as
    they are; TypeError for anything else (an int or a list is not text)."""
    if isinstance(text, str):
        try:
            return text.encode("ascii")
        except UnicodeEncodeError as error:
            raise StatusError(EncodeStatus.character_out_of_range,
                              f"{text[error.start]!r} at {error.start} is not a 7-bit character") from None
    return data_bytes(text, "text")


# ---- addresses and Q32.32 -------------------------------------------------------------------------------


def _integer(value: int, what: str) -> None:
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{what} is an int, not {type(value).__name__}")


def _count(value: int, what: str, limit: int) -> int:
    """An int in 0..limit: TypeError naming ``what`` for anything but an int, ValueError outside the range."""
    _integer(value, what)
    if not 0 <= value <= limit:
        raise ValueError(f"{what} is 0..{limit}, got {value}")
    return value


def hops_from_basic_address(address: int) -> int:
    """Hops (1..15) of a BASIC address (10..24): ``address - 9``. ValueError for any other address, TypeError
    for anything but an int."""
    _integer(address, "a BASIC address")
    if not FIRST_BASIC_ADDRESS <= address <= LAST_BASIC_ADDRESS:
        raise ValueError(f"a BASIC address is {FIRST_BASIC_ADDRESS}..{LAST_BASIC_ADDRESS}, got {address}")
    return address - (FIRST_BASIC_ADDRESS - 1)


def basic_address_from_hops(hops: int) -> int:
    """The BASIC address (10..24) of a hop count (1..15). ValueError for any other count, TypeError for anything
    but an int."""
    _integer(hops, "a hop count")
    if not MIN_HOPS <= hops <= MAX_HOPS:
        raise ValueError(f"hops are {MIN_HOPS}..{MAX_HOPS}, got {hops}")
    return hops + FIRST_BASIC_ADDRESS - 1


def q32_from_float(value: float) -> int:
    """``value`` as Q32.32 (value * 2**32 rounded to the nearest, ties away from zero), as SEND rounds it.
    StatusError (Q32Status) for NaN and values outside [-2**31, 2**31)."""
    status, raw = _core.q32_from_double(number(value))
    if status != 0:
        raise StatusError(Q32Status(status), f"{value!r} has no Q32.32 value")
    return int(raw)


# The tool's decimal syntax (host/q32_text.hpp parse_q32): a sign, digits with an optional point, an exponent.
_DECIMAL_TEXT = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")


def q32_from_decimal(value: Union[str, decimal.Decimal]) -> int:
    """The decimal number ``value`` as Q32.32 exactly as ``trionet ring encode var --value`` reads it: the number
    the text (or decimal.Decimal) writes, not the float nearest to it, times 2**32 rounded once to the nearest,
    ties away from zero. A float such as 895654.974 may be an exact tie at 2**-32 that the decimal is not, so
    :func:`q32_from_float` can end one bit apart. StatusError (Q32Status) for NaN, infinities and values
    outside [-2**31, 2**31); ValueError for text that is not a decimal number (the tool's syntax: "99",
    "-2.345", "+1e3", ".5", at most 1000 characters)."""
    if isinstance(value, str):
        if len(value) > 1000 or not _DECIMAL_TEXT.fullmatch(value):
            raise ValueError(f"not a decimal number: {value[:40]!r}")
        number_ = decimal.Decimal(value)
    elif isinstance(value, decimal.Decimal):
        number_ = value
    else:
        raise TypeError(f"expected a str or a decimal.Decimal, not {type(value).__name__}")
    if number_.is_nan():
        raise StatusError(Q32Status.not_a_number, f"{value!r} has no Q32.32 value")
    if number_.is_infinite() or (not number_.is_zero() and number_.adjusted() > 9):  # 10**10 > 2**31
        raise StatusError(Q32Status.out_of_range, f"{value!r} has no Q32.32 value")
    if number_.is_zero() or number_.adjusted() < -10:  # below 10**-10 < 2**-33: rounds to 0
        return 0
    sign, digits, exponent = number_.as_tuple()
    assert isinstance(exponent, int)
    n = int("".join(map(str, digits)))
    if exponent >= 0:
        magnitude = n * 10**exponent << 32
    else:
        scale = 10**-exponent
        magnitude = ((n << 33) + scale) // (2 * scale)  # floor(n / scale * 2**32 + 1/2)
    raw = -magnitude if sign else magnitude
    if not -(2**63) <= raw < 2**63:
        raise StatusError(Q32Status.out_of_range, f"{value!r} has no Q32.32 value")
    return raw


def _q32(value: Union[float, decimal.Decimal]) -> int:
    return q32_from_decimal(value) if isinstance(value, decimal.Decimal) else q32_from_float(value)


def q32_to_float(raw: int) -> float:
    """A Q32.32 value (raw / 2**32) as a float. TypeError for anything but an int, ValueError outside the 64
    bits of a Q32.32 (-2**63 .. 2**63 - 1)."""
    _integer(raw, "a Q32.32 value")
    if not -(2**63) <= raw < 2**63:
        raise ValueError(f"a Q32.32 value is -2**63 .. 2**63 - 1, got {raw}")
    return float(_core.q32_to_double(raw))


# ---- messages and encoders ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Message:
    """A ring message (ring::message). Build one with the class methods; :func:`encode` makes its frame."""

    type: MessageType
    hops: int
    text: bytes = b""
    vr: int = 0
    value: Union[float, decimal.Decimal] = 0.0
    offset: int = 0
    mode: int = 0

    @classmethod
    def characters(cls, hops: int, text: Text) -> "Message":
        """PRINT#: a character transfer of ``text`` (7-bit characters, at least one)."""
        return cls(MessageType.character, hops, text=bytes(_text_bytes(text)))

    @classmethod
    def variable(cls, hops: int, vr: int, value: Union[float, decimal.Decimal]) -> "Message":
        """SEND(n,1,vr,value): a direct variable transfer, VR(vr) = value (a decimal.Decimal is rounded exactly,
        as the tool reads its --value: :func:`q32_from_decimal`)."""
        return cls(MessageType.variable, hops, vr=vr, value=value)

    @classmethod
    def keypad_offset(cls, hops: int, offset: int) -> "Message":
        """SEND(n,2,offset): where a keypad sends its keys (offset in hops, 1..15)."""
        return cls(MessageType.keypad_offset, hops, offset=offset)

    @classmethod
    def keypad_mode(cls, hops: int, mode: int) -> "Message":
        """Keypad mode: 0 (key ON only) or 127 (key ON and key OFF)."""
        return cls(MessageType.keypad_mode, hops, mode=mode)


def _frame(result: Tuple[int, Optional[bytes]], detail: str) -> bytes:
    status, frame = result
    if frame is None:
        raise StatusError(EncodeStatus(status), detail)
    return frame


def encode(message: Message, *, profile: Optional[Profile] = None) -> bytes:
    """The whole frame of ``message`` (header to end of message), with the profile's CRC and variable layout
    (docs/protocol.md's without one). StatusError (EncodeStatus) for a field out of range. A character
    transfer longer than a decoder takes (256, or the profile's ring.max_characters) is encoded all the same,
    for tests of decoders; :func:`encode_print` refuses it as the tool does."""
    data = _data_of(profile)
    hops = message.hops
    if not isinstance(hops, int) or not MIN_HOPS <= hops <= MAX_HOPS:
        raise StatusError(EncodeStatus.hops_out_of_range, f"hops must be {MIN_HOPS}..{MAX_HOPS}, got {hops!r}")
    if message.type == MessageType.character:
        return _frame(_core.encode_characters(hops, _text_bytes(message.text), data), f"PRINT to {hops} hops")
    if message.type == MessageType.variable:
        if not 0 <= small(message.vr, what="vr") <= MAX_VR:
            raise StatusError(EncodeStatus.vr_out_of_range, f"vr must be 0..{MAX_VR}, got {message.vr}")
        raw = _q32(message.value)
        return _frame(_core.encode_variable(hops, message.vr, raw, data), f"VR({message.vr}) to {hops} hops")
    if message.type == MessageType.keypad_offset:
        if not 0 <= small(message.offset, what="offset") <= 255:
            raise StatusError(EncodeStatus.offset_out_of_range, f"offset must be 1..15, got {message.offset}")
        return _frame(_core.encode_keypad_offset(hops, message.offset), f"keypad offset {message.offset}")
    if message.type == MessageType.keypad_mode:
        if not 0 <= small(message.mode, what="mode") <= 255:
            raise StatusError(EncodeStatus.mode_out_of_range, f"mode must be 0 or 127, got {message.mode}")
        return _frame(_core.encode_keypad_mode(hops, message.mode), f"keypad mode {message.mode}")
    raise StatusError(EncodeStatus.unknown_type, f"{message.type!r}")


def _hops(to: int, what: str = "to") -> int:
    try:
        return hops_from_basic_address(to)
    except ValueError:
        raise StatusError(EncodeStatus.hops_out_of_range,
                          f"{what} must be a BASIC address {FIRST_BASIC_ADDRESS}..{LAST_BASIC_ADDRESS}, got {to!r}") from None


def encode_print(to: int, text: Text, *, profile: Optional[Profile] = None) -> bytes:
    """`trionet ring encode print --to N TEXT`: PRINT #to,text as one character transfer of 1..256 7-bit
    characters (the profile's ring.max_characters with a profile). ``to`` is a BASIC address 10..24. As the
    tool, a longer text is refused (StatusError, EncodeStatus.buffer_too_small: the frame does not fit a
    decoder's buffer); :func:`encode` of a :class:`Message` encodes it all the same."""
    message = Message.characters(_hops(to), text)
    data = _data_of(profile)
    limit = MAX_CHARACTERS if data is None else int(data.ring_max_characters)
    if len(message.text) > limit:
        raise StatusError(EncodeStatus.buffer_too_small,
                          f"TEXT has {len(message.text)} characters; a character transfer carries at most {limit}")
    return encode(message, profile=profile)


def encode_var(to: int, vr: int, value: Union[float, decimal.Decimal], *, profile: Optional[Profile] = None) -> bytes:
    """`trionet ring encode var --to N --vr V --value X`: SEND(to,1,vr,value). A float is rounded as a double
    (:func:`q32_from_float`); for the tool's frame of a decimal X, whatever it is, pass decimal.Decimal("X")
    (:func:`q32_from_decimal`): a float that is an exact tie at 2**-32 can end one bit apart."""
    return encode(Message.variable(_hops(to), vr, value), profile=profile)


def encode_offset(to: int, offset: int) -> bytes:
    """`trionet ring encode offset --to N --offset M`: SEND(to,2,offset); both BASIC addresses 10..24."""
    return encode(Message.keypad_offset(_hops(to), _hops(offset, "offset")))


def encode_mode(to: int, mode: int) -> bytes:
    """`trionet ring encode mode --to N --mode 0|127`: the keypad mode."""
    return encode(Message.keypad_mode(_hops(to), mode))


# ---- decoding -------------------------------------------------------------------------------------------


class Decoder(_core.Decoder):  # type: ignore[misc]
    """A streaming ring decoder (ring::decoder with the profile's CRC and variable layout).

    ``feed(data)`` takes any bytes-like object (bytes, bytearray, memoryview, mmap: read in place, not
    copied) and returns the events it completed, in order, each with the fields of
    ``trionet ring decode --raw``: the decoder keeps its state between calls, so a message may be split
    anywhere. ``finish()`` reports a message still open at the end of the input (an "unfinished" event);
    ``line_idle()`` tells the decoder that the line went idle (an open message is an ``idle_line`` frame
    error). Memory is bounded: the decoder holds one message (256 characters) and ``feed`` returns at most
    one event per byte fed.
    """

    # The C++ decoder is made by __new__, not __init__: an instance made with Decoder.__new__(Decoder) alone is
    # a working decoder, not an unconstructed C++ object (which pybind11 would let a method read: a crash).
    def __new__(cls, profile: Optional[Profile] = None, *args: Any, **kwargs: Any) -> "Decoder":
        data = _data_of(profile)
        if data is not None and data.ring_max_characters != MAX_CHARACTERS:
            raise ValueError(f"profile ring.max_characters is {data.ring_max_characters}: the decoder is built for "
                             f"{MAX_CHARACTERS}")
        self: Decoder = _core.Decoder.__new__(cls)
        _core.Decoder.__init__(self, data)
        return self

    def __init__(self, profile: Optional[Profile] = None) -> None:
        pass  # made by __new__


def decode(data: Any, *, profile: Optional[Profile] = None) -> List[Event]:
    """Every event of ``data`` as one whole stream, the unfinished message at its end included."""
    decoder = Decoder(profile)
    return list(decoder.feed(data)) + list(decoder.finish())


# ---- VR() -----------------------------------------------------------------------------------------------


class VrTable(_core.VrValues):  # type: ignore[misc]
    """VR(0) .. VR(size - 1) as floats, written by the network through an optional write policy.

    ``memoryview(table)`` views the values in place (format 'd', no copy); ``table[vr]`` reads and writes
    one. ``policy`` is None (every write to a VR in the table is applied) or a callable (vr, value) -> bool
    whose answer is taken as Python truth: a false one (False, 0, None, "") refuses the write; an exception in
    it, or in bool() of its answer, refuses the write and is raised again by the call that fed the node.
    """

    # The C++ table is made by __new__, not __init__: VrTable.__new__(VrTable) alone gives a table of 1024 VRs,
    # not an unconstructed C++ object (which pybind11 would let a method read: a crash).
    def __new__(cls, size: int = 1024, *args: Any, **kwargs: Any) -> "VrTable":
        if isinstance(size, bool) or not isinstance(size, int):
            raise TypeError(f"a VR table's size is an int, not {type(size).__name__}")
        if not 1 <= size <= 16384:
            raise ValueError(f"a VR table holds 1..16384 variables, got {size}")
        self: VrTable = _core.VrValues.__new__(cls)
        _core.VrValues.__init__(self, size)
        return self

    def __init__(self, size: int = 1024, policy: Optional[Callable[[int, float], bool]] = None) -> None:
        self.policy = policy

    def __getitem__(self, vr: int) -> float:
        return float(self.get(self._index(vr)))

    def __setitem__(self, vr: int, value: float) -> None:
        self.set(self._index(vr), float(value))

    def _index(self, vr: int) -> int:
        _integer(vr, "a VR number")
        if not 0 <= vr < len(self):
            raise IndexError(f"VR({vr}) is outside the table (0..{len(self) - 1})")
        return vr

    def write_from_network(self, vr: int, value: float) -> VrWriteStatus:
        """Writes VR(vr) as the network does, through the write policy (value rounded to Q32.32)."""
        _integer(vr, "a VR number")
        if not 0 <= vr <= 65535:  # a VR on the network is 16 bits; out_of_range past the table
            raise ValueError(f"a VR number from the network is 0..65535, got {vr}")
        return VrWriteStatus(self.write(vr, number(value)))

    def nonzero(self) -> Dict[int, float]:
        """Every VR that is not 0, as {vr: value}."""
        values = memoryview(self)
        return {vr: values[vr] for vr in range(len(values)) if values[vr] != 0}


# ---- nodes ----------------------------------------------------------------------------------------------


class RingNode:
    """What every ring node does: bytes received from the previous node in, bytes for the next node out
    (trionet::byte_port). Counters only grow; bad bytes are counted, never raised."""

    _node: Any

    def receive(self, data: Any) -> None:
        """Bytes received from the previous node (any bytes-like object), in order."""
        self._node.receive(data)

    def transmit(self, limit: int = 65536) -> bytes:
        """Up to ``limit`` bytes for the next node: forwarded messages and the node's own, as they are due."""
        return bytes(self._node.transmit(_count(limit, "limit", 2**63 - 1)))

    def line_idle(self) -> None:
        """The receive line has been idle (docs/protocol.md 1.10): an open message is lost and counted."""
        self._node.line_idle()

    @property
    def transmit_pending(self) -> bool:
        """True while the node has a byte to send."""
        return bool(self._node.transmit_pending)

    @property
    def in_message(self) -> bool:
        """True while a message is passing through or arriving."""
        return bool(self._node.in_message)

    @property
    def netstat(self) -> int:
        """NETSTAT: bit 0 a send refused, 1 a forward lost, 2 a CRC error, 3 a frame error, 4 no room."""
        return int(self._node.netstat)

    def clear_netstat(self) -> None:
        """Clears NETSTAT."""
        self._node.clear_netstat()

    def counters(self) -> Dict[str, int]:
        """The node's counters, with the C++ struct's field names."""
        return dict(self._node.counters())

    def forwarding_counters(self) -> Dict[str, int]:
        """The link's counters (ring::link_counters): forwarded, lost, cut, dropped, sent."""
        return dict(self._node.forwarding_counters())

    def clear_counters(self) -> None:
        """Starts every count of :meth:`counters` and :meth:`forwarding_counters` again from 0 (not NETSTAT)."""
        self._node.clear_counters()


def _to(to: int, what: str = "a BASIC address") -> int:
    """A BASIC address as an int; out of 10..24 it is passed on for the node to refuse (SendStatus)."""
    if not isinstance(to, int):
        raise TypeError(f"{what} is an int, not {type(to).__name__}")
    return to if -1 <= to <= 255 else -1


class MotionCoordinator(RingNode):
    """A Motion Coordinator on the ring (ring::motion_coordinator<>): PRINT#, SEND, KEY#, GET# and VR(),
    forwarding what is not for it. ``vr`` is its VR table (a size, or a :class:`VrTable` to share)."""

    def __init__(self, vr: Union[int, VrTable] = 1024, *,
                 write_policy: Optional[Callable[[int, float], bool]] = None) -> None:
        self._vr = vr if isinstance(vr, VrTable) else VrTable(vr)
        if write_policy is not None:
            self._vr.policy = write_policy
        self._node = _core.MotionCoordinator(self._vr)

    @property
    def vr(self) -> VrTable:
        """The node's VR table, the one the ring writes (read-only: the node keeps the table it was made with;
        write to it, or make a node with another table)."""
        return self._vr

    def print(self, to: int, text: Text) -> int:
        """PRINT #to,text without waiting: as many whole character messages as the transmit queue has room
        for; returns how many characters were queued (all of them, or fewer when the queue is full, which
        sets NETSTAT bit 0). StatusError (SendStatus) for a bad address or text."""
        status, queued = self._node.print(_to(to), _text_bytes(text))
        if status not in (SendStatus.ok, SendStatus.queue_full):
            raise StatusError(SendStatus(status), f"PRINT #{to}")
        return int(queued)

    def _sent(self, status: int, what: str) -> bool:
        if status == SendStatus.queue_full:
            return False
        if status != SendStatus.ok:
            raise StatusError(SendStatus(status), what)
        return True

    def send(self, to: int, vr: int, value: float) -> bool:
        """SEND(to,1,vr,value): a direct variable transfer. False when the transmit queue is full (NETSTAT
        bit 0); StatusError (SendStatus) for a bad address, VR or value."""
        if not isinstance(vr, int):
            raise TypeError(f"a VR is an int, not {type(vr).__name__}")
        if not 0 <= vr <= MAX_VR:
            raise StatusError(SendStatus.vr_out_of_range, f"vr must be 0..{MAX_VR}, got {vr}")
        return self._sent(self._node.send_variable(_to(to), vr, number(value)), f"SEND({to},1,{vr},{value!r})")

    def send_keypad_offset(self, to: int, offset: int) -> bool:
        """SEND(to,2,offset): tells the keypad at ``to`` where its keys go (BASIC address counted from it)."""
        return self._sent(self._node.send_keypad_offset(_to(to), _to(offset, "an offset")), f"SEND({to},2,{offset})")

    def send_keypad_mode(self, to: int, mode: int) -> bool:
        """Keypad mode 0 (key ON only) or 127 (key ON and key OFF) to the keypad at ``to``."""
        return self._sent(self._node.send_keypad_mode(_to(to), _to(mode, "a mode")), f"keypad mode {mode} to {to}")

    def key(self, channel: int = 4) -> bool:
        """KEY#3 or KEY#4: True when a character is waiting (nothing is taken)."""
        if channel not in (3, 4):
            raise StatusError(GetStatus.bad_channel, f"KEY# takes channel 3 or 4, got {channel}")
        return bool(self._node.key(_to(channel, "a channel")))

    def get(self, channel: int = 4) -> Optional[int]:
        """GET#4: the next character as it came; GET#3: translated through DEFKEY. None when none waits."""
        status, value = self._node.get(_to(channel, "a channel"))
        if status == GetStatus.nothing_yet:
            return None
        if status != GetStatus.ok:
            raise StatusError(GetStatus(status), f"GET# takes channel 3 or 4, got {channel}")
        return int(value)

    @property
    def characters_waiting(self) -> int:
        """Characters in the receive buffer."""
        return int(self._node.characters_waiting)

    @property
    def transmit_free(self) -> int:
        """Free bytes in the transmit queue."""
        return int(self._node.transmit_free)


def _key(key: Union[Key, int, str]) -> int:
    if isinstance(key, str):
        names = {"+": "up", "-": "down", "clr": "clear", "y": "yes", "enter": "yes", "n": "no", ".": "point"}
        name = key.lower()
        name = names.get(name, name)
        if len(name) == 1 and name.isdigit():
            name = "digit_" + name
        try:
            return int(Key[name])
        except KeyError:
            raise ValueError(f"no key called {key!r} (0-9, up, down, clear, yes, no, point, start, stop)") from None
    _integer(key, "a key (a Key, its number or its name)")
    return int(Key(key))


class Keypad(RingNode):
    """A membrane keypad on the ring (ring::keypad<>): in local mode until a keypad offset arrives, then its
    keys go to the node ``offset`` hops along; its 2 x 20 display shows the characters sent to it."""

    def __init__(self) -> None:
        self._node = _core.Keypad()

    def press(self, key: Union[Key, int, str]) -> KeyStatus:
        """A key went down ("7", "up", Key.yes, ...): its character is queued unless in local mode."""
        return KeyStatus(self._node.press(_key(key)))

    def release(self, key: Union[Key, int, str]) -> KeyStatus:
        """A key came up: its key OFF character is queued in keypad mode 127."""
        return KeyStatus(self._node.release(_key(key)))

    @property
    def network_mode(self) -> bool:
        """True once a keypad offset has arrived."""
        return bool(self._node.network_mode)

    @property
    def offset(self) -> int:
        """Hops to where key presses go (0 in local mode)."""
        return int(self._node.offset)

    @property
    def mode(self) -> int:
        """Keypad mode: 0 (key ON only) or 127 (key ON and key OFF)."""
        return int(self._node.mode)

    @property
    def display(self) -> Tuple[str, str]:
        """The display's two lines of 20 characters."""
        first, second = self._node.display
        return str(first), str(second)

    @property
    def cursor(self) -> int:
        """The cursor position, 0..39."""
        return int(self._node.cursor)

    @property
    def cursor_visible(self) -> bool:
        """False after character 14, True again after 15."""
        return bool(self._node.cursor_visible)


# ---- the simulated ring ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class LinkByte:
    """One byte on one link of a :class:`Simulator` (link i runs from node i to node i + 1)."""

    time: int
    link: int
    sent: int
    received: int
    delivered: bool


class Simulator:
    """A deterministic ring of 2..15 nodes (ring::simulator): each byte-time every node sends at most one
    byte to the next. Time is a count of byte-times, never a clock. ``idle_byte_times`` is how long a link
    carries nothing before its receiver's line counts as idle (0: never)."""

    def __init__(self, nodes: Optional[List[RingNode]] = None, *, idle_byte_times: int = 2) -> None:
        self._ring = _core.Simulator(_count(idle_byte_times, "idle_byte_times", 2**32 - 1))
        self.nodes: List[RingNode] = []
        for node in nodes or []:
            self.add(node)

    def add(self, node: RingNode) -> None:
        """Adds the next node round the ring (ValueError past 15 nodes)."""
        if not isinstance(node, RingNode):
            raise TypeError(f"a ring node is a MotionCoordinator or a Keypad, not {type(node).__name__}")
        if not self._ring.add(node._node):
            raise ValueError("a ring has at most 15 nodes")
        self.nodes.append(node)

    def run(self, byte_times: int, trace: Optional[Callable[[LinkByte], None]] = None) -> None:
        """Runs ``byte_times`` byte-times; ``trace`` sees every byte sent on every link."""
        if len(self.nodes) < 2:
            raise ValueError("a ring needs at least 2 nodes")
        _count(byte_times, "byte_times", 2**64 - 1)
        if trace is None:
            self._ring.run(byte_times, None)
        else:
            self._ring.run(byte_times, lambda t, link, sent, received, delivered:
                           trace(LinkByte(t, link, sent, received, delivered)))

    def run_until_quiet(self, limit: int = 1_000_000) -> int:
        """Runs until no node has anything to send (or ``limit`` byte-times); returns the byte-times run."""
        start = self.now
        while not self.quiet and self.now - start < limit:
            self.run(1)
        return self.now - start

    @property
    def now(self) -> int:
        """Byte-times run so far."""
        return int(self._ring.now)

    @property
    def quiet(self) -> bool:
        """True when no node has anything to send."""
        return bool(self._ring.quiet)

    @property
    def bytes_delivered(self) -> int:
        """Bytes delivered since the start."""
        return int(self._ring.bytes_delivered)

    def drop_next(self, link: int) -> None:
        """The next byte sent on ``link`` never arrives."""
        self._ring.drop_next(self._link(link))

    def flip_next(self, link: int, mask: int) -> None:
        """The next byte sent on ``link`` arrives with the bits of ``mask`` flipped."""
        _integer(mask, "mask")
        self._ring.flip_next(self._link(link), mask & 0xFF)

    def cut(self, link: int, cut: bool = True) -> None:
        """Cuts ``link`` (nothing arrives) or mends it."""
        if not isinstance(cut, bool):
            raise TypeError(f"cut is a bool, not {type(cut).__name__}")
        self._ring.cut(self._link(link), cut)

    def _link(self, link: int) -> int:
        """Link i carries node i's bytes to node i + 1 (the last to the first)."""
        _integer(link, "a link")
        if not 0 <= link < max(len(self.nodes), 1):
            raise ValueError(f"the ring's links are 0..{max(len(self.nodes), 1) - 1}, got {link}")
        return link


# ---- a node on a serial port ----------------------------------------------------------------------------


class SerialLink:
    """A ring node on a serial port: what arrives is fed to the node, what the node sends is written.

    ``port`` is a pyserial ``serial.Serial`` (any port pyserial opens: /dev/ttyUSB0 at 125000 baud, a pty,
    ``loop://``) or anything with ``read(n)``, ``write(data)`` and ``in_waiting``. The line counts as idle
    after ``idle_seconds`` without a byte while a message is open (docs/protocol.md 1.10).
    """

    def __init__(self, node: RingNode, port: Any, *, idle_seconds: float = 0.05) -> None:
        if not isinstance(node, RingNode):
            raise TypeError(f"node is a MotionCoordinator or a Keypad, not {type(node).__name__}")
        if port is None or not (hasattr(port, "read") and hasattr(port, "write")):
            raise TypeError(f"port is an open serial port (pyserial's Serial), not {type(port).__name__}")
        self.node = node
        self.port = port
        self.idle_seconds = idle_seconds
        self.bytes_in = 0
        self.bytes_out = 0
        self._last_byte = time.monotonic()

    def pump(self, timeout: float = 0.0) -> int:
        """Writes what the node has to send, then reads what has arrived (waiting up to ``timeout`` seconds
        for the first byte) and feeds it to the node; returns the number of bytes received."""
        self._write()
        waiting = self.port.in_waiting
        if waiting == 0 and timeout > 0:
            previous = self.port.timeout
            self.port.timeout = timeout
            try:
                data = self.port.read(1)
            finally:
                self.port.timeout = previous
            waiting = self.port.in_waiting
            data += self.port.read(waiting) if waiting else b""
        else:
            data = self.port.read(waiting) if waiting else b""
        now = time.monotonic()
        if data:
            self._last_byte = now
            self.bytes_in += len(data)
            self.node.receive(data)
            self._write()
        elif self.node.in_message and now - self._last_byte >= self.idle_seconds:
            self.node.line_idle()
        return len(data)

    def run(self, seconds: float, until: Optional[Callable[[], bool]] = None, step: float = 0.005) -> bool:
        """Pumps for up to ``seconds`` or until ``until()`` is true (then returns True)."""
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            if until is not None and until():
                return True
            self.pump(step)
        return until is not None and until()

    def _write(self) -> None:
        out = self.node.transmit()
        if out:
            self.port.write(out)
            self.bytes_out += len(out)


__all__ = [
    "DecodeStatus", "Decoder", "EncodeStatus", "Event", "FIRST_BASIC_ADDRESS", "FrameError", "GetStatus", "Key",
    "KeyStatus", "Keypad", "LAST_BASIC_ADDRESS", "LinkByte", "MAX_CHARACTERS", "MAX_HOPS", "MAX_VR", "MIN_HOPS",
    "Message", "MessageType", "MotionCoordinator", "Profile", "Q32Status", "RingNode", "SendStatus", "SerialLink",
    "Simulator", "VrTable", "VrWriteStatus", "basic_address_from_hops", "decode", "encode", "encode_mode",
    "encode_offset", "encode_print", "encode_var", "hops_from_basic_address", "q32_from_decimal", "q32_from_float",
    "q32_to_float",
]
