"""The optimizer seam: one ``run(problem, context)`` signature for every method.

A method is a ``MethodSpec`` in the registry (registry.py): its ``name`` (what project
files, the CLI and the GUI call it), a ``label`` for people, its own ``settings``
dataclass (as pymoo builds an algorithm from its own options: VNS has ``trials``,
NSGA-II ``population``), and its ``run`` function. ``run(problem, context)`` gets a
``DesignProblem`` and a ``RunContext``: the method's settings, the stop rule, the seed,
a start point, and the hooks (progress snapshots, ``cancel`` checked between batches, a
cancelled run returning its best so far, and ``on_solution`` for each point of a front
as it is found). It returns an ``OptimizationResult`` whose answer is judged on every
patch. The same seed gives the same result.

Adding a method: a module with its settings dataclass and a ``run(problem, context)``
function, one ``MethodSpec``, and ``registry.register(spec)`` (or one line among the
registry's built-ins).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, fields, is_dataclass, replace
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from lightinv_core.design.solution import Solution
from lightinv_core.optimize.progress import CancelFn, ProgressFn
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.termination import StopRule

if TYPE_CHECKING:
    from lightinv_core.design.model import Design
    from lightinv_core.optimize.problem import DesignProblem

SolutionFn = Callable[[Solution], None]
S = TypeVar("S")


@dataclass(frozen=True)
class NoSettings:
    """The settings of a method that has none of its own."""


@dataclass(frozen=True)
class RunContext:
    """Everything a method receives besides the problem.

    ``settings``: the method's own settings (its spec's dataclass), or any object whose
    attributes of the same names give them (the project's ``OptimizerSettings``), or
    None for the defaults: read them with ``options``. ``stop``: when to stop; ``seed``:
    every random choice comes from it; ``x0``: a start layout (None: a random one);
    ``progress``, ``cancel``, ``on_solution``: the caller's hooks.
    """

    settings: Any = None
    stop: StopRule = field(default_factory=StopRule)
    seed: int = 0
    x0: np.ndarray | None = None
    progress: ProgressFn | None = None
    cancel: CancelFn | None = None
    on_solution: SolutionFn | None = None

    def options(self, cls: type[S]) -> S:
        """The settings as ``cls``: ``settings`` itself when it is one, else ``cls``
        with each field taken from the attribute of that name when there is one."""
        return settings_as(cls, self.settings)

    def but(self, **changes) -> RunContext:
        """This context with ``changes``."""
        return replace(self, **changes)


def context_of(context: RunContext | None, given: dict[str, Any]) -> RunContext:
    """``context`` (default: a plain ``RunContext``) with the fields ``given`` as
    keywords: a search called as ``vns(problem, seed=3, stop=rule)`` or
    ``vns(problem, context)``."""
    return (context or RunContext()).but(**given) if given else context or RunContext()


def settings_as(cls: type[S], source: Any) -> S:
    """``source`` as the settings dataclass ``cls`` (see ``RunContext.options``)."""
    if isinstance(source, cls):
        return source
    if source is None or not is_dataclass(cls):
        return cls()
    given = {f.name: getattr(source, f.name) for f in fields(cls) if hasattr(source, f.name)}
    return cls(**given)


def never_refused(design: Design) -> str | None:
    """``refusal`` of a method that applies to every design."""
    return None


def one_layout(design: Design) -> bool:
    """``finds_front`` of a method returning one best layout."""
    return False


def always_front(design: Design) -> bool:
    """``finds_front`` of a method that always returns a front."""
    return True


@dataclass(frozen=True)
class MethodSpec:
    """One optimisation method in the registry.

    ``run(problem, context)`` optimises; ``settings`` is its settings dataclass;
    ``finds_front(design)`` says whether a run on ``design`` returns a Pareto front
    (else one best layout). For the GUI: ``count_setting`` is (label, settings field)
    of the number of runs or points a front method makes (None: none), and
    ``progress_label`` what ``Progress.best_goal`` holds when it is not the primary
    goal (a front's methods; None: the primary goal).
    """

    name: str
    label: str
    run: Callable[[DesignProblem, RunContext], OptimizationResult]
    settings: type = NoSettings
    finds_front: Callable[[Design], bool] = one_layout
    count_setting: tuple[str, str] | None = None
    progress_label: str | None = None
    refusal: Callable[[Design], str | None] = never_refused
    run_goal: Callable[[Design, Any, int], str | None] | None = None

    def settings_from(self, source: Any) -> Any:
        """This method's settings read from ``source`` (e.g. a project's
        ``OptimizerSettings``): the fields it shares with them, defaults for the rest."""
        return settings_as(self.settings, source)
