#!/usr/bin/env python3
"""Checks tshark's packet list (the one-line summary of every frame) with the dissectors of wireshark/.

    check_summary.py --lua-dir DIR CAPTURE EXPECTED.txt

EXPECTED.txt has one line per frame, as tshark prints it with
-T fields -e frame.number -e _ws.col.Source -e _ws.col.Destination -e _ws.col.Protocol -e _ws.col.Info
(tab-separated). Every line must be equal. tshark runs with an empty home directory, so that no personal
plugin or preference changes what it shows.

Exit status: 0 equal, 1 a difference (a diff is printed), 2 a tool failure, 77 tshark is not installed or
loads installed trionet dissectors by itself.
"""
import difflib
import os
import shutil
import subprocess
import sys
import tempfile

DISSECTORS = ("trionet_ring.lua", "trionet_can.lua", "trionet_genius.lua")
COLUMNS = ("frame.number", "_ws.col.Source", "_ws.col.Destination", "_ws.col.Protocol", "_ws.col.Info")


def installed_dissectors(tshark, environment):
    """The trionet dissectors in a Lua plugin folder that tshark loads by itself (the trionet-wireshark
    package's): the tree's cannot be loaded beside them (two protocols of one name), so the check is skipped."""
    folders = subprocess.run([tshark, "-G", "folders"], capture_output=True, text=True, errors="replace",
                             env=environment, check=False).stdout
    found = []
    for line in folders.splitlines():
        name, _, path = line.partition(":")
        if "Lua Plugins" in name:
            found += [os.path.join(path.strip(), d) for d in DISSECTORS if os.path.isfile(os.path.join(path.strip(), d))]
    return found


def main(argv):
    if len(argv) != 4 or argv[0] != "--lua-dir":
        print(__doc__, file=sys.stderr)
        return 2
    lua_dir, capture, expected_path = argv[1:]
    tshark = shutil.which("tshark")
    if tshark is None:
        print("SKIPPED: tshark is not installed (Debian: apt-get install tshark)")
        return 77
    command = [tshark, "-r", capture, "-T", "fields", "-E", "separator=/t"]
    for name in DISSECTORS:
        command += ["-X", "lua_script:" + os.path.join(lua_dir, name)]
    for column in COLUMNS:
        command += ["-e", column]
    with tempfile.TemporaryDirectory() as home:
        environment = dict(os.environ, HOME=home)
        installed = installed_dissectors(tshark, environment)
        if installed:
            print("SKIPPED: tshark loads installed trionet dissectors by itself (%s): the tree's cannot be loaded "
                  "beside them" % ", ".join(installed))
            return 77
        ran = subprocess.run(command, capture_output=True, text=True, env=environment)
    if ran.returncode != 0:
        print("tshark failed (status %d):\n%s" % (ran.returncode, ran.stderr))
        return 2
    with open(expected_path, encoding="utf-8") as f:
        expected = f.read().splitlines()
    actual = ran.stdout.splitlines()
    if actual != expected:
        print("%s: tshark's packet list differs from %s:" % (capture, expected_path))
        for line in difflib.unified_diff(expected, actual, "expected", "tshark", lineterm=""):
            print(line)
        return 1
    print("%s: %d frames, Source, Destination, Protocol and Info as expected" % (os.path.basename(capture),
                                                                                  len(actual)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
