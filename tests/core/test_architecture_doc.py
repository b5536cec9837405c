"""docs/architecture.md's generated parts: the engine's layers (from the import-linter
contract in pyproject.toml and each module's docstring) and the registries a new kind
goes into (from the registries themselves). Rerun with LIGHTINV_WRITE_DOCS=1 to
regenerate them after a layer, a module's docstring or a registry changes."""

from __future__ import annotations

import ast
import os
import re
import tomllib
from pathlib import Path

from lightinv_core.climate.control_modes import control_mode, control_mode_names
from lightinv_core.goals import goal_specs
from lightinv_core.optimize.registry import methods
from lightinv_core.quantities import quantity_specs
from lightinv_core.scenarios import scenario_specs
from lightinv_core.scene.importers.registry import importers
from lightinv_core.sources.types import source_types

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "architecture.md"
BLOCK = re.compile(r"(<!-- generated:(\w+) -->\n)(.*?)(<!-- /generated:\2 -->)", re.S)


def _summary(module: str) -> str:
    """The first sentence of a core module's or package's docstring."""
    base = ROOT / "lightinv_core" / module
    path = base / "__init__.py" if base.is_dir() else base.with_suffix(".py")
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
    text = " ".join(doc.split("\n\n")[0].split())
    first = re.split(r"(?<=\.)\s", text, maxsplit=1)[0]
    return first.rstrip(".").replace("``", "`")


def layers() -> str:
    """The core's layers, high to low, as the import-linter contract lists them."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    contract = next(
        c for c in config["tool"]["importlinter"]["contracts"] if c["id"] == "core-layers"
    )
    rows = ["| layer | module | holds |", "|---:|---|---|"]
    for i, layer in enumerate(contract["layers"], 1):
        for name in (n.strip() for n in layer.split("|")):
            rows.append(f"| {i} | `{name}` | {_summary(name)} |")
    return "\n".join(rows)


def _cell(text: object) -> str:
    return str(text).replace("|", "\\|")


def registries() -> str:
    """One table per registry: what is registered today, by the names views show."""
    out = [
        "| source type | kind | label | electric | daylit | strength |",
        "|---|---|---|---|---|---|",
    ]
    out += [
        f"| `{type(t).__name__}` | `{t.kind}` | {t.label} | {'yes' if t.electric else 'no'} "
        f"| {'yes' if t.daylit else 'no'} | `{t.strength}` |"
        for t in source_types()
    ]
    out += ["", "| goal | label | unit | direction |", "|---|---|---|---|"]
    out += [
        f"| `{g.kind}` | {g.label} | {_cell(g.unit or '-')} | "
        f"{'maximise' if g.maximise else 'minimise'} |"
        for g in goal_specs()
    ]
    out += ["", "| quantity | label | scenario | annual band (lux) |", "|---|---|---|---|"]
    for q in quantity_specs():
        band = "-"
        if q.hours is not None:
            band = f"{q.hours.lo:g}-{q.hours.hi:g}"
            if q.hours.point_share is not None:
                band += f", point counts at {q.hours.point_share:g} of hours"
        out.append(f"| `{q.name}` | {_cell(q.label)} | {q.scenario or 'its own'} | {band} |")
    out += ["", "| scenario | label | daylit | weather year |", "|---|---|---|---|"]
    out += [
        f"| `{s.name}` | {s.label} | {'yes' if s.daylit else 'no'} | "
        f"{'yes' if s.weather else 'no'} |"
        for s in scenario_specs()
    ]
    out += ["", "| import format | suffixes | up axis | options |", "|---|---|---|---|"]
    out += [
        f"| {i.name} | {' '.join(f'`{s}`' for s in i.suffixes)} | {i.up} | "
        f"{', '.join(i.options) or '-'} |"
        for i in importers()
    ]
    out += ["", "| optimizer | label | settings |", "|---|---|---|"]
    out += [f"| `{m.name}` | {m.label} | `{m.settings.__name__}` |" for m in methods()]
    out += ["", "| control mode | label |", "|---|---|"]
    out += [f"| `{n}` | {control_mode(n).label} |" for n in control_mode_names()]
    return "\n".join(out)


PARTS = {"layers": layers, "registries": registries}


def rendered(text: str) -> str:
    return BLOCK.sub(lambda m: m[1] + PARTS[m[2]]() + "\n" + m[4], text)


def test_the_generated_parts_of_the_architecture_doc_are_current():
    text = DOC.read_text(encoding="utf-8")
    assert sorted(m[2] for m in BLOCK.finditer(text)) == sorted(PARTS)
    new = rendered(text)
    if os.environ.get("LIGHTINV_WRITE_DOCS") == "1":
        DOC.write_text(new, encoding="utf-8")
        return
    assert new == text, "docs/architecture.md is stale: rerun with LIGHTINV_WRITE_DOCS=1"
