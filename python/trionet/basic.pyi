from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

from ._profile import Profile

MAX_PROGRAM_BYTES: int

@dataclass(frozen=True)
class Program:
    text: str
    name: str = ...

class Keypad:
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

@dataclass(frozen=True)
class NetworkEvent:
    kind: str
    time: int
    node: int
    text: str
    display: Tuple[str, ...] = ...

Node = Union[str, Program, Keypad]

def examples() -> List[str]: ...

class Network:
    def __init__(self, nodes: Sequence[Node], *, keys: str = ..., statements_per_byte_time: int = ...,
                 bit_rate: float = ..., key_gap: int = ..., profile: Optional[Profile] = ...,
                 on_event: Optional[Callable[[NetworkEvent], None]] = ..., trace: bool = ...,
                 _builtin: bool = ...) -> None: ...
    def run(self, byte_times: int = ...) -> Dict[str, Any]: ...
    def run_json(self, byte_times: int = ...) -> str: ...
    def step(self) -> None: ...
    def press(self, keypad: int, key: str) -> None: ...
    @property
    def now(self) -> int: ...
    @property
    def seconds(self) -> float: ...
    @property
    def settled(self) -> bool: ...

def simulate(nodes: Sequence[Node], *, keys: str = ..., byte_times: int = ..., statements_per_byte_time: int = ...,
             bit_rate: float = ..., key_gap: int = ..., profile: Optional[Profile] = ...,
             on_event: Optional[Callable[[NetworkEvent], None]] = ..., trace: bool = ...) -> Dict[str, Any]: ...
def simulate_example(name: str, *, keys: Optional[str] = ..., byte_times: int = ..., statements_per_byte_time: int = ...,
                     bit_rate: float = ..., key_gap: int = ..., on_event: Optional[Callable[[NetworkEvent], None]] = ...,
                     trace: bool = ...) -> Dict[str, Any]: ...
