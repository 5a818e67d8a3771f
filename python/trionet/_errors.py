"""The package's exceptions and its enum helper."""

from __future__ import annotations

import enum
from collections.abc import Iterable
from typing import Any, Optional, Tuple


class TrionetError(Exception):
    """Base class of every exception the package raises itself."""


class StatusError(TrionetError, ValueError):
    """A call was refused as misuse: ``status`` (a member of the C++ status enum, as an IntEnum) says why, and
    nothing was sent, written or queued."""

    def __init__(self, status: enum.IntEnum, detail: Optional[str] = None) -> None:
        self.status = status
        self.detail = detail
        super().__init__(f"{status.name}: {detail}" if detail else status.name)


def small(value: int, limit: int = 0xFFFF, what: str = "") -> int:
    """An int for a C++ parameter of at most ``limit``: TypeError for anything but an int (naming ``what`` when
    given); values outside 0..limit become ``limit``, which is out of range wherever it goes, so that the
    library refuses them with its own status."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{what} is an int, not {type(value).__name__}" if what else
                        f"expected an int, not {type(value).__name__}")
    return value if 0 <= value <= limit else limit


def number(value: float) -> float:
    """A real number (int, float or anything with __float__ but a str or bytes) as a float."""
    if isinstance(value, (str, bytes, bytearray)):
        raise TypeError(f"expected a number, not {type(value).__name__}")
    return float(value)


def data_bytes(value: Any, what: str = "data") -> Any:
    """``value`` if it is a bytes-like object (bytes, bytearray, memoryview, mmap, array; read as it is); a
    TypeError naming ``what`` for anything else: ``bytes(5)`` would be five NUL bytes and ``bytes([72, 73])``
    a list read as bytes."""
    if isinstance(value, (bytes, bytearray)):
        return value
    try:
        memoryview(value).release()
    except TypeError:
        raise TypeError(f"{what} must be a bytes-like object (bytes, bytearray, memoryview), not "
                        f"{type(value).__name__}") from None
    return value


def int_enum(name: str, members: Iterable[Tuple[str, int]], module: str, doc: str) -> type:
    """An enum.IntEnum whose members are a C++ enum's (names as the C++ code spells them)."""
    made = enum.IntEnum(name, list(members), module=module)  # type: ignore[misc]
    made.__doc__ = doc
    return made
