"""docs/python.md as printed: its Python examples are doctests, and its example commands run (the install
commands are run by scripts/fresh-debian-check --python on a fresh Debian)."""

import doctest
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import trionet

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "python.md"
PACKAGE_PARENT = str(Path(trionet.__file__).resolve().parents[1])


def test_the_pages_examples_give_what_it_prints(monkeypatch):
    monkeypatch.chdir(ROOT)
    text = PAGE.read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 6
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    globs = {}
    for number, block in enumerate(blocks):
        test = parser.get_doctest(block, globs, f"docs/python.md block {number + 1}", str(PAGE), 0)
        runner.run(test, clear_globs=False)
        globs = test.globs  # later blocks use the names of earlier ones, as a reader would
    result = runner.summarize(verbose=False)
    assert result.failed == 0 and result.attempted > 20


def example_commands():
    text = PAGE.read_text()
    section = text.split("## Examples", 1)[1].split("\n## ", 1)[0]
    commands = []
    for block in re.findall(r"```sh\n(.*?)```", section, re.S):
        commands += [line for line in block.splitlines() if line.strip()]
    return commands


@pytest.mark.parametrize("command", example_commands())
def test_the_pages_example_commands_run(command):
    assert command.startswith("python3 ")
    env = dict(os.environ, PYTHONPATH=PACKAGE_PARENT)
    done = subprocess.run([sys.executable] + command.split()[1:], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
