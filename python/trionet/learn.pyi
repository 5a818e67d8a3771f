import enum
from dataclasses import dataclass
from typing import Any, Iterable, List, Optional, Sequence, Tuple, Union

from ._profile import Profile
from .genius import Character

class CrcLearnStatus(enum.IntEnum):
    ok = 0
    ambiguous = 1
    too_many_candidates = 2
    no_candidate = 3
    no_frames = 4
    bad_frame = 5

class LayoutLearnStatus(enum.IntEnum):
    ok = 0
    ambiguous = 1
    no_layout_fits = 2
    count_mismatch = 3
    no_frames = 4
    bad_frame = 5

class CrcInputFinding(enum.IntEnum):
    same_bytes = 0
    as_sent = 1
    least_significant_first = 2
    both_fit = 3
    none_fits = 4
    undecided = 5

class GroupOrder(enum.IntEnum):
    least_significant_first = 0
    most_significant_first = 1

class CrcInput(enum.IntEnum):
    as_sent = 0
    least_significant_first = 1

_Frames = Union[bytes, bytearray, memoryview, Sequence[Any]]

@dataclass(frozen=True)
class CrcParameters:
    polynomial: int
    initial: int
    reflect_in: bool
    reflect_out: bool
    xor_out: int
    name: str = ...

@dataclass(frozen=True)
class CrcLearnResult:
    status: CrcLearnStatus
    classes: Tuple[Tuple[CrcParameters, ...], ...]
    survivors: int
    frames: int
    def __bool__(self) -> bool: ...
    @property
    def crc(self) -> Optional[CrcParameters]: ...

def variable_transfers(stream: Any) -> Tuple[List[bytes], int]: ...
def learn_ring_crc(frames: _Frames, *, even_polynomials: bool = ..., max_classes: int = ...) -> CrcLearnResult: ...

@dataclass(frozen=True)
class OrderFit:
    vr: GroupOrder
    value: GroupOrder
    fits: bool
    first_contradiction: int

@dataclass(frozen=True)
class LayoutLearnResult:
    status: LayoutLearnStatus
    vr_group_order: GroupOrder
    value_group_order: GroupOrder
    crc_input: CrcInput
    orders: Tuple[OrderFit, ...]
    crc_finding: CrcInputFinding
    def __bool__(self) -> bool: ...

def learn_ring_layout(frames: _Frames, sent: Iterable[Tuple[int, float]], *,
                      crc: Optional[CrcParameters] = ...) -> LayoutLearnResult: ...

@dataclass(frozen=True)
class Crc6Sample:
    data: bytes
    crc: int

def genius_crc_samples(characters: Iterable[Union[Character, Tuple[int, bool]]], *,
                       profile: Optional[Profile] = ...) -> Tuple[List[Crc6Sample], List[Crc6Sample], int]: ...
def learn_genius_crc(samples: Sequence[Union[Crc6Sample, Tuple[bytes, int]]], *, even_polynomials: bool = ...,
                     max_classes: int = ...) -> CrcLearnResult: ...
