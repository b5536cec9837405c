"""The run panel: the project's optimisation settings, Run / Cancel, live status and the
convergence plots.

Settings are the project's (``OptimizerSettings`` and the primary goal): editing a field
writes it to the document at once, so a saved project runs the same from the command
line. The number of seeds is the panel's own: several seeds run the same problem that
many times (the paper's experiment 4) and are not saved.

The method list follows the open design: a method that cannot run on it (NSGA-II on a
design with one goal: ``MethodSpec.refusal``) is listed greyed out, its tooltip saying
why. A front method names the two goals it trades, by their labels.
"""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets

from app.document import Document
from app.view.convergence_plot import ConvergencePlot
from app.view.scatter_axes import goal_axis_label
from app.widgets.elided_label import ElidedLabel
from lightinv_core.errors import LightInvError
from lightinv_core.goals import goal_spec, goal_specs
from lightinv_core.optimize.fronts import front_pair
from lightinv_core.optimize.method import MethodSpec
from lightinv_core.optimize.registry import get_method, methods


def sweep_count(method: MethodSpec, design) -> tuple[str, str] | None:
    """(label, settings field) of a front method's run or point count; None for one
    best layout (the panel's seeds) or a front method without one."""
    return method.count_setting if method.finds_front(design) else None


class RunPanel(QtWidgets.QWidget):
    """Settings, buttons and progress of one optimisation run at a time."""

    runRequested = QtCore.Signal()
    cancelRequested = QtCore.Signal()

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        lay = QtWidgets.QHBoxLayout(self)
        left = QtWidgets.QWidget()
        left.setMaximumWidth(360)
        form = QtWidgets.QFormLayout(left)
        form.setContentsMargins(0, 0, 0, 0)
        form.setVerticalSpacing(4)
        # What to run, Run and what it is doing first, the limits below: on a 1366 x 768
        # laptop the dock is about 300 px high and Run sat under six rows of settings,
        # reached by scrolling (issue #29).
        self.method = QtWidgets.QComboBox()
        for m in methods():
            self.method.addItem(m.label, m.name)
        form.addRow("Method", self.method)
        self.goal = QtWidgets.QComboBox()
        form.addRow("Goal", self.goal)
        self.trades = QtWidgets.QLabel("")
        self.trades.setWordWrap(True)
        form.addRow(self.trades)
        buttons = QtWidgets.QHBoxLayout()
        self.run_button = QtWidgets.QPushButton("Run")
        self.cancel_button = QtWidgets.QPushButton("Cancel")
        self.cancel_button.setEnabled(False)
        buttons.addWidget(self.run_button)
        buttons.addWidget(self.cancel_button)
        form.addRow(buttons)
        self.state = QtWidgets.QLabel("Ready")
        self.state.setWordWrap(True)
        form.addRow(self.state)
        # Two lines (evaluations and speed; sub-run, best and search penalty), elided to
        # the column (whole on hover): cut mid-number at 1366 px before.
        self.counters = ElidedLabel("")
        form.addRow(self.counters)
        limits = QtWidgets.QGridLayout()
        limits.setContentsMargins(0, 0, 0, 0)
        self.max_evals = QtWidgets.QSpinBox(maximum=100_000_000, singleStep=1000)
        self.max_evals.setSpecialValueText("no limit")
        self.max_evals.setToolTip(
            "Most light evaluations of each run (each seed), in all: a sweep shares them out"
        )
        self.time_limit = QtWidgets.QDoubleSpinBox(maximum=86_400.0, decimals=1, suffix=" s")
        self.time_limit.setSpecialValueText("no limit")
        self.time_limit.setToolTip("Longest time of each run")
        self.seed = QtWidgets.QSpinBox(maximum=2**31 - 1)
        self.runs = QtWidgets.QSpinBox(minimum=1, maximum=1000)
        self.runs_label = QtWidgets.QLabel("Seeds")
        cells = (
            (QtWidgets.QLabel("Evaluations"), self.max_evals),
            (QtWidgets.QLabel("Time limit"), self.time_limit),
            (QtWidgets.QLabel("Seed"), self.seed),
            (self.runs_label, self.runs),
        )
        for i, (label, box) in enumerate(cells):
            limits.addWidget(label, i // 2, 2 * (i % 2))
            limits.addWidget(box, i // 2, 2 * (i % 2) + 1)
        limits.setColumnStretch(1, 1)
        limits.setColumnStretch(3, 1)
        form.addRow(limits)
        self.show_best = QtWidgets.QCheckBox("show the best so far in the view")
        self.show_best.setChecked(True)
        form.addRow(self.show_best)
        lay.addWidget(left)
        self.plot = ConvergencePlot()
        lay.addWidget(self.plot, 1)

        self.method.currentIndexChanged.connect(self._method_edited)
        self.goal.currentIndexChanged.connect(self._goal_edited)
        self.max_evals.valueChanged.connect(lambda v: self._set(max_evals=v or None))
        self.time_limit.valueChanged.connect(lambda v: self._set(time_limit=v or None))
        self.seed.valueChanged.connect(lambda v: self._set(seed=v))
        self.runs.valueChanged.connect(self._runs_edited)
        self.run_button.clicked.connect(self.runRequested)
        self.cancel_button.clicked.connect(self.cancelRequested)
        for sig in (doc.sceneChanged, doc.designChanged):
            sig.connect(self.refresh)
        self._seeds = 1

    # -- document -> widgets ----------------------------------------------------------------
    def refresh(self) -> None:
        """Show the project's settings (signals blocked: showing is not editing)."""
        if self.doc.project is None:
            return
        o = self.doc.project.optimizer
        widgets = (self.method, self.goal, self.max_evals, self.time_limit, self.seed, self.runs)
        for w in widgets:
            w.blockSignals(True)
        design = self.doc.design
        self._offer_methods(design)
        self.method.setCurrentIndex(self.method.findData(o.method))
        self.goal.clear()
        # Every registered goal; one the design cannot take (a match without a target
        # lighting) is refused with the model's reason when chosen.
        for spec in goal_specs():
            self.goal.addItem(spec.short, str(spec.kind))
        self.goal.setCurrentIndex(self.goal.findData(str(design.goals[0].kind)))
        self.goal.setEnabled(not self._multi())
        self._show_trade()
        self.max_evals.setValue(o.max_evals or 0)
        self.time_limit.setValue(o.time_limit or 0.0)
        self.seed.setValue(o.seed)
        self._show_runs()
        for w in widgets:
            w.blockSignals(False)

    def _offer_methods(self, design) -> None:
        """Grey out the methods that cannot run on ``design``, saying why (tooltip)."""
        model = self.method.model()
        for i in range(self.method.count()):
            why = get_method(self.method.itemData(i)).refusal(design)
            model.item(i).setEnabled(why is None)
            self.method.setItemData(i, why or "", QtCore.Qt.ToolTipRole)

    def refusal(self) -> str | None:
        """Why the project's method cannot run on the open design (None: it can)."""
        return get_method(self.doc.project.optimizer.method).refusal(self.doc.design)

    def _show_trade(self) -> None:
        """What the chosen method will do with the design's goals, in words."""
        why = self.refusal()
        if why is not None:
            self.trades.setText(why)
        elif self._multi():
            a, b = (goal_spec(k).label.lower() for k in front_pair(self.doc.design))
            self.trades.setText(f"Front of {a} against {b}")
        else:
            self.trades.setText("")

    def _multi(self) -> bool:
        return get_method(self.doc.project.optimizer.method).finds_front(self.doc.design)

    def _show_runs(self) -> None:
        o = self.doc.project.optimizer
        method = get_method(o.method)
        count = sweep_count(method, self.doc.design)
        if count is not None:
            self.runs_label.setText(count[0])
            self.runs.setValue(getattr(o, count[1]))
        elif self._multi():
            self.runs_label.setText("Runs")
            self.runs.setValue(1)
        else:
            self.runs_label.setText("Seeds (runs)")
            self.runs.setValue(self._seeds)

    # -- widgets -> document ----------------------------------------------------------------
    def _set(self, **fields) -> None:
        try:
            self.doc.set_optimizer(**fields)
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            self.refresh()

    def _method_edited(self) -> None:
        self._set(method=self.method.currentData())
        self.refresh()

    def _goal_edited(self) -> None:
        kind = self.goal.currentData()
        if kind is not None:
            try:  # the climate goals need a work plane
                self.doc.set_primary_goal(kind)
            except LightInvError as exc:
                QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
                self.refresh()

    def _runs_edited(self, value: int) -> None:
        method = get_method(self.doc.project.optimizer.method)
        count = sweep_count(method, self.doc.design)
        if count is not None:
            self._set(**{count[1]: value})
        elif not self._multi():
            self._seeds = value

    # -- queries and run state ----------------------------------------------------------------
    def seeds(self) -> list[int]:
        """Seeds of a single-objective run: the project's seed, then the next ones."""
        o = self.doc.project.optimizer
        n = 1 if self._multi() else self._seeds
        return [o.seed + i for i in range(n)]

    def goal_label(self) -> str:
        """The plotted objective with its units (a sweep's: that of its second sub-run,
        the goal it minimises at each bound or its second step)."""
        if self._multi():
            method = get_method(self.doc.project.optimizer.method)
            if method.run_goal is not None:
                return self.run_goal_label(1)
            return method.progress_label or "objective of each sub-run"
        return goal_axis_label(self.doc.design.goals[0].kind)

    def run_goal_label(self, run: int) -> str:
        """The goal (with units) sub-run ``run`` of the project's method optimises."""
        o = self.doc.project.optimizer
        method = get_method(o.method)
        if method.run_goal is None or not self._multi():
            return self.goal_label()
        return goal_axis_label(method.run_goal(self.doc.design, o, run))

    def plot_labels(self):
        """(label of the objective plot, run -> its goal's label) for the convergence
        plot of a run starting now."""
        o, design = self.doc.project.optimizer, self.doc.design
        method = get_method(o.method)
        if method.run_goal is not None and self._multi():
            # The design and settings as the run starts (edits during it change nothing).
            return self.goal_label(), lambda run: goal_axis_label(method.run_goal(design, o, run))
        return self.goal_label(), None

    def set_running(self, running: bool) -> None:
        """Enable Cancel (and nothing else) while a run goes on."""
        self.run_button.setEnabled(not running)
        self.cancel_button.setEnabled(running)
        for w in (self.method, self.goal, self.max_evals, self.time_limit, self.seed, self.runs):
            w.setEnabled(not running and (w is not self.goal or self.goal.count() > 0))
        if not running:
            self.goal.setEnabled(not self._multi())

    def show_progress(self, snap) -> None:
        """Counters of a ``RunSnapshot``: evaluations (all sub-runs, as the core counts
        them), the sub-run, its best goal value and its search penalty."""
        p = snap.latest
        if p is None and snap.precompute is not None and snap.precompute < 1.0:
            self.counters.setText(
                f"Precomputing the luminaire arrays' light: {100 * snap.precompute:.0f}% "
                f"({snap.elapsed:.0f} s); the search starts after it"
            )
            return
        # The search's time and rate, as the core reports them when the run ends; the
        # arrays' precompute apart (it made "53 s, 47 /s" of a 1 s search).
        searched = snap.elapsed - snap.precompute_seconds
        rate = snap.evaluations / searched if searched > 0 else 0.0
        text = f"{snap.evaluations:,} evaluations, {searched:.1f} s, {rate:,.0f} /s"
        if snap.precompute_seconds >= 0.5:
            text += f" (after {snap.precompute_seconds:.0f} s precomputing the arrays)"
        if p is not None:
            run = f"run {p.run + 1} of {p.runs}, " if p.runs > 1 else ""
            level = f", level n/{p.level}" if p.level > 1 else ""
            # The search's own penalty: read at the level's representative patches, less
            # the feasibility tolerance (plus the arrays' margin), from the arrays'
            # lattice blend; the result's P is judged on every patch when it ends.
            text += (
                f"\n{run}best {self.progress_label(p.run)} {p.best_goal:.6g}, "
                f"search P ≈ {p.best_penalty:.3g}{level}"
            )
        self.counters.setText(text)

    def progress_label(self, run: int) -> str:
        """What ``Progress.best_goal`` of sub-run ``run`` is, with units."""
        method = get_method(self.doc.project.optimizer.method)
        if self._multi() and method.run_goal is None:
            return method.progress_label or "objective"
        return self.run_goal_label(run)
