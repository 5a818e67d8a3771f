"""A ring of two: trionet.ring.MotionCoordinator on a pty through pyserial, and `trionet ring join --as mc` on the
other end of the pty pair (socat makes the pair, as README.md's live examples do)."""

import os
import shutil
import subprocess
import time

import pytest
import serial

from trionet import ring


@pytest.fixture
def pty_pair(tmp_path):
    socat = shutil.which("socat")
    if socat is None:
        pytest.skip("socat is not installed (Debian: apt-get install socat): it makes the pty pair")
    a, b = tmp_path / "ring-a", tmp_path / "ring-b"
    process = subprocess.Popen([socat, f"pty,raw,echo=0,link={a}", f"pty,raw,echo=0,link={b}"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 5
    while not (a.exists() and b.exists()) and time.monotonic() < deadline:
        time.sleep(0.01)
    try:
        assert a.exists() and b.exists(), "socat made no pty pair"
        yield str(a), str(b)
    finally:
        process.terminate()
        process.wait(timeout=5)


def test_a_python_node_and_ring_join_exchange_vrs_and_text(cli, pty_pair):
    mine, theirs = pty_pair
    with serial.Serial(mine, baudrate=125000, timeout=0) as port:
        mc = ring.MotionCoordinator()
        link = ring.SerialLink(mc, port)
        join = subprocess.Popen([cli, "ring", "join", theirs, "--as", "mc"], stdin=subprocess.PIPE,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            join.stdin.write("send 10 200 99\nprint 10 HI\n")
            join.stdin.flush()
            assert link.run(10.0, until=lambda: mc.vr[200] == 99 and mc.characters_waiting == 2)
            assert [mc.get(4), mc.get(4)] == [ord("H"), ord("I")]
            assert mc.send(10, 201, 7.5)  # to the tool's node
            assert mc.send(11, 202, 1.25)  # two hops: the tool forwards it back round to this node
            assert link.run(10.0, until=lambda: mc.vr[202] == 1.25)
            link.run(0.2)
            join.stdin.write("vr 201\nquit\n")
            join.stdin.flush()
            out, err = join.communicate(timeout=20)
        finally:
            if join.poll() is None:
                join.kill()
                join.wait()
    assert join.returncode == 0, err
    assert 'vr_write vr=201 value=7.5 status="ok"' in out
    assert "vr vr=201 value=7.5" in out
    assert mc.counters()["variables_written"] == 2 and mc.counters()["frame_errors"] == 0
    assert mc.forwarding_counters()["messages_sent"] == 2 and mc.netstat == 0
    assert link.bytes_out == 32 and link.bytes_in >= 32


def test_a_serial_link_counts_an_idle_line_in_a_message():
    class Port:
        """Half a message, then nothing."""

        def __init__(self):
            self.data = ring.encode_print(10, "HELLO")[:-1]
            self.timeout = 0
            self.written = b""

        @property
        def in_waiting(self):
            return len(self.data)

        def read(self, n):
            out, self.data = self.data[:n], self.data[n:]
            return out

        def write(self, data):
            self.written += data

    mc = ring.MotionCoordinator()
    link = ring.SerialLink(mc, Port(), idle_seconds=0.01)
    assert link.pump() == 6 and mc.in_message
    time.sleep(0.02)
    link.pump()
    assert not mc.in_message and mc.counters()["frame_errors"] == 1
