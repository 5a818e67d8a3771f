#!/usr/bin/env python3
"""The keypad emulator drawn in a real terminal (tmux): nothing wraps and the drawing never repeats.

    keypad_terminal_tmux.py TRIONET

Runs `trionet ring simulate example1 --interactive` and `trionet ring join PTY --as keypad` in tmux panes of
80 x 24 and 60 x 20 (and one resized from 80 x 24 to 60 x 20 while it runs), types keys, feeds the keypad
display text and keypad offset, and reads the screen and its scrollback with capture-pane -J (which joins a
wrapped line back into one; after the resize, the screen only, as tmux keeps what it pushed out at the old
size). Each must show:
  - no line of more than width - 1 characters (a longer one wrapped, or filled the last column);
  - each title exactly once, scrollback included (a redraw that went wrong leaves copies above);
  - the drawing itself: the boxed display with the text sent to it, the help, the events of the keys typed.
Exit status: 0 all pass, 1 a check failed, 77 tmux is not installed (the test is then skipped).
"""
import os
import pty
import shutil
import subprocess
import sys
import tempfile
import time
import tty

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
    return condition


class Pane:
    """A detached tmux session of its own (own server socket, no configuration) running one command."""

    def __init__(self, command, columns, rows, pass_fds=()):
        self.directory = tempfile.mkdtemp(prefix="trionet-tmux-")
        self.socket = os.path.join(self.directory, "socket")
        self.size = (columns, rows)
        self.tmux(["-f", "/dev/null", "new-session", "-d", "-s", "keypad", "-x", str(columns), "-y", str(rows),
                   command], pass_fds=pass_fds)
        self.tmux(["set-option", "-g", "status", "off"])
        self.tmux(["set-option", "-g", "history-limit", "5000"])

    def tmux(self, arguments, pass_fds=()):
        return subprocess.run(["tmux", "-S", self.socket] + arguments, check=True, capture_output=True, text=True,
                              pass_fds=pass_fds).stdout

    def keys(self, *keys):
        for key in keys:
            self.tmux(["send-keys", "-t", "keypad", key])
            time.sleep(0.15)

    def resize(self, columns, rows):
        self.tmux(["resize-window", "-t", "keypad", "-x", str(columns), "-y", str(rows)])
        self.size = (columns, rows)

    def screen(self, history=True):
        """The screen and its scrollback (`history`), wrapped lines joined, trailing empty lines dropped."""
        lines = self.tmux(["capture-pane", "-p", "-J"] + (["-S", "-"] if history else []) + ["-t", "keypad"])
        lines = lines.split("\n")
        while lines and not lines[-1].strip():
            lines.pop()
        return lines

    def wait_for(self, text, seconds=10):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            if any(text in line for line in self.screen()):
                return True
            time.sleep(0.1)
        return False

    def close(self):
        subprocess.run(["tmux", "-S", self.socket, "kill-server"], capture_output=True)
        shutil.rmtree(self.directory, ignore_errors=True)


def check_screen(name, pane, titles, must_show, history=True):
    before = len(failures)
    columns, rows = pane.size
    lines = pane.screen(history)
    where = "%s at %d x %d" % (name, columns, rows)
    long_lines = [line for line in lines if len(line) > columns - 1]
    for line in long_lines[:3]:
        check(False, "%s: a line of %d characters (wrapped): %r" % (where, len(line), line))
    check(len(long_lines) <= 3, "%s: %d more lines too long" % (where, len(long_lines) - 3))
    for title in titles:
        count = sum(1 for line in lines if line.rstrip().endswith(title))
        check(count == 1, "%s: the title %r appears %d times" % (where, title, count))
    for text in must_show:
        check(any(text in line for line in lines), "%s: %r is not on the screen" % (where, text))
    if len(failures) > before:
        print("%s, the screen:\n%s" % (where, "\n".join("    |" + line for line in lines)))


def simulate(trionet, columns, rows, resize_to=None):
    pane = Pane("%s ring simulate example1 --interactive" % trionet, columns, rows)
    try:
        if not check(pane.wait_for("keypad 2 (node 3)"), "simulate: no drawing at %d x %d" % (columns, rows)):
            return
        pane.wait_for("SPEED:")
        # Enough keys for more events than the screen has lines; Tab moves to keypad 2.
        pane.keys("1", "u", "y", "u", "u", "d", "Tab", "2", "d", "d", "u", "y")
        if resize_to:
            # The terminal keeps what it pushed out at the old size: check the screen only.
            pane.resize(*resize_to)
            pane.keys("u")
        time.sleep(1.0)
        check_screen("ring simulate example1 --interactive" + (" (resized)" if resize_to else ""), pane,
                     ["keypad 1 (node 2)", "keypad 2 (node 3)"],
                     ["+--------------------+", "SPEED:", "keys:", "t: stop", "keypad 2: key"],
                     history=resize_to is None)
        pane.keys("q")
    finally:
        pane.close()


def join_keypad(trionet, columns, rows):
    master, slave = pty.openpty()
    tty.setraw(slave)
    port = os.ttyname(slave)
    pane = Pane("%s ring join %s --as keypad" % (trionet, port), columns, rows)
    try:
        title = "trionet keypad on " + port
        if not check(pane.wait_for(title), "ring join --as keypad: no drawing at %d x %d" % (columns, rows)):
            return
        os.write(master, bytes.fromhex("8b0288"))  # SEND(10,2,11): keypad offset 2 hops
        text = b"\x0cSPEED: 1200 mm/s\r\nLENGTH: 2500.0 mm"  # clear, then both display lines
        os.write(master, bytes([0x89]) + text + bytes([0x88]))
        pane.wait_for("LENGTH:")
        pane.keys("1", "2", "u", "d", "c", "y", "n", "s", "t", "1", "2", "3")
        time.sleep(1.0)
        check_screen("ring join --as keypad", pane, [title],
                     ["|SPEED: 1200 mm/s    |", "|LENGTH: 2500.0 mm   |", "network mode", "keys:", "key="])
        pane.keys("q")
        time.sleep(0.5)
    finally:
        pane.close()
        os.close(master)
        os.close(slave)


def main(argv):
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    if shutil.which("tmux") is None:
        print("SKIPPED: tmux is not installed (Debian: apt-get install tmux)")
        return 77
    trionet = os.path.abspath(argv[0])
    for columns, rows in ((80, 24), (60, 20)):
        simulate(trionet, columns, rows)
        join_keypad(trionet, columns, rows)
    simulate(trionet, 80, 24, resize_to=(60, 20))
    for f in failures:
        print("FAIL: " + f)
    if failures:
        return 1
    print("keypad emulator in tmux at 80 x 24, 60 x 20 and resized: no line wraps, every title once")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
