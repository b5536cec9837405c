"""The optimizer seam: the protocol every optimisation method implements.

A method is an object with a registry ``name`` (what project files, the CLI and the GUI
call it), a ``label`` for people, whether it finds a Pareto front for a design
(``finds_front``), and ``run``: given a
``DesignProblem``, the run settings (whole: each method reads the fields it uses), a
stop rule and a seed, it returns an ``OptimizationResult`` whose answer is judged on
every patch. It reports ``Progress`` snapshots, checks ``cancel`` between batches (a
cancelled run returns its best so far) and, when it finds several solutions, hands
each to ``on_solution`` as it is found. The same seed gives the same result.

Adding a method: write its module in this package with a class satisfying
``OptimizationMethod`` and add one instance to ``registry.METHODS``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Protocol

from lightinv_core.design.solution import Solution
from lightinv_core.optimize.progress import CancelFn, ProgressFn
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.termination import StopRule

if TYPE_CHECKING:
    from lightinv_core.design.model import Design
    from lightinv_core.optimize.problem import DesignProblem
    from lightinv_core.optimize.settings import OptimizerSettings

SolutionFn = Callable[[Solution], None]


class OptimizationMethod(Protocol):
    """One optimisation method (see the module docstring)."""

    name: str
    label: str
    count_setting: tuple[str, str] | None
    """(label, settings field) of the number of runs or points a front method makes,
    for the GUI; None when it has none."""
    progress_label: str | None
    """What ``Progress.best_goal`` holds when it is not the primary goal (a front's
    methods), for the plots; None: the primary goal."""

    def finds_front(self, design: Design) -> bool:
        """Whether a run on ``design`` returns a Pareto front (else one best layout)."""
        ...

    def run(
        self,
        problem: DesignProblem,
        settings: OptimizerSettings,
        stop: StopRule,
        seed: int,
        progress: ProgressFn | None = None,
        cancel: CancelFn | None = None,
        on_solution: SolutionFn | None = None,
    ) -> OptimizationResult:
        """Optimise ``problem``; the answer is judged on every patch."""
        ...
