"""Every optimisation method, found by name: project files, the CLI and the GUI read
their choices from here.

Registering a method is one line in ``METHODS`` (its module implements the
``OptimizationMethod`` protocol of method.py).
"""

from __future__ import annotations

from lightinv_core.errors import DesignError
from lightinv_core.optimize.method import OptimizationMethod
from lightinv_core.optimize.mop import EpsilonMethod, TwoStepMethod
from lightinv_core.optimize.multilevel import MultilevelMethod
from lightinv_core.optimize.vns import VNSMethod

METHODS: tuple[OptimizationMethod, ...] = (
    VNSMethod(),
    MultilevelMethod(),
    EpsilonMethod(),
    TwoStepMethod(),
)


def method_names() -> tuple[str, ...]:
    """The registry names of every method, in the order the GUI lists them."""
    return tuple(m.name for m in METHODS)


def single_objective_names() -> tuple[str, ...]:
    """The methods that return one best solution (not a front)."""
    return tuple(m.name for m in METHODS if not m.multi_objective)


def get_method(name: str) -> OptimizationMethod:
    """The method registered as ``name`` (DesignError listing the known ones)."""
    for m in METHODS:
        if m.name == name:
            return m
    raise DesignError(
        f"unknown optimisation method {name!r} (methods: {', '.join(method_names())})"
    )
