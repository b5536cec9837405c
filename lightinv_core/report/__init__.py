"""Reports of a project's solution: false-colour views, tables and plots, as a PDF.

Built on matplotlib only (``Figure`` + Agg canvas, never pyplot), so it runs headless
and next to a GUI without touching its backend. See docs/report.md.

- ``write_report(project, prepared, path, ...)``: the whole PDF (``pdf.py``);
- ``render_view(patches, values, camera, ...)``: one false-colour view (``views.py``);
- ``source_table``, ``intention_table``, ... : the tables as data (``tables.py``);
- ``convergence_figure``, ``pareto_figure``: the plots (``figures.py``);
- ``daylight_section``: the daylight and energy section's numbers, tables and plans
  (``daylight.py``; designs with skylights and work planes);
- ``solution_field``: the illuminance of a saved solution (``chosen.py``);
- ``provenance``: the run that found a layout (``provenance.py``);
- ``status_table``, ``workplane_criteria``: the criteria with their verdicts
  (``criteria.py``); the room, the luminaires' data sheets and the flow layout are in
  ``room.py``, ``datasheet.py``, ``layout.py`` and ``sections.py``.
"""

from lightinv_core.report.chosen import choose_solution, solution_field
from lightinv_core.report.criteria import status_table, workplane_criteria
from lightinv_core.report.daylight import DaylightSection, daylight_section
from lightinv_core.report.figures import convergence_figure, pareto_figure
from lightinv_core.report.pdf import ReportInfo, write_report
from lightinv_core.report.provenance import Provenance, provenance
from lightinv_core.report.tables import (
    Table,
    group_table,
    intention_table,
    rules_table,
    source_table,
)
from lightinv_core.report.views import (
    CAMERAS,
    Camera,
    Outline,
    marker_legend,
    render_view,
    source_outlines,
)

__all__ = [
    "CAMERAS",
    "Camera",
    "DaylightSection",
    "Outline",
    "Provenance",
    "ReportInfo",
    "Table",
    "choose_solution",
    "convergence_figure",
    "daylight_section",
    "group_table",
    "intention_table",
    "marker_legend",
    "pareto_figure",
    "provenance",
    "render_view",
    "rules_table",
    "solution_field",
    "source_outlines",
    "source_table",
    "status_table",
    "workplane_criteria",
    "write_report",
]
