"""The `test` extra of pyproject.toml is what the tests need: every third-party module they import (and
the benchmark modules they load) is in it, at the version python/ci pins in requirements-ci.txt, so that
`pip install "./python[test]"` followed by `pytest` passes and skips nothing."""

import ast
import re
import sys
from pathlib import Path

import pytest

tomllib = pytest.importorskip("tomllib")  # Python >= 3.11, as the extra's pins

HERE = Path(__file__).resolve().parent
PYTHON = HERE.parent
# Import names that differ from their distribution's name, and modules that come with the package itself.
DISTRIBUTION = {"numpy": "numpy", "scipy": "scipy", "h5py": "h5py", "pytest": "pytest", "mypy": "mypy",
                "imufusion": "imufusion"}
PROVIDED = {"quatprop", "numpy"}  # numpy: the package's own dependency


def pins(lines):
    """{name: version} of `name==version` requirements (comments and blank lines skipped)."""
    out = {}
    for line in lines:
        line = line.split("#", 1)[0].strip()
        if line:
            m = re.fullmatch(r"([A-Za-z0-9_.-]+)==([0-9][0-9A-Za-z.]*)", line)
            assert m, f"not pinned exactly: {line!r}"
            out[m.group(1).lower()] = m.group(2)
    return out


def imported(path, seen):
    """Top-level modules `path` imports (or asks `pytest.importorskip` for), following the imports of the
    benchmark modules the tests load."""
    if path in seen:
        return set()
    seen.add(path)
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.split(".")[0])
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr == "importorskip" and node.args and isinstance(node.args[0], ast.Constant)):
            names.add(node.args[0].value.split(".")[0])  # a test that would be skipped without it
    local = set()
    found = set()
    for name in names:
        for folder in (HERE, PYTHON / "benchmarks"):
            if (folder / f"{name}.py").is_file():
                local.add(name)
                found |= imported(folder / f"{name}.py", seen)
    return (names | found) - local


def test_the_test_extra_covers_the_tests_imports_at_the_ci_pins():
    extra = pins(tomllib.loads((PYTHON / "pyproject.toml").read_text())["project"]["optional-dependencies"]["test"])
    ci = pins((PYTHON / "requirements-ci.txt").read_text().splitlines())
    seen = set()
    modules = set()
    for test in sorted(HERE.glob("test_*.py")):
        modules |= imported(test, seen)
    third_party = {m for m in modules if m not in sys.stdlib_module_names and m not in PROVIDED}
    unknown = third_party - set(DISTRIBUTION)
    assert not unknown, f"tests import {sorted(unknown)}: add them to the test extra and to DISTRIBUTION"
    needed = {DISTRIBUTION[m] for m in third_party}
    assert needed == set(extra), f"the test extra is {sorted(extra)}, the tests import {sorted(needed)}"
    for name, version in extra.items():
        assert ci.get(name) == version, f"{name}: the extra pins {version}, requirements-ci.txt {ci.get(name)}"
    assert "h5py" in needed  # test_broad.py's reader (the failure)
