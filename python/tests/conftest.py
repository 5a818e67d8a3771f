"""Shared fixtures: the `trionet` tool the package is compared with (TRIONET_CLI, else build/src/trionet)."""

import os
import shutil
import subprocess
from pathlib import Path
from typing import List

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _cli_path() -> str:
    given = os.environ.get("TRIONET_CLI")
    if given:
        return given
    built = ROOT / "build" / "src" / "trionet"
    if built.exists():
        return str(built)
    found = shutil.which("trionet")
    return found or ""


@pytest.fixture(scope="session")
def cli() -> str:
    """The path of the `trionet` tool (the tests that compare with it need it)."""
    path = _cli_path()
    if not path or not os.access(path, os.X_OK):
        pytest.fail("the trionet tool is needed: set TRIONET_CLI or build build/src/trionet")
    return path


@pytest.fixture(scope="session")
def run_cli(cli):
    """Runs the tool with arguments (and standard input), returning its standard output; fails on a
    non-zero exit status unless `status` says otherwise."""

    def run(args: List[str], stdin: bytes = b"", status: int = 0, cwd=None) -> str:
        done = subprocess.run([cli] + args, input=stdin, capture_output=True, timeout=300, cwd=cwd)
        assert done.returncode == status, (args, done.returncode, done.stderr.decode(errors="replace"))
        return done.stdout.decode()

    return run


@pytest.fixture(scope="session")
def root() -> Path:
    """The source tree."""
    return ROOT


def pytest_configure(config):
    # python-can 4.1 on Python 3.11 warns about importlib.metadata's old interface when it lists its
    # interfaces: not ours.
    config.addinivalue_line("filterwarnings", "ignore:SelectableGroups dict interface:DeprecationWarning")
