"""The report's plots as matplotlib figures: convergence, Pareto; and a table drawn on a
page (``draw_table``, the daylight section's energy page).

Every function returns a ``matplotlib.figure.Figure`` with an Agg canvas (pyplot is
never used). Text is real text, so it stays selectable and searchable in the PDF.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import StrMethodFormatter

from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.kinds import GoalKind
from lightinv_core.optimize.quality import FrontQuality
from lightinv_core.report.provenance import method_label
from lightinv_core.report.tables import Table
from lightinv_core.report.views import A4_LANDSCAPE
from lightinv_core.value_text import goal_label

PASS_COLOUR, FAIL_COLOUR, HEAD_COLOUR = "#d9f2d9", "#f8d0d0", "#e4e8f0"
ROW_HEIGHT = 0.032  # of the page height, per table row


def new_figure(figsize: tuple[float, float] = A4_LANDSCAPE, **kwargs) -> Figure:
    """A figure with an Agg canvas, independent of pyplot and of the global backend."""
    fig = Figure(figsize=figsize, **kwargs)
    FigureCanvasAgg(fig)
    return fig


def _col_widths(table: Table) -> list[float]:
    lengths = [
        max([len(table.columns[j])] + [len(r[j]) for r in table.rows]) + 2
        for j in range(len(table.columns))
    ]
    total = sum(lengths)
    return [n / total for n in lengths]


def draw_table(
    fig: Figure, table: Table, top: float, rows: range | None = None, title: str | None = None
) -> float:
    """Draw ``table`` (or its ``rows``) from height ``top`` (figure fraction) down;
    returns the height where the next item can start."""
    rows = rows if rows is not None else range(len(table.rows))
    fig.text(0.05, top, title or table.title, fontsize=13, fontweight="bold", va="top")
    h = ROW_HEIGHT * (len(rows) + 1)
    ax = fig.add_axes((0.05, top - 0.045 - h, 0.9, h))
    ax.set_axis_off()
    cells = [list(table.rows[i]) for i in rows] or [["—"] * len(table.columns)]
    t = ax.table(
        cellText=cells,
        colLabels=list(table.columns),
        colWidths=_col_widths(table),
        cellLoc="left",
        colLoc="left",
        bbox=(0, 0, 1, 1),
    )
    t.auto_set_font_size(False)
    t.set_fontsize(9)
    for cell in t.get_celld().values():
        # The text inset is a fraction of the cell width: keep it about 1% of the page.
        cell.PAD = min(0.1, 0.012 / max(cell.get_width(), 1e-3))
    for j in range(len(table.columns)):
        t[0, j].set_facecolor(HEAD_COLOUR)
        t[0, j].get_text().set_fontweight("bold")
    for k, i in enumerate(rows):
        colour = {"pass": PASS_COLOUR, "fail": FAIL_COLOUR}.get(table.flags[i])
        if colour:
            t[k + 1, len(table.columns) - 1].set_facecolor(colour)
    y = top - 0.06 - h
    if table.note and (not rows or rows[-1] == len(table.rows) - 1):
        for line in textwrap.wrap(table.note, 150):
            fig.text(0.05, y, line, fontsize=9, va="top", color="0.3")
            y -= 0.024
    return y - 0.03


def _levels(history: np.ndarray, stage_evals=None) -> tuple[np.ndarray, list[float]]:
    """Cumulative evaluations of a (possibly multilevel) history, and where stages start.

    Each multilevel stage counts its evaluations from zero (a row whose count does not
    grow starts a stage). With ``stage_evals`` (the evaluations each stage used, e.g.
    ``info.level_evaluations``) stages are placed exactly; without, each stage is
    drawn from the previous stage's last recorded improvement.
    """
    ev = history[:, 0].astype(float)
    first = [0, *(i for i in range(1, len(ev)) if ev[i] <= ev[i - 1])]
    exact = (
        isinstance(stage_evals, list | tuple)
        and len(stage_evals) == len(first)
        and all(isinstance(n, int | float) for n in stage_evals)
    )
    out, starts = ev.copy(), []
    for k, i in enumerate(first[1:], 1):
        offset = float(sum(stage_evals[:k])) if exact else out[i - 1]
        stop = first[k + 1] if k + 1 < len(first) else len(ev)
        out[i:stop] = ev[i:stop] + offset
        starts.append(offset)
    return out, starts


def convergence_figure(solution: Solution, primary: str, fig=None) -> Figure | None:
    """Best primary goal and best penalty against evaluations, from ``info.history``
    (rows: evaluations, best f + P, best P, best goal); None without a history. Into
    ``fig`` (a subfigure of a report page) when given."""
    rows = solution.info.history
    if not rows:
        return None
    H = np.array([[float(v) for v in r[:4]] for r in rows if len(r) >= 4])
    if len(H) == 0:
        return None
    ev, starts = _levels(H, solution.info.level_evaluations)
    total = solution.info.evaluations
    end = max(float(total), ev[-1]) if isinstance(total, int | float) else ev[-1]
    x = np.r_[ev, end]
    name = goal_label(primary)
    short = name.split(" (")[0]
    fig = new_figure(layout="constrained") if fig is None else fig
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    goal = np.r_[H[:, 3], H[-1, 3]]
    ok = np.isfinite(goal)
    ax1.step(x[ok], goal[ok], where="post", color="C0", lw=1.6)
    ax1.set_ylabel(f"best {name}")
    ax1.set_title(f"Convergence: {short} (the optimised goal) and penalty")
    pen = np.r_[H[:, 2], H[-1, 2]]
    ok = np.isfinite(pen)
    ax2.step(x[ok], pen[ok], where="post", color="C3", lw=1.6)
    positive = pen[ok & (pen > 0)]
    lin = 10 ** math.floor(math.log10(positive.min())) if len(positive) else 1e-6
    ax2.set_yscale("symlog", linthresh=lin)
    ax2.set_ylim(bottom=0)
    ax2.set_ylabel("best penalty P (symlog)")
    ax2.set_xlabel("radiosity evaluations")
    # Feasible from the first improvement of the last stage after which P stays 0.
    last = int(np.flatnonzero(np.r_[True, np.diff(H[:, 0]) <= 0])[-1])
    pos = np.flatnonzero(H[last:, 2] != 0)
    first = last + (int(pos[-1]) + 1 if len(pos) else 0)
    feasible_at = ev[first] if first < len(H) else None
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        for s in starts:
            ax.axvline(s, color="0.5", ls=":", lw=1)
        if feasible_at is not None:
            ax.axvline(feasible_at, color="C2", ls="--", lw=1)
    if feasible_at is not None:
        ax2.annotate(
            f"feasible from {int(feasible_at):,} evaluations",
            (feasible_at, 0),
            xytext=(6, 12),
            textcoords="offset points",
            color="C2",
            fontsize=9,
        )
    if np.nanmax(np.abs(goal[np.isfinite(goal)]), initial=0) >= 1e4:
        ax1.yaxis.set_major_formatter(StrMethodFormatter("{x:,.0f}"))
    if starts:
        ax1.annotate(
            "dotted lines: next multilevel stage",
            (0.01, 0.97),
            xycoords="axes fraction",
            va="top",
            fontsize=8.5,
            color="0.4",
        )
    return fig


MAX_LABELLED_POINTS = 20
"""A front with more points (NSGA-II's) is drawn without a number beside each point."""


def pareto_figure(
    front: ParetoFront, chosen: Solution | None, quality: FrontQuality | None = None, fig=None
) -> Figure | None:
    """The front's second objective against its first (``front.objectives``: reflected
    light power (lm) against electric power (W) for the power/light fronts, e.g. glazing
    area against annual energy for a climate front) of its solutions and the other
    candidates, the reported solution marked, the front's hypervolume and spacing in
    the title when ``quality`` is given; None when empty. Into ``fig`` when given."""
    if not front.solutions:
        return None
    default = (str(GoalKind.MIN_ELECTRIC_POWER), str(GoalKind.MAX_LIGHT_POWER))
    kinds = tuple(front.objectives[:2]) if len(front.objectives) >= 2 else default

    def xy(sols):
        return np.array(
            [[s.objectives.get(k, np.nan) for k in kinds] for s in sols],
            dtype=float,
        ).reshape(-1, 2)

    fig = new_figure(layout="constrained") if fig is None else fig
    ax = fig.add_subplot()
    front_ids = {id(s) for s in front.solutions}
    others = [s for s in front.candidates if id(s) not in front_ids and s not in front.solutions]
    if others:
        P = xy(others)
        ax.scatter(
            P[:, 0],
            P[:, 1],
            s=18,
            color="0.7",
            label="other runs (dominated or infeasible)",
            zorder=2,
        )
    F = xy(front.solutions)
    order = np.argsort(F[:, 0], kind="stable")
    ax.plot(F[order, 0], F[order, 1], "-o", color="C0", ms=6, label="Pareto front", zorder=3)
    for i, (a, b) in enumerate(F if len(F) <= MAX_LABELLED_POINTS else ()):
        ax.annotate(
            str(i + 1), (a, b), xytext=(5, -12), textcoords="offset points", fontsize=9, color="C0"
        )
    if chosen is not None:
        c = xy([chosen])[0]
        ax.scatter(
            [c[0]],
            [c[1]],
            marker="*",
            s=320,
            color="C3",
            zorder=4,
            edgecolors="k",
            linewidths=0.6,
            label="solution in this report",
        )
    if np.nanmax(np.abs(F[:, 1]), initial=0) >= 1e4:
        ax.yaxis.set_major_formatter(StrMethodFormatter("{x:,.0f}"))
    if np.nanmax(np.abs(F[:, 0]), initial=0) >= 1e4:
        ax.xaxis.set_major_formatter(StrMethodFormatter("{x:,.0f}"))
    ax.set_xlabel(goal_label(kinds[0]))
    ax.set_ylabel(goal_label(kinds[1]))
    method = f" ({method_label(front.method)})" if front.method else ""
    title = (
        f"Pareto front{method}: {len(front.solutions)} non-dominated of "
        f"{max(len(front.candidates), len(front.solutions))} solutions"
    )
    if quality is not None:
        spread = "–" if quality.spacing is None else f"{quality.spacing:.4f}"
        title += f"\nhypervolume {quality.hypervolume:.4f}, spacing {spread} (normalised)"
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right" if kinds == default else "best")
    return fig
