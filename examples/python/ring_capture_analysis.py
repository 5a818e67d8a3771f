#!/usr/bin/env python3
"""Analyses a capture of fibre-ring bytes: messages by type and hops, errors by reason with where the first
of each was, and the last value of every VR written.

    python3 examples/python/ring_capture_analysis.py capture.bin        # raw bytes, e.g. from a serial port
    python3 examples/python/ring_capture_analysis.py --profile plant.json capture.bin
    python3 examples/python/ring_capture_analysis.py                     # a capture made here on a simulated ring

The file is read in 64 KiB pieces through trionet.ring.Decoder, so a capture of any size takes the same
memory. The events have the fields of `trionet ring decode --raw` (`--json` prints them as JSON lines).
Without a file, two Motion Coordinators and a keypad exchange messages on trionet.ring.Simulator, with a
few bits flipped on the way, and the bytes of one link are the capture.
"""

import argparse
import collections
import json
import sys
from typing import Counter, Dict, Optional, Tuple

from trionet import Profile, ProfileError, ring

CHUNK = 1 << 16


def simulated_capture() -> bytes:
    """The bytes that left node 1 of a small simulated ring (MC, MC, keypad), with some bits flipped."""
    first, second, keypad = ring.MotionCoordinator(), ring.MotionCoordinator(), ring.Keypad()
    sim = ring.Simulator([first, second, keypad])
    captured = bytearray()

    def tap(byte: ring.LinkByte) -> None:
        if byte.link == 0:
            captured.append(byte.received)

    first.send_keypad_offset(11, 10)
    for i in range(200):
        while not first.send(10, 100 + i % 8, i * 0.25):
            sim.run(10, trace=tap)
        if i % 10 == 0:
            first.print(11, f"\x0cCOUNT {i}")
        if i % 50 == 25:
            sim.flip_next(0, 0x04)
        sim.run(20, trace=tap)
    sim.run(200, trace=tap)
    return bytes(captured)


def analyse(stream, profile: Optional[Profile], as_json: bool) -> int:
    decoder = ring.Decoder(profile)
    kinds: Counter[Tuple[str, str]] = collections.Counter()
    first_error: Dict[str, int] = {}
    last_vr: Dict[int, float] = {}
    total = 0

    def take(events) -> None:
        nonlocal total
        for event in events:
            total += 1
            if as_json:
                print(json.dumps(event.to_dict()))
            if event.event == "message":
                kinds[(event.type, f"hops {event.hops}")] += 1
                if event.type == "var":
                    last_vr[event.vr] = event.value
            else:
                reason = event.reason or event.event
                kinds[(event.event, reason)] += 1
                first_error.setdefault(reason, event.position)

    while True:
        chunk = stream.read(CHUNK)
        if not chunk:
            break
        take(decoder.feed(chunk))
    take(decoder.finish())
    if as_json:
        return 0

    print(f"{decoder.position} bytes, {total} events")
    for (kind, detail), count in sorted(kinds.items()):
        where = f"  (first at byte {first_error[detail]})" if detail in first_error else ""
        print(f"  {kind:12} {detail:14} {count:8}{where}")
    if last_vr:
        print("last value of each VR: " + " ".join(f"VR({vr})={value:g}" for vr, value in sorted(last_vr.items())))
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].replace("\n", " "))
    parser.add_argument("capture", nargs="?", help="a file of raw ring bytes (default: a simulated capture)")
    parser.add_argument("--profile", help="a profile (docs/profile.md) with the network's CRC and layout")
    parser.add_argument("--json", action="store_true", help="print every event as a JSON line instead")
    args = parser.parse_args()
    try:
        profile = Profile.from_file(args.profile) if args.profile else None
    except (OSError, ProfileError) as e:
        print(f"{parser.prog}: profile {args.profile}: {e.strerror if isinstance(e, OSError) else e}", file=sys.stderr)
        return 1
    if args.capture is None:
        import io

        return analyse(io.BytesIO(simulated_capture()), profile, args.json)
    try:
        f = open(args.capture, "rb")
    except OSError as e:
        print(f"{parser.prog}: cannot open {args.capture}: {e.strerror}", file=sys.stderr)
        return 1
    with f:
        return analyse(f, profile, args.json)


if __name__ == "__main__":
    sys.exit(main())
