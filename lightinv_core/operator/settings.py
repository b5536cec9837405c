"""How a radiosity operator is built: the settings a project stores and the CLI overrides."""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.fields import _check_fields, _integer, _number, _optional


@dataclass(frozen=True)
class OperatorSettings:
    """How the radiosity operator is built: relative accuracy ``tol`` (used when ``rank``
    is None), or a fixed ``rank`` (clusters); ``rays`` per patch for the form factors and
    the ray ``seed``."""

    tol: float = 0.01
    rank: int | None = None
    rays: int = 1024
    seed: int = 0

    def __post_init__(self) -> None:
        _check_fields(
            self,
            {
                "tol": lambda v, p: _number(v, p, gt=0.0, lt=1.0),
                "rank": _optional(lambda v, p: _integer(v, p, lo=1)),
                "rays": lambda v, p: _integer(v, p, lo=1),
                "seed": lambda v, p: _integer(v, p, lo=0),
            },
        )
