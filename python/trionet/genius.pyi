import enum
from dataclasses import dataclass
from typing import Any, Dict, Iterable, List, NamedTuple, Optional, Sequence, Tuple, Union

from ._profile import Profile

class CharacterStatus(enum.IntEnum):
    ok = 0
    start_bit_not_0 = 1
    stop_bit_not_1 = 2
    not_11_bits = 3

class ControlKind(enum.IntEnum):
    start = 0
    stop = 1
    start_of_block = 2
    end_of_block = 3
    unknown = 4

class EncodeStatus(enum.IntEnum):
    ok = 0
    buffer_too_small = 1
    sender_out_of_range = 2
    destination_out_of_range = 3
    empty_transmission = 4
    empty_block = 5

class ParseStatus(enum.IntEnum):
    in_progress = 0
    ok = 1
    skipped = 2
    data_outside_transmission = 3
    control_outside_transmission = 4
    start_inside_transmission = 5
    unknown_control = 6
    destination_out_of_range = 7
    missing_destination = 8
    block_not_closed = 9
    end_of_block_outside_block = 10
    empty_block = 11
    empty_transmission = 12
    block_crc_mismatch = 13
    stop_crc_mismatch = 14
    overflow = 15
    framing_error = 16

class Rate(enum.IntEnum):
    standard_153k6 = 0
    extended_153k6 = 1
    baud_76k8 = 2
    baud_38k4 = 3

class LayoutStatus(enum.IntEnum):
    ok = 0
    sba_out_of_range = 1
    duplicate_sba = 2
    sender_not_on_bus = 3
    bad_position = 4
    bad_timing = 5

class ScanTimeStatus(enum.IntEnum):
    ok = 0
    too_many_devices = 1

MAX_SBA: int

_Buffer = Any  # any object with the buffer protocol

class Character(NamedTuple):
    byte: int
    control: bool = ...

@dataclass(frozen=True)
class DecodedCharacter:
    status: CharacterStatus
    character: Character
    def __bool__(self) -> bool: ...

def encode_character(character: Union[Character, int], control: bool = ...) -> int: ...
def decode_character(word: int) -> DecodedCharacter: ...
def crc6(data: _Buffer, *, profile: Optional[Profile] = ...) -> int: ...

@dataclass(frozen=True)
class Segment:
    data: bytes
    block: bool = ...
    destination: int = ...

@dataclass(frozen=True)
class Transmission:
    sender: int
    segments: Tuple[Segment, ...] = ...
    destination: Optional[int] = ...
    @property
    def broadcast(self) -> bool: ...
    @property
    def data(self) -> bytes: ...

def encode_transmission(transmission: Transmission, *, profile: Optional[Profile] = ...) -> List[Character]: ...
def encode_words(transmission: Transmission, *, profile: Optional[Profile] = ...) -> List[int]: ...

class TransmissionParser:
    received: Optional[Transmission]
    def __init__(self, *, profile: Optional[Profile] = ...) -> None: ...
    def push(self, character: Union[Character, Tuple[int, bool]]) -> ParseStatus: ...
    def push_framing_error(self) -> ParseStatus: ...
    def feed(self, characters: Iterable[Union[Character, Tuple[int, bool]]]) -> List[Transmission]: ...
    def counts(self) -> Dict[str, int]: ...
    @property
    def errors(self) -> int: ...
    @property
    def in_transmission(self) -> bool: ...
    def reset(self) -> None: ...

def decode_transmissions(characters: Iterable[Union[Character, Tuple[int, bool]]], *,
                         profile: Optional[Profile] = ...) -> List[Transmission]: ...
def rate_from_name(name: str) -> Rate: ...
def rate_properties(rate: Rate) -> Dict[str, Any]: ...

@dataclass(frozen=True)
class BusTiming:
    rate: Rate
    bit_time_us: float
    skip_us: float
    propagation_us_per_2000ft: float = ...
    detection_us: float = ...
    @classmethod
    def default(cls, rate: Union[Rate, str]) -> BusTiming: ...

@dataclass(frozen=True)
class Device:
    sba: int
    position_ft: float = ...
    data_bytes: int = ...

@dataclass(frozen=True)
class Turn:
    sba: int
    position_ft: float
    start_us: float

@dataclass(frozen=True)
class TurnMargin:
    first: int
    second: int
    margin_us: float
    too_small: bool

@dataclass(frozen=True)
class TurnAnalysis:
    after: int
    turns: Tuple[Turn, ...]
    margins: Tuple[TurnMargin, ...]
    too_small_count: int
    bus_length_ft: float
    longer_than_rate_allows: bool
    more_devices_than_rate_allows: bool

def analyse_turns(devices: Sequence[Union[Device, Tuple[int, float]]], timing: Union[BusTiming, Rate, str],
                  after: int) -> TurnAnalysis: ...

@dataclass(frozen=True)
class ScanTransmission:
    sba: int
    start_us: float
    end_us: float
    collided: bool

@dataclass(frozen=True)
class BusScan:
    transmissions: Tuple[ScanTransmission, ...]
    collisions: int
    complete: bool

def simulate_scan(devices: Sequence[Union[Device, Tuple[int, float]]], timing: Union[BusTiming, Rate, str],
                  after: int) -> BusScan: ...
def device_scan_time_ns(rate: Union[Rate, str], io_bytes: int) -> int: ...

@dataclass(frozen=True)
class ScanTime:
    total_ns: int
    io_bytes: int
    devices: int
    @property
    def milliseconds(self) -> float: ...

def bus_scan_time(rate: Union[Rate, str], io_bytes: Iterable[int]) -> ScanTime: ...
