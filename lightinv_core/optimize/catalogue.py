"""The names of the optimisation methods, without their code: what a project file's
``method`` may say (``settings.py`` checks it here, so reading a file imports no
algorithm). ``registry.py`` finds each name's ``MethodSpec``.
"""

from __future__ import annotations

from typing import Any

BUILT_IN: dict[str, str] = {
    "auto": "portfolio:AUTO",
    "vns": "vns:VNS",
    "multilevel": "multilevel:MULTILEVEL",
    "cmaes": "cmaes:CMAES",
    "epsilon": "mop:EPSILON",
    "two_step": "mop:TWO_STEP",
    "nsga2": "nsga2:NSGA2",
}
"""Name -> "module:spec" (in this package) of each built-in method, in the order the GUI
lists them."""
REGISTERED: dict[str, Any] = {}
"""Name -> ``MethodSpec`` of each method ``registry.register`` added."""


def method_names() -> tuple[str, ...]:
    """The registry names of every method, in the order the GUI lists them."""
    return (*BUILT_IN, *REGISTERED)
