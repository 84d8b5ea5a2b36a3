"""The layout's rules, read from the code itself: imports between the packages of teach/ point
down their layers only, rerun only in teach/observe/, mujoco only in teach/sim/, and no file I/O
in the session machine or its learning."""

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


# --- the layers: an import points down only -------------------------------------------------------

LAYERS: list[tuple[str, ...]] = [
    ("errors", "limits", "display"),
    ("fsutil", "protect", "children"),
    ("lock", "bt"),
    ("domain",),
    ("demos", "symbolic", "generations"),
    ("open_demonstration",),
    ("replay",),
    ("learn",),
    ("evaluate",),
    ("observe",),
    ("sim",),
    ("world",),
    ("messages", "text"),  # where the message catalogue goes when it leaves session/ (either name)
    ("dialogue",),
    ("session",),
    ("voice",),
    ("terminal", "review"),
    ("commands",),
    ("cli",),
]
"""The packages and top-level modules of teach/, bottom to top: a module may import from its own
package and from the layers below it, never from its own layer's other members or from above
(imports inside functions and under TYPE_CHECKING count too). docs/architecture.md shows the same
list; a new package must be placed here."""

KNOWN_UPWARD: dict[tuple[str, str], str] = {}
"""Arrows that still run up, each with the reason and who removes it. This list only shrinks:
delete a line when its arrow is gone; never add one."""


def _unit(module: str) -> str:
    """The layer member a module of teach belongs to: its package, or the top-level module itself."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def teach_imports(text: str, package: str) -> set[str]:
    """The modules of teach a file of ``package`` imports, anywhere in it (``from teach import x``
    names teach.x; relative imports are resolved)."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Import):
            found |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            parts = package.split(".")[:len(package.split(".")) + 1 - node.level] if node.level else []
            base = ".".join([*parts, *([node.module] if node.module else [])])
            found |= {f"{base}.{alias.name}" if base == "teach" else base for alias in node.names}
    return {name for name in found if name.startswith("teach.")}


def upward_arrows() -> list[tuple[str, str, str]]:
    """Every import of a module in the same layer (another member) or above: (file, its unit, the unit)."""
    layer = {unit: number for number, members in enumerate(LAYERS) for unit in members}
    arrows = []
    for path in MODULES:
        source = _unit(".".join(path.relative_to(ROOT).with_suffix("").parts))
        if source in ("", "__init__"):
            continue
        assert source in layer, f"{path.relative_to(ROOT)}: {source!r} is in no layer of LAYERS: place it"
        package = ".".join(path.relative_to(ROOT).parts[:-1])
        imported_units = {_unit(name) for name in teach_imports(path.read_text(encoding="utf-8"), package)}
        for target in sorted(imported_units - {source, ""}):
            assert target in layer, f"{path.relative_to(ROOT)} imports {target!r}, which is in no layer of LAYERS"
            if layer[target] >= layer[source]:
                arrows.append((str(path.relative_to(ROOT)), source, target))
    return arrows


def test_imports_between_packages_point_down_their_layers():
    unexpected = [f"{file} ({source}) imports teach.{target}" for file, source, target in upward_arrows()
                  if (file, target) not in KNOWN_UPWARD]
    assert unexpected == []
    gone = set(KNOWN_UPWARD) - {(file, target) for file, _source, target in upward_arrows()}
    assert gone == set(), "delete these from KNOWN_UPWARD: their arrows are gone"


def test_the_layer_check_sees_imports_in_functions_and_relative_ones():
    assert teach_imports("def later():\n    from teach.session.machine import SessionManager\n",
                         "teach.learn") == {"teach.session.machine"}
    assert teach_imports("from ..world import protocol\nfrom . import goal\nfrom teach import limits\n",
                         "teach.learn") == {"teach.world", "teach.learn", "teach.limits"}
    assert teach_imports("if TYPE_CHECKING:\n    import teach.session\n", "teach.bt") == {"teach.session"}


# --- no circle between files -------------------------------------------------------------------

KNOWN_CIRCLES: dict[frozenset[str], str] = {}
"""Circles of imports between files that still exist, each with the reason. Only shrinks."""


def module_imports() -> dict[str, set[str]]:
    """Each module of teach and the modules of teach it imports (anywhere in it)."""
    names = {".".join(p.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__"): p for p in MODULES}
    graph: dict[str, set[str]] = {}
    for name, path in names.items():
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        found = teach_imports(path.read_text(encoding="utf-8"), package)
        graph[name] = {other for other in found if other in names and other not in (name, "teach")}
    return graph


def circles(graph: dict[str, set[str]]) -> list[frozenset[str]]:
    """The strongly connected groups of more than one module (Tarjan's algorithm, iteratively)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[frozenset[str]] = []
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        while work:
            node, targets = work[-1]
            target = next(targets, None)
            if target is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    group = {stack.pop()}
                    while node not in group:
                        group.add(stack.pop())
                    if len(group) > 1:
                        found.append(frozenset(group))
            elif target not in index:
                index[target] = low[target] = len(index)
                stack.append(target)
                work.append((target, iter(sorted(graph[target]))))
            elif target in stack:
                low[node] = min(low[node], index[target])
    return found


def test_no_files_import_each_other_in_a_circle():
    assert [sorted(group) for group in circles(module_imports()) if group not in KNOWN_CIRCLES] == []


def test_the_circle_check_sees_a_circle():
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [frozenset({"a", "b", "c"})]


def test_the_architecture_document_shows_the_layers():
    shown = " < ".join(" ".join(members) for members in LAYERS)
    assert shown in " ".join((ROOT / "docs" / "architecture.md").read_text(encoding="utf-8").split())


@pytest.mark.parametrize(("package", "home"), [("rerun", "observe"), ("mujoco", "sim")])
def test_a_heavy_library_is_imported_in_its_package_only(package, home):
    outside = [str(p.relative_to(ROOT)) for p in MODULES if package in imported(p) and p.parent.name != home]
    assert outside == []
    assert any(package in imported(p) for p in MODULES if p.parent.name == home)  # the check can see it


@pytest.mark.parametrize("name", ["session/machine.py", "session/learning.py", "session/commands.py",
                                  "session/describe.py", "messages.py", "session/record.py", "session/turn.py",
                                  "session/showing.py", "session/definitions.py", "session/running.py",
                                  "session/resumed.py", "session/relearning.py",
                                  "session/arguments.py", "session/published.py", "session/compat.py",
                                  "session/vocabulary.py", "session/guiding.py", "session/hand.py",
                                  "open_demonstration.py"])
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
