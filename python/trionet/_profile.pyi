import enum
import os
from typing import Any, Dict, Union

from ._errors import TrionetError

class ProfileStatus(enum.IntEnum):
    ok = 0
    not_json = 1
    unsupported_version = 2
    missing_key = 3
    unknown_key = 4
    wrong_type = 5
    out_of_range = 6
    duplicate_code = 7

class ProfileError(TrionetError, ValueError):
    status: ProfileStatus
    key: str
    message: str
    line: int
    column: int
    def __init__(self, status: int, key: str, message: str, line: int, column: int) -> None: ...

class Profile:
    def __init__(self) -> None: ...
    @classmethod
    def from_json(cls, text: Union[str, bytes]) -> Profile: ...
    @classmethod
    def from_file(cls, path: Union[str, os.PathLike[str]]) -> Profile: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def header(self, namespace: str = ...) -> str: ...
    @property
    def name(self) -> str: ...
    @name.setter
    def name(self, value: str) -> None: ...
    def __eq__(self, other: object) -> bool: ...

def _data_of(profile: Profile | None) -> Any: ...
