"""Profiles: every configurable wire parameter of a network in one JSON file (docs/profile.md)."""

from __future__ import annotations

import json
import os
from typing import Any, Dict, Optional, Union

from . import _trionet
from ._errors import TrionetError, int_enum

_core = _trionet.profile

ProfileStatus = int_enum("ProfileStatus", _core.enums["ProfileStatus"], __name__,
                         "Why a profile could not be read (learn::profile_status).")


class ProfileError(TrionetError, ValueError):
    """A profile that is not valid: ``status`` says what is wrong, ``key`` names the offending key as a path
    ("ring.crc.polynomial"), ``line`` and ``column`` say where (1-based; 0 when not known)."""

    def __init__(self, status: int, key: str, message: str, line: int, column: int) -> None:
        self.status = ProfileStatus(status)
        self.key = key
        self.message = message
        self.line = line
        self.column = column
        where = f" at line {line}, column {column}" if line else ""
        what = f" {key}" if key else ""
        super().__init__(f"{self.status.name}{what}{where}: {message}" if message else f"{self.status.name}{what}{where}")


class Profile:
    """The wire parameters of a network: the ring's CRC and variable layout, the keypad's codes, the CAN byte
    order and node count, the Genius CRC-6 and control layout. ``Profile()`` is the default: the decisions
    of docs/protocol.md. Read one with :meth:`from_file` or :meth:`from_json`; pass it as ``profile=`` to the
    encoders, decoders and simulations that take one."""

    def __init__(self) -> None:
        self._data = _core.ProfileData()

    @classmethod
    def from_json(cls, text: Union[str, bytes]) -> "Profile":
        """Reads a profile; keys left out keep their defaults. Raises ProfileError naming the bad key. Bytes are
        read as the tool reads a file: invalid UTF-8 is an error (not_json), not replaced."""
        if isinstance(text, (bytes, bytearray)):
            text = bytes(text)  # to the C++ reader as they are: it checks the UTF-8, as `trionet profile show`
        elif not isinstance(text, str):
            raise TypeError(f"a profile is JSON text (str or bytes), not {type(text).__name__}")
        status, data, key, message, line, column = _core.read_profile(text)
        if data is None:
            raise ProfileError(status, key, message, line, column)
        profile = cls.__new__(cls)
        profile._data = data
        return profile

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"]) -> "Profile":
        """Reads a profile file (OSError if it cannot be read, ProfileError if it is not valid: a file larger than
        1 MiB is too_large, as for the tool, not cut and parsed)."""
        with open(path, "rb") as f:
            return cls.from_json(f.read((1 << 20) + 1))  # one byte more than the reader takes: too_large

    def to_json(self) -> str:
        """The profile as JSON with every key, as `trionet profile show` writes it."""
        return str(self._data.to_json())

    def to_dict(self) -> Dict[str, Any]:
        """The profile as the dict its JSON reads as."""
        return dict(json.loads(self.to_json()))

    def header(self, namespace: str = "trionet_profile") -> str:
        """A C++17 header of constexpr policies for a firmware build (`trionet profile header`)."""
        if not isinstance(namespace, str):
            raise TypeError(f"namespace is a str, not {type(namespace).__name__}")
        return str(self._data.header(namespace))

    @property
    def name(self) -> str:
        """Free text, for people."""
        return str(self._data.name)

    @name.setter
    def name(self, value: str) -> None:
        if not isinstance(value, str):
            raise TypeError(f"a profile's name is a str, not {type(value).__name__}")
        self._data.name = value

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Profile) and bool(self._data == other._data)

    def __repr__(self) -> str:
        return f"Profile(name={self.name!r})"


def _data_of(profile: Optional[Profile]) -> Any:
    """The C++ profile of ``profile`` (None for the default), checking its type."""
    if profile is None:
        return None
    if not isinstance(profile, Profile):
        raise TypeError(f"profile must be a trionet.Profile, not {type(profile).__name__}")
    return profile._data
