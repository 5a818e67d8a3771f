import enum
from dataclasses import dataclass
from typing import Any, Callable, Dict, Iterator, Optional, Union

import can as python_can

from .ring import VrTable

class SchemeStatus(enum.IntEnum):
    ok = 0
    bad_node_count = 1
    bad_node = 2
    same_node = 3
    bad_channel = 4
    not_exchange_identifier = 5

class EncodeStatus(enum.IntEnum):
    ok = 0
    vr_out_of_range = 1
    not_a_number = 2
    too_large = 3
    fraction_out_of_range = 4

class DecodeStatus(enum.IntEnum):
    ok = 0
    bad_dlc = 1
    bad_sign = 2
    bad_fraction = 3
    bad_identifier = 4

class ByteOrder(enum.IntEnum):
    big_endian = 0
    little_endian = 1

class SendStatus(enum.IntEnum):
    ok = 0
    no_such_node = 1
    own_node = 2
    no_such_channel = 3
    vr_out_of_range = 4
    not_a_number = 5
    too_large = 6
    fraction_out_of_range = 7
    port_busy = 8
    port_failed = 9

class ReceiveStatus(enum.IntEnum):
    ok = 0
    refused = 1
    out_of_range = 2
    value_out_of_range = 3
    foreign = 4
    bad_dlc = 5
    bad_sign = 6
    bad_fraction = 7

MIN_NODE_COUNT: int
MAX_NODE_COUNT: int
DEFAULT_NODE_COUNT: int
MAX_MESSAGE_VR: int

_Buffer = Any  # any object with the buffer protocol

def base_identifier(node: int, nodes: int = ...) -> int: ...
def receive_identifier(node: int, channel: int, nodes: int = ...) -> int: ...
def exchange_identifier(sender: int, receiver: int, nodes: int = ...) -> int: ...
def transmit_identifier(sender: int, channel: int, nodes: int = ...) -> int: ...
def destination_of(sender: int, channel: int, nodes: int = ...) -> int: ...
def transmit_channel_to(sender: int, destination: int, nodes: int = ...) -> int: ...

@dataclass(frozen=True)
class Route:
    sender: int
    receiver: int
    receive_channel: int

def route_of(identifier: int, nodes: int = ...) -> Optional[Route]: ...

@dataclass(frozen=True)
class DecodedVr:
    status: DecodeStatus
    vr: int = ...
    value: float = ...
    negative: bool = ...
    integer_part: int = ...
    fraction: int = ...
    route: Optional[Route] = ...
    def __bool__(self) -> bool: ...

def encode_vr(vr: int, value: float, byte_order: ByteOrder = ...) -> bytes: ...
def decode_vr(data: _Buffer, byte_order: ByteOrder = ...) -> DecodedVr: ...
def to_message(sender: int, receiver: int, vr: int, value: float, *, nodes: int = ...,
               byte_order: ByteOrder = ...) -> python_can.Message: ...
def from_message(message: python_can.Message, *, nodes: int = ..., byte_order: ByteOrder = ...) -> DecodedVr: ...

@dataclass(frozen=True)
class ReceivedVr:
    sender: int
    vr: int
    value: float
    receive_channel: int

@dataclass(frozen=True)
class ReceivedFrame:
    status: ReceiveStatus
    sender: int = ...
    receive_channel: int = ...
    vr: int = ...
    value: float = ...

class VrExchangeNode:
    bus: python_can.BusABC
    node: int
    nodes: int
    byte_order: ByteOrder
    @property
    def vr(self) -> VrTable: ...
    on_vr: Optional[Callable[[ReceivedVr], None]]
    send_timeout: Optional[float]
    def __init__(self, bus: python_can.BusABC, node: int, nodes: int = ..., *, byte_order: ByteOrder = ...,
                 vr: Union[int, VrTable] = ..., write_policy: Optional[Callable[[int, float], bool]] = ...,
                 on_vr: Optional[Callable[[ReceivedVr], None]] = ..., send_timeout: Optional[float] = ...,
                 queue_limit: int = ...) -> None: ...
    def send(self, to: int, vr: int, value: float) -> None: ...
    def receive(self, message: python_can.Message) -> ReceivedFrame: ...
    def poll(self, timeout: float = ...) -> int: ...
    def received(self, timeout: Optional[float] = ...) -> Iterator[ReceivedVr]: ...
    def __iter__(self) -> Iterator[ReceivedVr]: ...
    @property
    def pending(self) -> int: ...
    def start(self) -> None: ...
    def stop(self) -> None: ...
    def close(self) -> None: ...
    def __enter__(self) -> VrExchangeNode: ...
    def __exit__(self, *exc: Any) -> None: ...
    def counters(self) -> Dict[str, int]: ...
    def clear_counters(self) -> None: ...
    def wait_for(self, condition: Callable[[], bool], timeout: float) -> bool: ...
