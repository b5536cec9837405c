"""The scenarios an intention is judged in: one ``ScenarioSpec`` each, in one registry.

A scenario says which light an intention's quantity is read from: the luminaires
alone, or with daylight through the glazing under some sky. Its spec gives its names
for people (the window's list entry, the tables' note), whether it includes daylight or
needs the weather year, and how its illuminance is summed from the light model's
parts (``light.daylight.ScenarioLight``: the luminaires' light and, per sky group, the
daylight per exterior lux). The light model, the report and the window look scenarios
up here (``scenario_spec``); a new scenario is one ``register_scenario`` call.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

from lightinv_core.kinds import Scenario


@dataclass(frozen=True)
class ScenarioSpec:
    """One scenario.

    ``name``: its name in project files; ``label``: the window's list entry;
    ``light``: what its light is, for the report's notes (``str.format`` fields
    ``exterior_lux`` and ``overcast_lux`` from the design's ``Daylight``, lux);
    ``daylit``: its light includes daylight (so it needs glazing to differ from
    night); ``weather``: it is measured over the weather year (only annual daylight
    metrics are, see ``quantities.HourBand``); ``lux(light, idx) -> (R', m)``: its
    illuminance (lux) at receivers idx of a ``ScenarioLight`` with sky groups (None
    for a scenario measured only by metrics).
    """

    name: str
    label: str
    light: str
    daylit: bool = True
    weather: bool = False
    lux: Callable[[Any, Any], Any] | None = None

    def describe(self, daylight: Any) -> str:
        """What the light is, with the design's exterior illuminances (lux)."""
        return self.light.format(
            exterior_lux=f"{daylight.exterior_lux:,.0f}",
            overcast_lux=f"{daylight.overcast_lux:,.0f}",
        )


_SCENARIOS: dict[str, ScenarioSpec] = {}


def register_scenario(spec: ScenarioSpec) -> ScenarioSpec:
    """Add a scenario (ValueError when its name is taken); returns the spec."""
    if spec.name in _SCENARIOS:
        raise ValueError(f"scenario {spec.name!r} is already registered")
    _SCENARIOS[spec.name] = spec
    return spec


def unregister_scenario(name: str) -> None:
    """Remove a scenario added by ``register_scenario`` (the built-in ones stay)."""
    if name in tuple(Scenario):
        raise ValueError(f"scenario {name!r} is built in")
    _SCENARIOS.pop(name, None)


def scenario_spec(name: str) -> ScenarioSpec:
    """The spec of a scenario (KeyError naming the known ones when unknown)."""
    try:
        return _SCENARIOS[str(name)]
    except KeyError:
        raise KeyError(f"scenario {name!r} is not one of {scenario_names()}") from None


def scenario_specs() -> Iterator[ScenarioSpec]:
    """Every scenario, the built-in ones first in ``Scenario`` order."""
    return iter(tuple(_SCENARIOS.values()))


def scenario_names() -> tuple[str, ...]:
    """Every scenario's name, in registry order."""
    return tuple(str(s) for s in _SCENARIOS)


def is_scenario(name: object) -> bool:
    """Whether ``name`` names a registered scenario."""
    return isinstance(name, str) and name in _SCENARIOS


def scenario_kind(name: str) -> Scenario | str:
    """The ``Scenario`` member of a built-in name, the name itself for a registered one."""
    return Scenario(name) if name in tuple(Scenario) else str(name)


def _design(light, idx):
    return light.electric[idx] + light.design_daylight(idx)


def _overcast(light, idx):
    return light.electric[idx] + light.daylight.overcast_lux * light.overcast_daylight(idx)


for _spec in (
    ScenarioSpec(
        Scenario.DESIGN,
        "design: luminaires + skylights at the design exterior lux",
        "luminaires plus daylight at {exterior_lux} lux exterior",
        lux=_design,
    ),
    ScenarioSpec(
        Scenario.NIGHT,
        "night: luminaires only",
        "luminaires only",
        daylit=False,
        lux=lambda light, idx: light.electric[idx],
    ),
    ScenarioSpec(
        Scenario.OVERCAST,
        "overcast: luminaires + the CIE overcast sky",
        "luminaires plus the CIE overcast sky of {overcast_lux} lux; DF in % of the exterior",
        lux=_overcast,
    ),
    ScenarioSpec(
        Scenario.ANNUAL,
        "annual: every occupied hour of the weather year",
        "shares 0-1 of the occupied hours of the weather year",
        weather=True,
    ),
):
    register_scenario(_spec)
