#!/usr/bin/env python3
"""scripts/wireshark-compare skips (77, naming the folder) when tshark loads installed trionet dissectors by
itself: loading the tree's beside them is an error ("two protocols with the same description"), and a machine
with the trionet-wireshark package installed failed every comparison. A stand-in tshark reports a global Lua
plugins folder that holds the dissectors, then one that does not.

    skip_installed_test.py SOURCE_DIR
"""
import os
import stat
import subprocess
import sys
import tempfile


def run_compare(source, tshark):
    compare = os.path.join(source, "scripts", "wireshark-compare")
    return subprocess.run([sys.executable, compare, "--tshark", tshark, "--lua-dir", os.path.join(source, "wireshark"),
                           "capture.pcapng", os.devnull], capture_output=True, text=True, check=False)


def main(source):
    with tempfile.TemporaryDirectory() as work:
        plugins = os.path.join(work, "plugins")
        os.mkdir(plugins)
        tshark = os.path.join(work, "tshark")
        with open(tshark, "w", encoding="utf-8") as f:
            # -G folders as tshark prints it; any other use fails, so that a run past the check shows.
            f.write("#!/bin/sh\nif [ \"$1\" = -G ]; then printf 'Global Lua Plugins:  \\t%s\\n' '" + plugins +
                    "'; exit 0; fi\necho 'not expected' >&2; exit 9\n")
        os.chmod(tshark, stat.S_IRWXU)
        failures = []
        ran = run_compare(source, tshark)
        if ran.returncode != 2:
            failures.append("without installed dissectors the stand-in tshark must have been run: %d %s" %
                            (ran.returncode, ran.stdout + ran.stderr))
        open(os.path.join(plugins, "trionet_ring.lua"), "w").close()
        ran = run_compare(source, tshark)
        if ran.returncode != 77 or os.path.join(plugins, "trionet_ring.lua") not in ran.stdout:
            failures.append("with an installed dissector: %d %s" % (ran.returncode, ran.stdout + ran.stderr))
        for failure in failures:
            print(failure)
        return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
