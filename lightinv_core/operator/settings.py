"""How a radiosity operator is built: the settings a project stores and the CLI overrides.

Each field is declared once in ``OPERATOR``: the checks here, the project file's reading
and writing and the table in docs/project-file.md come from it.
"""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.fields import Field, ObjectSpec, _integer, _number, _optional
from lightinv_core.transport.formfactors import DEFAULT_RAYS, MAX_RAYS

OPERATOR = ObjectSpec(
    "operator",
    (
        Field(
            "tol",
            lambda v, p: _number(v, p, gt=0.0, lt=1.0),
            0.01,
            "number, 0 < tol < 1",
            "target mean relative error of the reflected light C (used when `rank` is null)",
        ),
        Field(
            "rank",
            _optional(lambda v, p: _integer(v, p, lo=1)),
            None,
            "integer >= 1",
            "fixed number of clusters k; null: grow k until `tol` is met",
        ),
        Field(
            "rays",
            lambda v, p: _integer(v, p, lo=1, hi=MAX_RAYS),
            DEFAULT_RAYS,
            f"integer, 1 to {MAX_RAYS:,}",
            "rays per patch for the form factors",
        ),
        Field(
            "seed",
            lambda v, p: _integer(v, p, lo=0),
            0,
            "integer >= 0",
            "random seed of the ray tracing",
        ),
    ),
    write_defaults=True,  # a saved file shows every setting of its run
)


@dataclass(frozen=True)
class OperatorSettings:
    """How the radiosity operator is built: relative accuracy ``tol`` (used when ``rank``
    is None), or a fixed ``rank`` (clusters); ``rays`` per patch for the form factors and
    the ray ``seed``."""

    tol: float = OPERATOR.field("tol").default
    rank: int | None = OPERATOR.field("rank").default
    rays: int = OPERATOR.field("rays").default
    seed: int = OPERATOR.field("seed").default

    def __post_init__(self) -> None:
        OPERATOR.check_object(self)
