"""The type stubs (python/trionet/*.pyi) describe the package as it is: mypy's stubtest compares every stub
with the module it stands for (names, signatures, enum members), and mypy checks the examples against them."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

import trionet

PACKAGE = Path(trionet.__file__).resolve().parent
ROOT = Path(__file__).resolve().parents[2]


def mypy_or_skip():
    try:
        import mypy  # noqa: F401
    except ImportError:
        pytest.skip("mypy is not installed (Debian: apt-get install mypy): the stubs are not checked")


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    """One mypy cache for the module's runs: the standard library's stubs are read once."""
    return str(tmp_path_factory.mktemp("mypy-cache"))


def run(args):
    env = dict(os.environ, PYTHONPATH=str(PACKAGE.parent), MYPYPATH=str(PACKAGE.parent))
    return subprocess.run([sys.executable, "-m"] + args, capture_output=True, text=True, env=env, timeout=600,
                          cwd=PACKAGE.parent)


def test_every_stub_matches_its_module():
    mypy_or_skip()
    done = run(["mypy.stubtest", "trionet", "--allowlist", str(ROOT / "python" / "stubtest-allowlist.txt")])
    assert done.returncode == 0, done.stdout + done.stderr


def test_every_module_has_a_stub():
    for module in PACKAGE.glob("*.py"):
        if module.name != "__init__.py":
            assert module.with_suffix(".pyi").exists(), module.name


def test_the_examples_type_check_against_the_stubs(cache):
    mypy_or_skip()
    examples = sorted(str(p) for p in (ROOT / "examples" / "python").glob("*.py"))
    assert examples
    # python-can 4.1's can.Bus is a factory that mypy takes for its abstract base class: "abstract" is
    # python-can's false alarm, not the examples'.
    done = run(["mypy", "--cache-dir", cache, "--ignore-missing-imports",
                "--follow-imports", "silent", "--disable-error-code", "abstract"] + examples)
    assert done.returncode == 0, done.stdout + done.stderr


def stub_enums(path):
    """{class name: {member: value}} of every IntEnum class a stub declares."""
    import ast

    enums = {}
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, ast.ClassDef) and any(ast.unparse(b) == "enum.IntEnum" for b in node.bases):
            enums[node.name] = {t.targets[0].id: t.value.value for t in node.body if isinstance(t, ast.Assign)}
    return enums


def test_every_enum_in_the_stubs_has_the_runtime_members():
    import enum
    import importlib

    checked = 0
    for stub in sorted(PACKAGE.glob("*.pyi")):
        module = importlib.import_module("trionet." + stub.stem)
        runtime = {name: value for name, value in vars(module).items()
                   if isinstance(value, type) and issubclass(value, enum.IntEnum) and value.__module__ == module.__name__}
        declared = stub_enums(stub)
        assert set(declared) == set(runtime), stub.name
        for name, members in declared.items():
            assert members == {m.name: m.value for m in runtime[name]}, f"{stub.name}: {name}"
            checked += 1
    assert checked >= 25
