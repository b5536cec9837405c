"""The optimiser asks the registries, never a list of kinds: a registered goal takes
part in the front choices, and a sweep's goal direction comes from its spec."""

from __future__ import annotations

import pytest

from lightinv_core.design.model import Design, Goal, Source
from lightinv_core.design.solution import Solution
from lightinv_core.goals import GoalSpec, register_goal, unregister_goal
from lightinv_core.optimize.fronts import OBJECTIVES, front_of, front_pair, minimised
from lightinv_core.optimize.portfolio import wants_front

TOY = "max_toy_score"


@pytest.fixture
def toy_goal():
    register_goal(GoalSpec(TOY, "Toy score", "Most toy score", "toy", "toy", maximise=True))
    yield
    unregister_goal(TOY)


def _design(*kinds: str) -> Design:
    lamp = Source("L", "light", "luminaire", (0.0, 0.0, 0.5, 0.5), flux=1000.0)
    return Design((lamp,), tuple(Goal(k) for k in kinds))


def test_a_registered_goal_takes_part_in_the_front_choices(toy_goal):
    assert front_pair(_design(TOY)) == OBJECTIVES
    assert not wants_front(_design(TOY))
    assert wants_front(_design(TOY, "min_electric_power", "max_light_power"))


def test_a_front_of_a_registered_goal_follows_its_direction(toy_goal):
    def sol(score: float, watts: float) -> Solution:
        return Solution((), {TOY: score, "min_electric_power": watts}, 0.0)

    a, b, c = sol(5.0, 10.0), sol(9.0, 20.0), sol(4.0, 30.0)
    assert minimised(b, TOY) == -9.0
    front = front_of([a, b, c], "t", ("min_electric_power", TOY))
    # c has more power and less score than a: dominated when the score is maximised.
    assert front.solutions == (a, b)
