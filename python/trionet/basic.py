"""Trio BASIC programs on the simulated ring (docs/basic.md), as `trionet ring simulate` runs them.

A network is a list of nodes in ring order: ``"mc:FILE.bas"`` (a Motion Coordinator running that program),
``"mc"`` (one without a program), ``"keypad"``, or a :class:`Program` (a program given as text). A run ends
when every program has ended, failed or waits for ever, the key script is done and the ring is quiet, or
after ``byte_times``. Its result is the dict that `trionet ring simulate --json` prints as its last line
(the same C++ code writes both): ``byte_times``, ``seconds``, ``end`` ("settled" or "limit") and ``nodes``,
one dict per node with its state, VRs, variables and axis parameters (an MC) or its display (a keypad).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from collections.abc import Sequence
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

from . import _trionet
from ._profile import Profile, _data_of

_core = _trionet.basic

#: The longest program file read from a path (a larger one is refused, not read).
MAX_PROGRAM_BYTES = 1 << 20


@dataclass(frozen=True)
class Program:
    """A Motion Coordinator with a BASIC program given as text; ``name`` is what messages call it."""

    text: str
    name: str = "program.bas"


class Keypad:
    """A membrane keypad."""

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Keypad)

    def __hash__(self) -> int:
        return hash(Keypad)


@dataclass(frozen=True)
class NetworkEvent:
    """Something that happened during a run: ``kind`` is one of "key", "dropped", "vr_from_ring", "output",
    "netstat", "ended", "failed" and, when traced, "message", "frame_error", "display"; ``node`` is the
    1-based ring position; ``text`` says what happened as `trionet ring simulate` prints it; ``display`` is a
    keypad display's two lines (kind "display")."""

    kind: str
    time: int
    node: int
    text: str
    display: Tuple[str, ...] = ()


Node = Union[str, Program, Keypad]


def examples() -> List[str]:
    """The names of the networks built into the tool: example1, example2, example3, example3-fixed."""
    return [name for name, _title, _nodes, _keys in _core.builtin_networks()]


def _read_program(path: str) -> bytes:
    if os.path.isdir(path):
        raise IsADirectoryError(f"{path} is a directory, not a BASIC program")
    with open(path, "rb") as f:
        data = f.read(MAX_PROGRAM_BYTES + 1)
    if len(data) > MAX_PROGRAM_BYTES:
        raise ValueError(f"{path} is longer than {MAX_PROGRAM_BYTES} bytes: not a BASIC program")
    return data


def _whole(value: int, what: str) -> None:
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{what} is an int, not {type(value).__name__}")


def _spec(node: Node, builtin: bool) -> Tuple[str, str, Union[str, bytes]]:
    if isinstance(node, Program):
        if not isinstance(node.text, (str, bytes)) or not isinstance(node.name, str):
            raise TypeError(f"a Program is text (str or bytes) and a name (str), not {type(node.text).__name__} "
                            f"and {type(node.name).__name__}")
        return ("mc", node.name, node.text)
    if isinstance(node, Keypad) or node == "keypad":
        return ("keypad", "", "")
    if node == "mc":
        return ("mc", "", "")
    if isinstance(node, str) and node.startswith("mc:") and len(node) > 3:
        path = node[3:]
        if builtin:
            text = _core.builtin_file(path)
            if text is None:
                raise ValueError(f"{path} is not built into this package")
            return ("mc", path, text)
        return ("mc", path, _read_program(path))
    raise ValueError(f"a node is mc:FILE, mc, keypad, a Program or a Keypad, not {node!r}")


class Network:
    """A ring of Motion Coordinators running BASIC programs and keypads (host::ring_network).

    ``on_event`` is called with a :class:`NetworkEvent` for everything that happens as it happens (an
    exception in it stops the events and is raised when the run returns). ``trace`` adds every message on
    every link and every display change. ValueError for a program that does not compile
    ("NAME:LINE:COLUMN: message"), a bad key script or a ring that is not 2..15 nodes with at least one MC.
    """

    def __init__(self, nodes: Sequence[Node], *, keys: str = "", statements_per_byte_time: int = 1,
                 bit_rate: float = 125000.0, key_gap: int = 1000, profile: Optional[Profile] = None,
                 on_event: Optional[Callable[[NetworkEvent], None]] = None, trace: bool = False,
                 _builtin: bool = False) -> None:
        if isinstance(nodes, (str, bytes, Program, Keypad)):
            raise TypeError(f"nodes is a list of nodes (a ring has 2..15), not one {type(nodes).__name__}: "
                            f"[{nodes!r}, ...]")
        if not isinstance(keys, str):
            raise TypeError(f"keys is a key script (str), not {type(keys).__name__}")
        _whole(statements_per_byte_time, "statements_per_byte_time")
        _whole(key_gap, "key_gap")
        if isinstance(bit_rate, (str, bytes)) or bit_rate is None:
            raise TypeError(f"bit_rate is a number, not {type(bit_rate).__name__}")
        if not 1 <= statements_per_byte_time <= 1_000_000:
            raise ValueError(f"statements_per_byte_time must be 1..1000000, got {statements_per_byte_time}")
        if not 1 <= bit_rate <= 1e9:
            raise ValueError(f"bit_rate must be 1..10^9 bits per second, got {bit_rate}")
        if not 0 <= key_gap <= 1_000_000_000:
            raise ValueError(f"key_gap must be 0..10^9 byte-times, got {key_gap}")
        specs = [_spec(node, _builtin) for node in nodes]
        data = _data_of(profile)
        if data is not None and (data.ring_max_characters != 256 or data.ring_receive_buffer != 256):
            raise ValueError("the simulated ring is built for ring.max_characters and ring.receive_buffer 256")
        self._net = _core.Network(specs, statements_per_byte_time, float(bit_rate), key_gap, data)
        self._net.set_keys(keys)
        if on_event is not None or trace:
            traced_only = {"message", "frame_error", "display"}

            def sink(kind: str, t: int, node: int, text: str, display: List[str]) -> None:
                if kind in traced_only and not trace:
                    return
                event = NetworkEvent(kind, t, node, text, tuple(display))
                if on_event is not None:
                    on_event(event)

            self._net.on_event(sink)

    def run(self, byte_times: int = 1_000_000) -> Dict[str, Any]:
        """Runs until the network settles or ``byte_times`` byte-times have passed since the start; the
        summary, as `trionet ring simulate --json` prints it."""
        _whole(byte_times, "byte_times")
        if not 1 <= byte_times <= 10**12:
            raise ValueError(f"byte_times must be 1..10^12, got {byte_times}")
        return dict(json.loads(self._net.run(byte_times)))

    def run_json(self, byte_times: int = 1_000_000) -> str:
        """:meth:`run`, giving the JSON line itself."""
        _whole(byte_times, "byte_times")
        if not 1 <= byte_times <= 10**12:
            raise ValueError(f"byte_times must be 1..10^12, got {byte_times}")
        return str(self._net.run(byte_times))

    def step(self) -> None:
        """One byte-time."""
        self._net.step()

    def press(self, keypad: int, key: str) -> None:
        """Presses and releases a key now on keypad ``keypad`` (1-based among the keypads)."""
        _whole(keypad, "keypad")
        if not isinstance(key, str):
            raise TypeError(f"key is a key's name (str), not {type(key).__name__}")
        if not 1 <= keypad <= 15:
            raise ValueError(f"keypad is 1..15 (among the ring's keypads), got {keypad}")
        self._net.press(keypad, key)

    @property
    def now(self) -> int:
        """Byte-times run so far."""
        return int(self._net.now)

    @property
    def seconds(self) -> float:
        """Ring time run so far, in seconds."""
        return float(self._net.seconds)

    @property
    def settled(self) -> bool:
        """True once the run has met its end condition."""
        return bool(self._net.settled)


def simulate(nodes: Sequence[Node], *, keys: str = "", byte_times: int = 1_000_000,
             statements_per_byte_time: int = 1, bit_rate: float = 125000.0, key_gap: int = 1000,
             profile: Optional[Profile] = None, on_event: Optional[Callable[[NetworkEvent], None]] = None,
             trace: bool = False) -> Dict[str, Any]:
    """`trionet ring simulate --node ... --json`: builds the network, runs it, returns the summary dict."""
    return Network(nodes, keys=keys, statements_per_byte_time=statements_per_byte_time, bit_rate=bit_rate,
                   key_gap=key_gap, profile=profile, on_event=on_event, trace=trace).run(byte_times)


def simulate_example(name: str, *, keys: Optional[str] = None, byte_times: int = 1_000_000,
                     statements_per_byte_time: int = 1, bit_rate: float = 125000.0, key_gap: int = 1000,
                     on_event: Optional[Callable[[NetworkEvent], None]] = None,
                     trace: bool = False) -> Dict[str, Any]:
    """`trionet ring simulate NAME --json`: a network built into the tool, with its own key script unless
    ``keys`` is given."""
    for builtin, _title, nodes, builtin_keys in _core.builtin_networks():
        if builtin == name:
            network = Network(nodes, keys=builtin_keys if keys is None else keys,
                              statements_per_byte_time=statements_per_byte_time, bit_rate=bit_rate, key_gap=key_gap,
                              on_event=on_event, trace=trace, _builtin=True)
            return network.run(byte_times)
    raise ValueError(f"unknown network {name!r} (expected {', '.join(examples())})")


__all__ = ["Keypad", "MAX_PROGRAM_BYTES", "Network", "NetworkEvent", "Node", "Program", "examples", "simulate",
           "simulate_example"]
