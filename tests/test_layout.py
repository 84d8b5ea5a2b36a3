"""The layout's rules, read from the code itself: rerun only in teach/observe/, mujoco only in
teach/sim/, and no file I/O in the session machine or its learning."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from conftest import ROOT

TEACH = ROOT / "teach"
MODULES = sorted(TEACH.rglob("*.py"))
FILE_CALLS = {"open", "read_text", "write_text", "read_bytes", "write_bytes", "mkdir", "unlink", "rmdir", "touch",
              "copyfile", "rmtree", "write_demonstration", "read_demonstration", "write_tree", "load_domain",
              "atomic_write_text"}


def imported(path: Path) -> set[str]:
    """The top-level packages a module imports (anywhere in it, lazily too)."""
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module.split(".")[0])
    return names


@pytest.mark.parametrize(("package", "home"), [("rerun", "observe"), ("mujoco", "sim")])
def test_a_heavy_library_is_imported_in_its_package_only(package, home):
    outside = [str(p.relative_to(ROOT)) for p in MODULES if package in imported(p) and p.parent.name != home]
    assert outside == []
    assert any(package in imported(p) for p in MODULES if p.parent.name == home)  # the check can see it


@pytest.mark.parametrize("name", ["session/machine.py", "session/learning.py", "session/commands.py",
                                  "session/describe.py", "messages.py"])
def test_the_session_machine_does_no_file_io(name):
    tree = ast.parse((TEACH / name).read_text(encoding="utf-8"))
    calls = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            calls.add(node.func.id)
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and not ast.unparse(node.func.value).endswith("store"):  # the SessionStore does the I/O
            calls.add(node.func.attr)
    assert calls & FILE_CALLS == set()
    assert imported(TEACH / name) & {"os", "shutil", "io", "tempfile"} == set()
