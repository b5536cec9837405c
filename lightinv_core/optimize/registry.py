"""Every optimisation method, found by name: project files, the CLI, study.py and the GUI
read their choices from here.

The built-in methods are listed by name and module (``catalogue.py``), and a module is
imported only when its method is first asked for (``method_names`` imports none:
checking a project file's ``method`` does not load pymoo). Each is a ``MethodSpec``
(method.py) in its module. ``register`` adds a method from anywhere (a plug-in, a
test), ``unregister`` removes it.
"""

from __future__ import annotations

from importlib import import_module

from lightinv_core.design.model import Design
from lightinv_core.errors import DesignError
from lightinv_core.optimize.catalogue import BUILT_IN, REGISTERED, method_names
from lightinv_core.optimize.method import MethodSpec

__all__ = [
    "check_applies",
    "finds_front",
    "get_method",
    "method_names",
    "methods",
    "refusal",
    "register",
    "unregister",
]


def _built_in(name: str) -> MethodSpec:
    module, attr = BUILT_IN[name].split(":")
    spec = getattr(import_module(f"{__package__}.{module}"), attr)
    if spec.name != name:
        raise RuntimeError(f"{BUILT_IN[name]} is named {spec.name!r}, not {name!r}")
    return spec


def register(spec: MethodSpec) -> None:
    """Add ``spec`` under its name (DesignError if the name is taken)."""
    if spec.name in BUILT_IN or spec.name in REGISTERED:
        raise DesignError(f"an optimisation method named {spec.name!r} exists already")
    REGISTERED[spec.name] = spec


def unregister(name: str) -> None:
    """Remove the method ``register`` added as ``name`` (built-in ones stay)."""
    if REGISTERED.pop(name, None) is None:
        raise DesignError(f"no registered optimisation method {name!r} to remove")


def methods() -> tuple[MethodSpec, ...]:
    """Every method, in the order of ``method_names``."""
    return tuple(get_method(n) for n in method_names())


def get_method(name: str) -> MethodSpec:
    """The method registered as ``name`` (DesignError listing the known ones)."""
    if name in REGISTERED:
        return REGISTERED[name]
    if name in BUILT_IN:
        return _built_in(name)
    raise DesignError(
        f"unknown optimisation method {name!r} (methods: {', '.join(method_names())})"
    )


def finds_front(name: str, design: Design) -> bool:
    """Whether method ``name`` run on ``design`` returns a Pareto front."""
    return get_method(name).finds_front(design)


def refusal(name: str, design: Design) -> str | None:
    """Why method ``name`` cannot run on ``design`` (its ``MethodSpec.refusal``), None
    when it can."""
    return get_method(name).refusal(design)


def check_applies(name: str, design: Design) -> None:
    """DesignError with the reason when method ``name`` cannot run on ``design``, naming
    the methods that can."""
    why = refusal(name, design)
    if why is not None:
        can = [m.name for m in methods() if m.refusal(design) is None]
        raise DesignError(f"{why} (methods for this design: {', '.join(can)})")
