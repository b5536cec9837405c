"""Goals: what to optimise (each kind's names, unit and direction: ``goals.GoalSpec``)."""

from __future__ import annotations

from dataclasses import dataclass, field

from lightinv_core.design.model.source import source_kind
from lightinv_core.fields import Choice, ListOf, ObjectSpec, declare
from lightinv_core.goals import goal_kind, goal_names
from lightinv_core.kinds import GoalKind, source_kind_names

GOALS = tuple(str(g) for g in GoalKind)
"""The built-in goal kinds (``goals.goal_names()`` adds the registered ones)."""


def goal_not_taken(kind: str, field: str) -> str:
    """The message for a field goal ``kind`` does not take."""
    return "only a max_light_power goal takes source kinds"


@dataclass(frozen=True)
class Goal:
    """What to optimise.

    - ``min_electric_power``: sum of luminaire flux / efficacy (W);
    - ``max_light_power``: total reflected light power sum_i C_i A_i (lm), of
      the sources whose kind is in ``kinds`` (all when empty);
    - ``match``: relative distance e(E) = ||C(E) - C_obj|| / ||C_obj|| (paper
      eq. 11) to the light of the project's ``target_sources``;
    - ``min_installed_power``: rated power (W) of every luminaire at full output: the
      arrays' count x product watts plus the luminaire sources' flux / efficacy;
    - ``min_luminaire_count``: luminaires in the arrays plus luminaire sources;
    - the climate goals (``min_annual_energy``, ``max_sda``, ``min_glazing_area``) and
      registered ones: their ``GoalSpec``.
    """

    kind: GoalKind = field(
        metadata=declare(
            Choice(goal_names, goal_kind, name="goal kind"), "see the table of goal kinds"
        )
    )
    kinds: tuple[str, ...] = field(
        default=(),
        metadata=declare(
            ListOf(
                Choice(source_kind_names, source_kind),
                "kinds",
                unique=True,
                name="list of source kinds",
            ),
            "count the light of these kinds (all when empty)",
            kinds=(str(GoalKind.MAX_LIGHT_POWER),),
        ),
    )

    def __post_init__(self) -> None:
        GOAL_FIELDS.check_fields(self, f"goal {self.kind!r}")


GOAL_FIELDS = ObjectSpec.of(
    Goal,
    "goal",
    kind_field="kind",
    not_taken=goal_not_taken,
    default_anywhere=True,  # an empty list is the default: any goal may write it
)
"""The goal's fields, in the order a project file writes them."""
