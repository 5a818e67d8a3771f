"""The GE Genius bus (docs/protocol.md section 3): characters and their 11-bit words, the CRC-6,
transmissions (encoder and streaming parser), bus-access timing (skip time, turns, margins, a simulated bus
scan) and GE's published scan time.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Iterable, List, NamedTuple, Optional, Sequence, Tuple, Union

from . import _trionet
from ._errors import StatusError, data_bytes, int_enum, number, small
from ._profile import Profile, _data_of

_core = _trionet.genius
_e = _core.enums

CharacterStatus = int_enum("CharacterStatus", _e["CharacterStatus"], __name__,
                           "What is wrong with an 11-bit word (genius::character_status).")
ControlKind = int_enum("ControlKind", _e["ControlKind"], __name__,
                       "The four control characters, and unknown (genius::control_kind).")
EncodeStatus = int_enum("EncodeStatus", _e["EncodeStatus"], __name__,
                        "Why a transmission could not be encoded (genius::encode_status).")
ParseStatus = int_enum("ParseStatus", _e["ParseStatus"], __name__,
                       "What one character did in the transmission parser (genius::parse_status).")
Rate = int_enum("Rate", _e["Rate"], __name__, "The bus rates (genius::rate).")
LayoutStatus = int_enum("LayoutStatus", _e["LayoutStatus"], __name__,
                        "Why a bus layout cannot be analysed (genius::layout_status).")
ScanTimeStatus = int_enum("ScanTimeStatus", _e["ScanTimeStatus"], __name__,
                          "Why a scan time was not computed (genius::scan_time_status).")

MAX_SBA: int = _core.MAX_SBA


class Character(NamedTuple):
    """One Genius character: a data byte and the control flag."""

    byte: int
    control: bool = False


@dataclass(frozen=True)
class DecodedCharacter:
    """An 11-bit word read as a character: ``status`` is CharacterStatus.ok or the framing error."""

    status: CharacterStatus
    character: Character

    def __bool__(self) -> bool:
        return self.status == CharacterStatus.ok


def encode_character(character: Union[Character, int], control: bool = False) -> int:
    """The 11-bit word of a character (start bit 0, control bit, 8 data bits, stop bit 1)."""
    byte, control = (character.byte, character.control) if isinstance(character, Character) else (character, control)
    _byte_int(byte, "a character's byte")
    if not 0 <= byte <= 255:
        raise ValueError(f"a character's byte is 0..255, got {byte}")
    return int(_core.encode_character(byte, bool(control)))


def _byte_int(value: int, what: str) -> None:
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{what} is an int, not {type(value).__name__}")


def decode_character(word: int) -> DecodedCharacter:
    """Reads an 11-bit word; a framing error is a status, not an exception."""
    if word < 0:
        raise ValueError(f"a word is 0..0x7ff, got {word}")
    status, byte, control = _core.decode_character(small(word))
    return DecodedCharacter(CharacterStatus(status), Character(byte, control))


def crc6(data: Any, *, profile: Optional[Profile] = None) -> int:
    """The CRC-6 of ``data`` (CRC-6/G-704, or the profile's)."""
    return int(_core.crc6(data, _data_of(profile)))


@dataclass(frozen=True)
class Segment:
    """Plain data, or a block (``block`` True) to SBA ``destination`` with its own CRC."""

    data: bytes
    block: bool = False
    destination: int = 0


@dataclass(frozen=True)
class Transmission:
    """A transmission as the application sees it: ``destination`` None for a broadcast."""

    sender: int
    segments: Tuple[Segment, ...] = ()
    destination: Optional[int] = None

    @property
    def broadcast(self) -> bool:
        return self.destination is None

    @property
    def data(self) -> bytes:
        """Every data byte of the segments, in order."""
        return b"".join(s.data for s in self.segments)


def encode_transmission(transmission: Transmission, *, profile: Optional[Profile] = None) -> List[Character]:
    """The characters of a transmission (Start, destination, data and blocks, Stop with the CRC-6), with the
    profile's CRC and control layout. StatusError (EncodeStatus) for an SBA above 31, an empty block or no
    data at all; StatusError (ParseStatus, as ``trionet genius encode``) for a transmission that
    :class:`TransmissionParser` would not accept (more than 256 data bytes or 16 segments: ``overflow``)."""
    t = transmission
    for value, what in [(t.sender, "sender")] + ([(t.destination, "destination")] if t.destination is not None else []):
        _byte_int(value, f"the {what} SBA")
        if not 0 <= value <= 255:
            raise StatusError(EncodeStatus.sender_out_of_range if what == "sender" else EncodeStatus.destination_out_of_range,
                              f"{what} SBA {value}")
    for segment in t.segments:
        _byte_int(segment.destination, "a block's destination SBA")
    segments = [(s.block, s.destination if 0 <= s.destination <= 255 else 255,
                 bytes(data_bytes(s.data, "a segment's data"))) for s in t.segments]
    status, characters = _core.encode_transmission(t.sender, t.destination is None, t.destination or 0, segments,
                                                   _data_of(profile))
    if characters is None:
        raise StatusError(EncodeStatus(status), f"transmission from SBA {t.sender}")
    out = [Character(byte, control) for byte, control in characters]
    # What is returned must be what the decoder accepts (as the tool checks): parse it with the same parser.
    parser = TransmissionParser(profile=profile)
    parsed = ParseStatus.in_progress
    for c in out:
        parsed = parser.push(c)
        if parsed != ParseStatus.in_progress:
            break
    if parsed != ParseStatus.ok:
        raise StatusError(ParseStatus(parsed), f"cannot encode: the decoder would report {ParseStatus(parsed).name} "
                                               f"(at most 256 data bytes in 16 segments)")
    return out


def encode_words(transmission: Transmission, *, profile: Optional[Profile] = None) -> List[int]:
    """:func:`encode_transmission` as 11-bit words."""
    return [encode_character(c) for c in encode_transmission(transmission, profile=profile)]


def _transmission(t: Any) -> Transmission:
    sender, broadcast, destination, segments = t
    return Transmission(sender, tuple(Segment(bytes(data), block, dest) for block, dest, data in segments),
                        None if broadcast else destination)


class TransmissionParser:
    """A streaming transmission parser (genius::transmission_parser, 256 data bytes and 16 segments): push
    characters one at a time; a Stop with a matching CRC completes a :class:`Transmission`. Wire errors are
    statuses, counted by kind, and the parser finds the next Start by itself."""

    def __init__(self, *, profile: Optional[Profile] = None) -> None:
        self._parser = _core.TransmissionParser(_data_of(profile))
        self.received: Optional[Transmission] = None

    def push(self, character: Union[Character, Tuple[int, bool]]) -> ParseStatus:
        """Feeds one character; ParseStatus.ok when it completed a transmission (then in ``received``)."""
        byte, control = character
        _byte_int(byte, "a character's byte")
        if not 0 <= byte <= 255:
            raise ValueError(f"a character's byte is 0..255, got {byte}")
        status, t = self._parser.push(byte, bool(control))
        if t is not None:
            self.received = _transmission(t)
        return ParseStatus(status)

    def push_framing_error(self) -> ParseStatus:
        """The character layer saw a framing error: the open transmission is lost."""
        return ParseStatus(self._parser.push_framing_error())

    def feed(self, characters: Iterable[Union[Character, Tuple[int, bool]]]) -> List[Transmission]:
        """Pushes every character; the transmissions completed, in order."""
        done = []
        for c in characters:
            if self.push(c) == ParseStatus.ok and self.received is not None:
                done.append(self.received)
        return done

    def counts(self) -> dict:
        """How many times each status was returned, by name."""
        return dict(self._parser.counts())

    @property
    def errors(self) -> int:
        """Wire errors so far."""
        return int(self._parser.errors)

    @property
    def in_transmission(self) -> bool:
        """True between a Start and the end of its transmission."""
        return bool(self._parser.in_transmission)

    def reset(self) -> None:
        """Forgets any open transmission."""
        self._parser.reset()


def decode_transmissions(characters: Iterable[Union[Character, Tuple[int, bool]]], *,
                         profile: Optional[Profile] = None) -> List[Transmission]:
    """Every well-formed transmission of a stream of characters."""
    return TransmissionParser(profile=profile).feed(characters)


# ---- bus access -----------------------------------------------------------------------------------------


def rate_from_name(name: str) -> Rate:
    """A rate by its CLI name: "153.6s", "153.6e", "76.8" or "38.4"."""
    for rate in Rate:
        if _core.rate_properties(int(rate))["name"] == name:
            return rate
    raise ValueError(f"no rate {name!r} (153.6s, 153.6e, 76.8 or 38.4)")


def rate_properties(rate: Rate) -> dict:
    """A row of docs/protocol.md 3.3's rate table: name, description, baud, skip_bits, max_length_ft,
    max_devices."""
    return dict(_core.rate_properties(int(Rate(rate))))


@dataclass(frozen=True)
class BusTiming:
    """The timing parameters of a bus: start from :meth:`default` and replace what differs."""

    rate: Rate
    bit_time_us: float
    skip_us: float
    propagation_us_per_2000ft: float = 3.0
    detection_us: float = 0.0

    @classmethod
    def default(cls, rate: Union[Rate, str]) -> "BusTiming":
        """The rate's defaults: skip time by GE's rule, 3 us per 2000 ft, detection at half a bit time."""
        r = rate_from_name(rate) if isinstance(rate, str) else Rate(rate)
        d = _core.default_timing(int(r))
        return cls(r, d["bit_time_us"], d["skip_us"], d["propagation_us_per_2000ft"], d["detection_us"])

    def _dict(self) -> dict:
        return {"rate": int(self.rate), "bit_time_us": self.bit_time_us, "skip_us": self.skip_us,
                "propagation_us_per_2000ft": self.propagation_us_per_2000ft, "detection_us": self.detection_us}


@dataclass(frozen=True)
class Device:
    """A device on the bus: its SBA, where it sits (feet) and, for a bus scan, the data characters it sends."""

    sba: int
    position_ft: float = 0.0
    data_bytes: int = 1


@dataclass(frozen=True)
class Turn:
    """When a device's turn starts after the Stop, at its own position."""

    sba: int
    position_ft: float
    start_us: float


@dataclass(frozen=True)
class TurnMargin:
    """Time from the arrival of ``first``'s start bit at ``second`` to ``second``'s own turn."""

    first: int
    second: int
    margin_us: float
    too_small: bool


@dataclass(frozen=True)
class TurnAnalysis:
    """Turns and margins after one Stop (genius::turn_analysis)."""

    after: int
    turns: Tuple[Turn, ...]
    margins: Tuple[TurnMargin, ...]
    too_small_count: int
    bus_length_ft: float
    longer_than_rate_allows: bool
    more_devices_than_rate_allows: bool


def _devices(devices: Sequence[Union[Device, Tuple[int, float]]]) -> List[Tuple[int, float, int]]:
    out = []
    for d in devices:
        d = d if isinstance(d, Device) else Device(*d)
        _byte_int(d.data_bytes, "data_bytes")
        if not 0 <= d.data_bytes <= 65535:
            raise ValueError(f"data_bytes is 0..65535, got {d.data_bytes}")
        out.append((small(d.sba, 255), number(d.position_ft), d.data_bytes))
    return out


def _timing(timing: Union[BusTiming, Rate, str]) -> BusTiming:
    return timing if isinstance(timing, BusTiming) else BusTiming.default(timing)


def analyse_turns(devices: Sequence[Union[Device, Tuple[int, float]]], timing: Union[BusTiming, Rate, str],
                  after: int) -> TurnAnalysis:
    """Every other device's turn after the Stop of SBA ``after`` (`trionet genius timing`), and the margin
    between consecutive turns. StatusError (LayoutStatus) for a layout that cannot be analysed."""
    a = _core.analyse_turns(_devices(devices), _timing(timing)._dict(), small(after, 255))
    if a["status"] != 0:
        raise StatusError(LayoutStatus(a["status"]), f"after SBA {after}")
    return TurnAnalysis(a["after"], tuple(Turn(*t) for t in a["turns"]), tuple(TurnMargin(*m) for m in a["margins"]),
                        a["too_small_count"], a["bus_length_ft"], a["longer_than_rate_allows"],
                        a["more_devices_than_rate_allows"])


@dataclass(frozen=True)
class ScanTransmission:
    """One transmission of a simulated bus scan, times at the transmitter."""

    sba: int
    start_us: float
    end_us: float
    collided: bool


@dataclass(frozen=True)
class BusScan:
    """A simulated bus scan (genius::bus_scan)."""

    transmissions: Tuple[ScanTransmission, ...]
    collisions: int
    complete: bool


def simulate_scan(devices: Sequence[Union[Device, Tuple[int, float]]], timing: Union[BusTiming, Rate, str],
                  after: int) -> BusScan:
    """One bus scan from the Stop of SBA ``after`` until it transmits again, collisions included."""
    s = _core.simulate_scan(_devices(devices), _timing(timing)._dict(), small(after, 255))
    if s["status"] != 0:
        raise StatusError(LayoutStatus(s["status"]), f"after SBA {after}")
    return BusScan(tuple(ScanTransmission(*t) for t in s["transmissions"]), s["collisions"], s["complete"])


# ---- scan time ------------------------------------------------------------------------------------------


def device_scan_time_ns(rate: Union[Rate, str], io_bytes: int) -> int:
    """One device's contribution to the bus scan in nanoseconds, by GE's formula (exact)."""
    r = rate_from_name(rate) if isinstance(rate, str) else Rate(rate)
    return int(_core.device_scan_time_ns(int(r), _io_bytes(io_bytes)))


def _io_bytes(n: int) -> int:
    if isinstance(n, bool) or not isinstance(n, int):
        raise TypeError(f"io_bytes are ints, not {type(n).__name__}")
    if not 0 <= n < 2**32:
        raise ValueError(f"io_bytes is 0..2**32 - 1, got {n}")
    return n


@dataclass(frozen=True)
class ScanTime:
    """A bus's scan time: the sum of its devices' contributions, in nanoseconds (exact)."""

    total_ns: int
    io_bytes: int
    devices: int

    @property
    def milliseconds(self) -> float:
        return self.total_ns / 1e6


def bus_scan_time(rate: Union[Rate, str], io_bytes: Iterable[int]) -> ScanTime:
    """The scan time of a bus whose devices have ``io_bytes[i]`` input + output bytes each (a list, or any
    iterable of ints). StatusError
    (ScanTimeStatus) for more devices than the rate allows."""
    r = rate_from_name(rate) if isinstance(rate, str) else Rate(rate)
    io_bytes = list(io_bytes)  # once: an iterator is read here, not used up by the checks
    for n in io_bytes:
        _io_bytes(n)
    status, total, io, count = _core.bus_scan_time(int(r), io_bytes)
    if status != 0:
        raise StatusError(ScanTimeStatus(status), f"{len(io_bytes)} devices at {rate_properties(r)['name']}")
    return ScanTime(total, io, count)


__all__ = [
    "BusScan", "BusTiming", "Character", "CharacterStatus", "ControlKind", "DecodedCharacter", "Device",
    "EncodeStatus", "LayoutStatus", "MAX_SBA", "ParseStatus", "Rate", "ScanTime", "ScanTimeStatus",
    "ScanTransmission", "Segment", "Transmission", "TransmissionParser", "Turn", "TurnAnalysis", "TurnMargin",
    "analyse_turns", "bus_scan_time", "crc6", "decode_character", "decode_transmissions", "device_scan_time_ns",
    "encode_character", "encode_transmission", "encode_words", "rate_from_name", "rate_properties",
    "simulate_scan",
]
