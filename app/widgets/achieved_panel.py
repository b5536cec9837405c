"""The "Achieved" tab: every lighting intention of the design on screen, live.

For each bound of each intention: what is required, what the design as shown (hand
edits, a dragged source, a loaded result) achieves on every patch of the intention,
and whether it holds (to the tolerance the optimiser judges with). It refreshes with
the light, so dragging a source shows the desks' average and U0 change as it moves.
Intentions on a work plane read its grid points (EN 12464-1: Em the plain mean). Each
intention is judged in its scenario (``LayoutDaylight.checks``): design, night (the
luminaires alone), overcast (the CIE overcast sky) or, for DA, UDI and sDA, the
occupied hours of the weather year.
"""

from __future__ import annotations

from typing import NamedTuple

from PySide6 import QtGui, QtWidgets

from app.document import Document
from app.widgets.numbers import distinct
from app.widgets.observer_dgp_box import ObserverDgpBox
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Bound, Scenario
from lightinv_core.quantities import level_name, quantity_spec
from lightinv_core.scenarios import is_scenario, scenario_spec

COLUMNS = ("intention", "scenario", "bound", "required", "achieved", "units", "")
OK, NOT_OK, UNKNOWN = "met", "not met", "cannot tell"
LABELS = {
    Bound.MIN: "min ≥",
    Bound.MAX: "max ≤",
    Bound.AVERAGE: "average ≥",
    Bound.UNIFORMITY: "U0 ≥",
    Bound.MAX_AVERAGE: "average ≤",
}


class Row(NamedTuple):
    """One bound of one intention as the tab lists it: ``met`` None when it cannot be
    judged (``achieved`` then says why, e.g. an unreadable weather file)."""

    intention: str
    bound: str
    required: str
    achieved: str
    units: str
    met: bool | None
    scenario: str


class AchievedPanel(QtWidgets.QWidget):
    """Required against achieved for every intention bound of the design on screen, each
    in its intention's scenario (design, night, overcast, or the weather year)."""

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        lay = QtWidgets.QVBoxLayout(self)
        self.summary = QtWidgets.QLabel()
        self.summary.setWordWrap(True)
        lay.addWidget(self.summary)
        self.table = QtWidgets.QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(COLUMNS)
        self.table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
        self.table.verticalHeader().hide()
        lay.addWidget(self.table)
        self.observer_dgp = ObserverDgpBox()  # per eye, when a dgp intention asks
        lay.addWidget(self.observer_dgp)
        self._below = QtWidgets.QSpacerItem(0, 0)  # takes the rest while the box shows
        lay.addItem(self._below)
        self._daylight = None  # the layout's light the rows were read from
        # Every design edit relights once an operator exists (lightingChanged follows
        # designChanged); before it, only the scene's arrival matters.
        doc.lightingChanged.connect(self.refresh)
        doc.sceneChanged.connect(self.refresh)
        self.refresh()

    def rows(self) -> list[Row]:
        """The bounds of every intention judged on the design as written, in its
        scenario (``LayoutDaylight.checks``)."""
        d = self.doc
        ld = None
        self._missing = ""  # why the light to judge them is not there (refresh says it)
        if d.project is None or not d.design.intentions:
            return []
        if d.design_field() is not None:
            try:
                ld = d.layout_daylight()
            except LightInvError as exc:  # e.g. the clear glazing's light still being traced
                ld, self._missing = None, str(exc)
        self._daylight = ld
        if ld is None:
            return []
        out = []
        for it in d.design.intentions:
            try:
                checks = ld.checks(it)
            except LightInvError as exc:  # e.g. no readable weather year, no solar altitude,
                # its plane not in this scene: a grey row that says why, not a silent gap
                out.append(Row(it.name, "-", "-", str(exc), "", None, str(it.scenario)))
                continue
            for chk in checks:
                achieved, required = distinct(float(chk.value[0]), float(chk.limit))
                spec = quantity_spec(it.quantity)
                if spec.levels:  # EN 17037's score: say the level too, "2.43 (medium)"
                    achieved += f" ({level_name(spec, float(chk.value[0]))})"
                    required += f" ({level_name(spec, float(chk.limit))})"
                units = "" if chk.bound == Bound.UNIFORMITY else chk.units
                out.append(
                    Row(
                        it.name,
                        LABELS[chk.bound],
                        required,
                        achieved,
                        units,
                        bool(chk.met[0]),
                        str(it.scenario),
                    )
                )
        return out

    def refresh(self) -> None:
        self._daylight = None
        rows = self.rows()
        self.observer_dgp.show_figures(getattr(self._daylight, "glared", None))
        d = self.doc
        if d.project is None or d.design_field() is None:
            self.summary.setText("Lighting appears once the radiosity operator is ready.")
        elif not d.design.intentions:
            self.summary.setText(
                "No lighting intentions yet: double-click a group in the tree to add one."
            )
        elif not rows and self._missing:
            self.summary.setText(f"The intentions cannot be judged yet: {self._missing}.")
        else:
            bad = sum(r.met is False for r in rows)
            unknown = sum(r.met is None for r in rows)
            text = (
                "The design on screen meets every lighting intention."
                if not bad
                else f"The design on screen misses {bad} of {len(rows)} bounds (red)."
            )
            if unknown:
                why = next(r.achieved for r in rows if r.met is None)
                judged = len(rows) - unknown  # the bounds judged
                text = (
                    f"{unknown} intention{'s' * (unknown != 1)} cannot be judged (grey): {why}"
                    + (f"\nThe others miss {bad} of {judged} bounds (red)." if bad else "")
                )
            self.summary.setText(text + self._scenario_note(rows))
        self._name_columns(rows)
        self.table.setRowCount(len(rows))
        colours = {
            True: QtGui.QColor("#d9f2d9"),
            False: QtGui.QColor("#fbd5d5"),
            None: QtGui.QColor("#e4e4e4"),
        }
        for r, row in enumerate(rows):
            status = {True: OK, False: NOT_OK, None: UNKNOWN}[row.met]
            cells = (
                row.intention,
                row.scenario,
                row.bound,
                row.required,
                row.achieved,
                row.units,
                status,
            )
            for c, text in enumerate(cells):
                item = QtWidgets.QTableWidgetItem(text)
                item.setBackground(colours[row.met])
                self.table.setItem(r, c, item)
        self.table.resizeColumnsToContents()
        # With the glare box below, the intentions take only their rows' height.
        fit = self.table.horizontalHeader().height() + 4
        fit += sum(self.table.rowHeight(r) for r in range(self.table.rowCount()))
        boxed = self.observer_dgp.isVisibleTo(self)
        self.table.setMaximumHeight(fit if boxed else 16777215)
        grow = QtWidgets.QSizePolicy.Expanding if boxed else QtWidgets.QSizePolicy.Minimum
        self._below.changeSize(0, 0, QtWidgets.QSizePolicy.Minimum, grow)
        self.layout().invalidate()

    def _name_columns(self, rows: list[Row]) -> None:
        """Head the achieved column with the scenario its values are in: the desk's
        figures differ between tabs (the view's design scenario, the night an EN 12464-1
        preset is judged in), and the column says which light it read."""
        scenarios = {r.scenario for r in rows}
        where = next(iter(scenarios)) if len(scenarios) == 1 else "its scenario"
        achieved = f"achieved (in {where})"
        self.table.setHorizontalHeaderLabels([achieved if c == "achieved" else c for c in COLUMNS])

    def _scenario_note(self, rows: list[Row]) -> str:
        """Why a figure here differs from the view's and the work-plane table's: they
        show the design scenario, a row here its intention's."""
        design = str(Scenario.DESIGN)
        others = sorted({r.scenario for r in rows if is_scenario(r.scenario)} - {design})
        if not others:
            return ""
        named = "; ".join(scenario_spec(s).label for s in others)
        return (
            f"\nJudged in each intention's scenario ({named}); the view and the work-plane "
            f"table show the {design} scenario."
        )
