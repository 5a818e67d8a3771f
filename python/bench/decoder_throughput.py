#!/usr/bin/env python3
"""trionet.ring.Decoder against `trionet ring decode --raw` on the same ring bytes, in the same run.

    python3 python/bench/decoder_throughput.py [--megabytes 100] [--runs 3] [--cli build/src/trionet]

The bytes: a fixed mix of every message kind (character transfers of 5 to 40 characters, direct variable
transfers, keypad offsets and modes) with one frame in 50 damaged, written to a scratch file. The tool decodes
the file from standard input to /dev/null; the package reads it in 64 KiB pieces into one reused buffer and
takes every event, counting them by kind (each event's `event` field read), in a process of its own. Runs
alternate; the medians are reported, as CPU time (user + system, what a shared machine does not distort) and
as elapsed time, with the package's peak memory (its resident set) next to the size of the input.
"""

import argparse
import os
import random
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CHUNK = 1 << 16

CONSUMER = """
import resource, sys, time
from trionet import ring
path = sys.argv[1]
start_cpu = resource.getrusage(resource.RUSAGE_SELF)
start = time.perf_counter()
decoder = ring.Decoder()
counts = {}
buffer = bytearray(65536)
view = memoryview(buffer)
with open(path, "rb", buffering=0) as f:
    while True:
        n = f.readinto(buffer)
        if not n:
            break
        for event in decoder.feed(view[:n]):
            kind = event.event
            counts[kind] = counts.get(kind, 0) + 1
for event in decoder.finish():
    counts[event.event] = counts.get(event.event, 0) + 1
elapsed = time.perf_counter() - start
end_cpu = resource.getrusage(resource.RUSAGE_SELF)
cpu = end_cpu.ru_utime - start_cpu.ru_utime + end_cpu.ru_stime - start_cpu.ru_stime
print(cpu, elapsed, end_cpu.ru_maxrss, sum(counts.values()), sorted(counts.items()))
"""


def make_input(path: Path, size: int) -> None:
    from trionet import ring

    rnd = random.Random(2024)
    frames = []
    for i in range(400):
        kind = i % 4
        if kind == 0:
            frames.append(ring.encode_print(10 + i % 15, "".join(chr(32 + rnd.randrange(95)) for _ in range(5 + i % 36))))
        elif kind == 1:
            frames.append(ring.encode_var(10 + i % 15, rnd.randrange(16384), rnd.uniform(-1e6, 1e6)))
        elif kind == 2:
            frames.append(ring.encode_offset(10 + i % 15, 10 + (i // 4) % 15))
        else:
            frames.append(ring.encode_mode(10 + i % 15, 0 if i % 8 < 4 else 127))
    with open(path, "wb") as f:
        written = 0
        while written < size:
            block = bytearray()
            while len(block) < CHUNK * 16:
                frame = bytearray(rnd.choice(frames))
                if rnd.randrange(50) == 0:
                    frame[rnd.randrange(len(frame))] ^= 1 << rnd.randrange(8)
                block += frame
            block = block[: size - written]
            f.write(block)
            written += len(block)


def run_cli(cli: str, path: Path):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    with open(path, "rb") as f, open(os.devnull, "wb") as out:
        subprocess.run([cli, "ring", "decode", "--raw"], stdin=f, stdout=out, check=True)
    elapsed = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    return cpu, elapsed


def run_package(path: Path, pythonpath: str):
    env = dict(os.environ, PYTHONPATH=pythonpath)
    done = subprocess.run([sys.executable, "-c", CONSUMER, str(path)], capture_output=True, text=True, check=True,
                          env=env)
    cpu, elapsed, rss_kib, events, kinds = done.stdout.split(" ", 4)
    return float(cpu), float(elapsed), int(rss_kib), int(events), kinds.strip()


def main() -> int:
    root = Path(__file__).resolve().parents[2]
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--megabytes", type=int, default=100)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--cli", default=os.environ.get("TRIONET_CLI", str(root / "build" / "src" / "trionet")))
    parser.add_argument("--pythonpath", default=os.environ.get("PYTHONPATH", str(root / "build" / "python")))
    args = parser.parse_args()
    size = args.megabytes * 1000 * 1000

    with tempfile.TemporaryDirectory() as scratch:
        path = Path(scratch) / "ring.bin"
        os.environ["PYTHONPATH"] = args.pythonpath
        sys.path.insert(0, args.pythonpath)
        make_input(path, size)
        cli_runs, package_runs = [], []
        for _ in range(args.runs):
            cli_runs.append(run_cli(args.cli, path))
            package_runs.append(run_package(path, args.pythonpath))
        cli_cpu = statistics.median(r[0] for r in cli_runs)
        cli_wall = statistics.median(r[1] for r in cli_runs)
        py_cpu = statistics.median(r[0] for r in package_runs)
        py_wall = statistics.median(r[1] for r in package_runs)
        rss = max(r[2] for r in package_runs)
        events = package_runs[0][3]
    mb = size / 1e6
    print(f"input: {mb:.0f} MB of ring bytes, {events} events ({package_runs[0][4]})")
    print(f"trionet ring decode --raw : CPU {cli_cpu:.2f} s ({mb / cli_cpu:.1f} MB/s), elapsed {cli_wall:.2f} s "
          f"({mb / cli_wall:.1f} MB/s)  [median of {args.runs}]")
    print(f"trionet.ring.Decoder      : CPU {py_cpu:.2f} s ({mb / py_cpu:.1f} MB/s), elapsed {py_wall:.2f} s "
          f"({mb / py_wall:.1f} MB/s)  [median of {args.runs}], peak resident memory {rss / 1024:.0f} MiB")
    print(f"package / tool throughput: {cli_cpu / py_cpu:.2f} by CPU time, {cli_wall / py_wall:.2f} by elapsed time "
          f"(target: at least 0.5)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
