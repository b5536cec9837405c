"""Every optimisation method, found by name: project files, the CLI and the GUI read
their choices from here.

Registering a method is one line in ``METHODS`` (its module implements the
``OptimizationMethod`` protocol of method.py).
"""

from __future__ import annotations

from lightinv_core.design.model import Design
from lightinv_core.errors import DesignError
from lightinv_core.optimize.cmaes import CMAESMethod
from lightinv_core.optimize.method import OptimizationMethod
from lightinv_core.optimize.mop import EpsilonMethod, TwoStepMethod
from lightinv_core.optimize.multilevel import MultilevelMethod
from lightinv_core.optimize.nsga2 import NSGA2Method
from lightinv_core.optimize.portfolio import AutoMethod
from lightinv_core.optimize.vns import VNSMethod

METHODS: tuple[OptimizationMethod, ...] = (
    AutoMethod(),
    VNSMethod(),
    MultilevelMethod(),
    CMAESMethod(),
    EpsilonMethod(),
    TwoStepMethod(),
    NSGA2Method(),
)


def method_names() -> tuple[str, ...]:
    """The registry names of every method, in the order the GUI lists them."""
    return tuple(m.name for m in METHODS)


def finds_front(name: str, design: Design) -> bool:
    """Whether method ``name`` run on ``design`` returns a Pareto front."""
    return get_method(name).finds_front(design)


def get_method(name: str) -> OptimizationMethod:
    """The method registered as ``name`` (DesignError listing the known ones)."""
    for m in METHODS:
        if m.name == name:
            return m
    raise DesignError(
        f"unknown optimisation method {name!r} (methods: {', '.join(method_names())})"
    )
