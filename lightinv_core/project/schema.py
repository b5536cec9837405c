"""The published JSON Schema of project files (docs/project.schema.json).

Derived from the same specs as reading and writing (``TOP`` and ``FILE_SPECS``), so an
editor that knows the schema completes field names, shows their meaning and units and
flags bad values as LightInv's reader would. The reader still checks what a schema cannot
say (unique names, rules naming sources that exist, min <= max, the scene's groups).
"""

from __future__ import annotations

import json
from typing import Any

from lightinv_core.fields import json_schema
from lightinv_core.project.model import FILE_SPECS, SCHEMA, TOP

SCHEMA_FILE = "project.schema.json"
"""Its name in docs/."""


def project_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of a LightInv project file of this ``SCHEMA``."""
    out = json_schema(
        TOP,
        FILE_SPECS,
        title=f"LightInv project file, schema {SCHEMA}",
        description="A LightInv design, the scene it is on, run settings and saved "
        "results (docs/project-file.md). Generated from lightinv_core's field "
        "declarations: do not edit by hand.",
    )
    out["properties"]["schema"]["const"] = SCHEMA
    return out


def project_schema_text() -> str:
    """``project_schema()`` as the text of docs/project.schema.json."""
    return json.dumps(project_schema(), indent=2, ensure_ascii=False) + "\n"
