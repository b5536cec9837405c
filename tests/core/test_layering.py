"""The engine never imports the GUI stack (Qt, VTK, pyvista) or the app."""

from __future__ import annotations

import ast
import pkgutil
import re
import subprocess
import sys
from pathlib import Path

import pytest

import lightinv_core

FORBIDDEN = ("PySide6", "shiboken6", "vtk", "vtkmodules", "pyvista", "pyvistaqt", "app")
CORE = Path(lightinv_core.__file__).parent


def _imported_roots(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(), str(path))
    roots = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            roots |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            roots.add(node.module.split(".")[0])
    return roots


def test_no_core_module_imports_the_gui_stack():
    bad = {
        str(p.relative_to(CORE)): sorted(_imported_roots(p) & set(FORBIDDEN))
        for p in CORE.rglob("*.py")
    }
    assert {k: v for k, v in bad.items() if v} == {}


def test_importing_every_core_module_loads_no_gui_module():
    names = [m.name for m in pkgutil.walk_packages([str(CORE)], "lightinv_core.")]
    code = (
        "import importlib, sys\n"
        f"for m in {names!r}: importlib.import_module(m)\n"
        f"bad = [m for m in sys.modules if m.split('.')[0] in {FORBIDDEN!r}]\n"
        "print(','.join(bad))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_import_linter_contracts_hold():
    """The layer order of docs/architecture.md (pyproject's import-linter contracts)."""
    pytest.importorskip("importlinter", reason="import-linter is a dev dependency")
    tool = Path(sys.executable).parent / "lint-imports"
    out = subprocess.run([str(tool), "--no-cache"], capture_output=True, text=True, cwd=CORE.parent)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-2000:]
    assert re.search(r"Contracts: \d+ kept, 0 broken", out.stdout), out.stdout[-2000:]


def _cycles(adjacency: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    found: list[list[str]] = []
    for root in adjacency:
        if root in index:
            continue
        work = [(root, iter(adjacency[root]))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            v, edges = work[-1]
            w = next((e for e in edges if e in adjacency), None)
            if w is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    comp = []
                    while True:
                        u = stack.pop()
                        on_stack.discard(u)
                        comp.append(u)
                        if u == v:
                            break
                    if len(comp) > 1:
                        found.append(sorted(comp))
            elif w not in index:
                index[w] = low[w] = len(index)
                stack.append(w)
                on_stack.add(w)
                work.append((w, iter(adjacency[w])))
            elif w in on_stack:
                low[v] = min(low[v], index[w])
    return found


def test_no_import_cycles_between_modules():
    """No two modules of the core or the app import each other, even through others or
    inside a function (grimp, import-linter's graph, sees those too)."""
    import grimp  # import-linter's graph (the dev extra)

    graph = grimp.build_graph("lightinv_core", "app")
    adjacency = {m: graph.find_modules_directly_imported_by(m) for m in graph.modules}
    assert _cycles(adjacency) == []
    # The check finds a cycle when there is one.
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
