"""Learning a network's unpublished wire parameters from captured frames (docs/profile.md): the ring's CRC
of direct variable transfers and their field layout, and the Genius CRC-6 (`trionet ring learn`,
`trionet genius learn`). Frames that do not fit are results with a status, not exceptions.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable, List, Optional, Sequence, Tuple, Union

from . import _trionet
from ._errors import data_bytes, int_enum, number
from ._profile import Profile, _data_of
from .genius import Character

_core = _trionet.learn
_e = _core.enums

CrcLearnStatus = int_enum("CrcLearnStatus", _e["CrcLearnStatus"], __name__,
                          "The outcome of a CRC search (learn::crc_learn_status).")
LayoutLearnStatus = int_enum("LayoutLearnStatus", _e["LayoutLearnStatus"], __name__,
                             "The outcome of a layout search (learn::layout_learn_status).")
CrcInputFinding = int_enum("CrcInputFinding", _e["CrcInputFinding"], __name__,
                           "Which bytes the CRC covers, as far as the frames tell (learn::crc_input_finding).")
GroupOrder = int_enum("GroupOrder", _e["GroupOrder"], __name__,
                      "The order of a field's 7-bit groups (ring::group_order).")
CrcInput = int_enum("CrcInput", _e["CrcInput"], __name__, "Which order of bytes the CRC covers (ring::crc_input).")


@dataclass(frozen=True)
class CrcParameters:
    """A CRC of the Rocksoft/reveng model (16-bit on the ring, 6-bit on Genius); ``name`` is its catalogue
    name, or "" if it is not in the catalogue."""

    polynomial: int
    initial: int
    reflect_in: bool
    reflect_out: bool
    xor_out: int
    name: str = ""


@dataclass(frozen=True)
class CrcLearnResult:
    """Every class of CRCs that fits the frames (CRCs of one class give the same bits for every valid
    frame); the first member of each class is its representative."""

    status: CrcLearnStatus
    classes: Tuple[Tuple[CrcParameters, ...], ...]
    survivors: int
    frames: int

    def __bool__(self) -> bool:
        return self.status == CrcLearnStatus.ok

    @property
    def crc(self) -> Optional[CrcParameters]:
        """The representative of the one class found (status ok), else None."""
        return self.classes[0][0] if self.status == CrcLearnStatus.ok else None


def _classes(classes: Any) -> Tuple[Tuple[CrcParameters, ...], ...]:
    return tuple(tuple(CrcParameters(p["polynomial"], p["initial"], p["reflect_in"], p["reflect_out"], p["xor_out"],
                                     name) for p, name in members) for members in classes)


def variable_transfers(stream: Any) -> Tuple[List[bytes], int]:
    """The direct variable transfers of a stream of ring bytes: the 14 data bytes of each, and the number of
    bytes that were not part of one."""
    frames, skipped = _core.variable_transfers(stream)
    return [bytes(f) for f in frames], int(skipped)


def _max_classes(value: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"max_classes is an int, not {type(value).__name__}")
    if not 0 <= value <= 2**32 - 1:
        raise ValueError(f"max_classes is 0..2**32 - 1, got {value}")
    return value


def _frames(frames: Union[bytes, bytearray, memoryview, Sequence[Any]]) -> List[bytes]:
    if isinstance(frames, (bytes, bytearray, memoryview)):
        return variable_transfers(frames)[0]
    out = [bytes(data_bytes(f, "a frame")) for f in frames]
    for f in out:
        if len(f) != 14:
            raise ValueError(f"a direct variable transfer's data is 14 bytes, got {len(f)}")
    return out


def learn_ring_crc(frames: Union[bytes, bytearray, memoryview, Sequence[Any]], *, even_polynomials: bool = False,
                   max_classes: int = 256) -> CrcLearnResult:
    """Every 16-bit CRC that fits the frames (`trionet ring learn crc`): ``frames`` is a stream of ring bytes
    (its direct variable transfers are used) or a list of 14-byte frames. Three frames usually decide it."""
    r = _core.learn_ring_crc(_frames(frames), even_polynomials, _max_classes(max_classes))
    return CrcLearnResult(CrcLearnStatus(r["status"]), _classes(r["classes"]), r["survivors"], r["frames"])


@dataclass(frozen=True)
class OrderFit:
    """How one (VR, value) group-order pair did: ``first_contradiction`` is the index of the first frame that
    reads otherwise."""

    vr: GroupOrder
    value: GroupOrder
    fits: bool
    first_contradiction: int


@dataclass(frozen=True)
class LayoutLearnResult:
    """The layout of direct variable transfers found from frames and what was sent (`trionet ring learn
    layout`)."""

    status: LayoutLearnStatus
    vr_group_order: GroupOrder
    value_group_order: GroupOrder
    crc_input: CrcInput
    orders: Tuple[OrderFit, ...]
    crc_finding: CrcInputFinding

    def __bool__(self) -> bool:
        return self.status == LayoutLearnStatus.ok


def learn_ring_layout(frames: Union[bytes, bytearray, memoryview, Sequence[Any]],
                      sent: Iterable[Tuple[int, float]], *, crc: Optional[CrcParameters] = None) -> LayoutLearnResult:
    """The group orders and CRC input that make frame i read as ``sent[i]`` (VR, value). ``crc`` is a 16-bit
    CRC (ValueError for a polynomial, initial value or xor_out outside 0..0xFFFF)."""
    if crc is not None:
        if not isinstance(crc, CrcParameters):
            raise TypeError(f"crc is a CrcParameters, not {type(crc).__name__}")
        for value, what in [(crc.polynomial, "polynomial"), (crc.initial, "initial"), (crc.xor_out, "xor_out")]:
            if isinstance(value, bool) or not isinstance(value, int):
                raise TypeError(f"the CRC's {what} is an int, not {type(value).__name__}")
            if not 0 <= value <= 0xFFFF:
                raise ValueError(f"the ring's CRC is 16 bits: its {what} is 0..0xFFFF, got {value:#x}")
    pairs = []
    for v, x in sent:
        if isinstance(v, bool) or not isinstance(v, int):
            raise TypeError(f"a sent VR number is an int, not {type(v).__name__}")
        if not 0 <= v <= _trionet.ring.MAX_VR:
            raise ValueError(f"a sent VR number is 0..{_trionet.ring.MAX_VR}, got {v}")
        pairs.append((v, number(x)))
    given = None if crc is None else {"polynomial": crc.polynomial, "initial": crc.initial,
                                       "reflect_in": crc.reflect_in, "reflect_out": crc.reflect_out,
                                       "xor_out": crc.xor_out}
    r = _core.learn_ring_layout(_frames(frames), pairs, given)
    return LayoutLearnResult(LayoutLearnStatus(r["status"]), GroupOrder(r["vr_group_order"]),
                             GroupOrder(r["value_group_order"]), CrcInput(r["crc_input"]),
                             tuple(OrderFit(GroupOrder(v), GroupOrder(x), fits, first)
                                   for v, x, fits, first in r["orders"]),
                             CrcInputFinding(r["crc_finding"]))


@dataclass(frozen=True)
class Crc6Sample:
    """Bytes a Genius CRC-6 covers and the CRC sent for them."""

    data: bytes
    crc: int


def genius_crc_samples(characters: Iterable[Union[Character, Tuple[int, bool]]], *,
                       profile: Optional[Profile] = None) -> Tuple[List[Crc6Sample], List[Crc6Sample], int]:
    """The CRC samples of a stream of Genius characters: one per Stop, one per End of block, and the number
    of characters skipped."""
    chars = [(int(b), bool(c)) for b, c in characters]
    for b, _ in chars:
        if not 0 <= b <= 255:
            raise ValueError(f"a character's byte is 0..255, got {b}")
    stops, blocks, skipped = _core.genius_crc_samples(chars, _data_of(profile))
    return ([Crc6Sample(bytes(d), c) for d, c in stops], [Crc6Sample(bytes(d), c) for d, c in blocks], int(skipped))


def learn_genius_crc(samples: Sequence[Union[Crc6Sample, Tuple[bytes, int]]], *, even_polynomials: bool = False,
                     max_classes: int = 256) -> CrcLearnResult:
    """Every CRC-6 that fits the samples (`trionet genius learn crc`); 4 or 5 samples usually decide it."""
    pairs = [(bytes(data_bytes(s.data, "a sample's data")), int(s.crc)) if isinstance(s, Crc6Sample)
             else (bytes(data_bytes(s[0], "a sample's data")), int(s[1])) for s in samples]
    for _, c in pairs:
        if not 0 <= c <= 255:
            raise ValueError(f"a CRC-6 is 0..63, got {c}")
    r = _core.learn_genius_crc(pairs, even_polynomials, _max_classes(max_classes))
    return CrcLearnResult(CrcLearnStatus(r["status"]), _classes(r["classes"]), r["survivors"], r["samples"])


__all__ = [
    "Crc6Sample", "CrcInput", "CrcInputFinding", "CrcLearnResult", "CrcLearnStatus", "CrcParameters", "GroupOrder",
    "LayoutLearnResult", "LayoutLearnStatus", "OrderFit", "genius_crc_samples", "learn_genius_crc",
    "learn_ring_crc", "learn_ring_layout", "variable_transfers",
]
