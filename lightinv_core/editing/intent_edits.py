"""What the design asks for, as the user edits it: lighting intentions, work planes,
goals, and the daylight and climate they are judged in.

``IntentEdits`` is the document's concern for the design's brief (a mixin over
``state.DocumentState``); the sources that meet it are source_edits.py's.
"""

from __future__ import annotations

from dataclasses import replace

from lightinv_core.climate.weather import Weather
from lightinv_core.design.model import CalcObject, Intention, Observer
from lightinv_core.editing import rules
from lightinv_core.editing.climate import weather_of
from lightinv_core.editing.state import DocumentState
from lightinv_core.errors import DesignError


class IntentEdits(DocumentState):
    """Add, replace and remove intentions; choose goals; edit work planes and climate."""

    # -- lighting intentions --------------------------------------------------------------------
    def add_intention(self, intention: Intention) -> None:
        """Append a lighting intention (DesignError if its name is taken)."""
        self._set_design(
            replace(self.design, intentions=(*self.design.intentions, intention)),
            f"add intention {intention.name}",
        )

    def replace_intention(self, name: str, intention: Intention) -> None:
        """Put ``intention`` in place of the one called ``name`` (same position);
        DesignError if there is none or the new name is another intention's."""
        _check_rename(
            [i.name for i in self.design.intentions], name, intention.name, "lighting intention"
        )
        its = tuple(intention if i.name == name else i for i in self.design.intentions)
        self._set_design(replace(self.design, intentions=its), f"edit intention {name}")

    def remove_intention(self, name: str) -> None:
        """Delete a lighting intention."""
        its = tuple(i for i in self.design.intentions if i.name != name)
        self._set_design(replace(self.design, intentions=its), f"remove intention {name}")

    # -- goals ----------------------------------------------------------------------------------
    def set_goal(self, kind: str, on: bool) -> None:
        """Add goal ``kind`` (both power goals give a Pareto front) or remove it;
        DesignError when no goal would be left."""
        design = rules.with_goal(self.design, kind, on)
        if design != self.design:
            self._set_design(design, f"{'add' if on else 'remove'} goal {kind}")

    def set_primary_goal(self, kind: str) -> None:
        """Make ``kind`` the goal a single-objective run optimises (the others stay)."""
        design = rules.with_primary_goal(self.design, kind)
        if design is not self.design:
            self._set_design(design, f"goal {kind}")

    # -- work planes ----------------------------------------------------------------------------
    def set_workplanes(self, workplanes, label: str = "edit work planes") -> None:
        """Replace the design's work planes; intentions on a removed one go with it."""
        workplanes = tuple(workplanes)
        names = {w.name for w in workplanes}
        its = tuple(i for i in self.design.intentions if i.grid is None or i.grid in names)
        daylight = self.design.daylight
        if daylight.workplane is not None and daylight.workplane not in names:
            daylight = replace(daylight, workplane=None)  # dimming reads the first again
        self._set_design(
            replace(self.design, workplanes=workplanes, intentions=its, daylight=daylight), label
        )

    # -- observers (glare) ----------------------------------------------------------------------
    def add_observer(self, observer: Observer, intention: Intention | None = None) -> None:
        """Append an observer and, given, an intention at it (one undo step; DesignError
        if a name is taken). Where it stands is checked against the room when the
        design's light is shown or solved."""
        its = self.design.intentions + ((intention,) if intention is not None else ())
        self._set_design(
            replace(self.design, observers=(*self.design.observers, observer), intentions=its),
            f"add observer {observer.name}",
        )

    def remove_observer(self, name: str) -> None:
        """Delete an observer; an intention at it names the others, or goes with it."""
        its = []
        for it in self.design.intentions:
            if it.observers is not None and name in it.observers:
                left = tuple(o for o in it.observers if o != name)
                if not left:
                    continue
                it = replace(it, observers=left)
            its.append(it)
        obs = tuple(o for o in self.design.observers if o.name != name)
        self._set_design(
            replace(self.design, observers=obs, intentions=tuple(its)), f"remove observer {name}"
        )

    def add_observers(
        self, observers, intention: Intention | None = None, label: str | None = None
    ) -> None:
        """Append several observers and, given, an intention (one undo step: an EN
        12464-1 preset's UGR_L at its default observers)."""
        observers = tuple(observers)
        its = self.design.intentions + ((intention,) if intention is not None else ())
        names = ", ".join(o.name for o in observers)
        self._set_design(
            replace(self.design, observers=(*self.design.observers, *observers), intentions=its),
            label or f"add observers {names}",
        )

    def replace_observer(self, name: str, observer: Observer) -> None:
        """Put ``observer`` in place of the one called ``name`` (its place, height, view
        edited); a new name is carried into the intentions at it. DesignError if there
        is none or the new name is another observer's."""
        _check_rename([o.name for o in self.design.observers], name, observer.name, "observer")
        obs = tuple(observer if o.name == name else o for o in self.design.observers)
        its = tuple(
            replace(it, observers=tuple(observer.name if o == name else o for o in it.observers))
            if it.observers is not None and name in it.observers
            else it
            for it in self.design.intentions
        )
        self._set_design(
            replace(self.design, observers=obs, intentions=its), f"edit observer {name}"
        )

    def move_observer(self, name: str, dx: float, dy: float) -> None:
        """Move an observer by (dx, dy) m in plan (a drag in the view; consecutive moves
        are one undo step, "move observer NAME")."""
        ob = next((o for o in self.design.observers if o.name == name), None)
        if ob is None:
            raise DesignError(f"no observer {name!r}")
        x, y = ob.position
        moved = replace(ob, position=(round(x + dx, 4), round(y + dy, 4)))
        obs = tuple(moved if o.name == name else o for o in self.design.observers)
        self._set_design(replace(self.design, observers=obs), f"move observer {name}")

    # -- calculation objects --------------------------------------------------------------------
    def add_calc_object(self, obj: CalcObject, intention: Intention | None = None) -> None:
        """Append a calculation object and, given, an intention on it (one undo step;
        DesignError if a name is taken)."""
        its = self.design.intentions + ((intention,) if intention is not None else ())
        self._set_design(
            replace(self.design, calc_objects=(*self.design.calc_objects, obj), intentions=its),
            f"add calculation object {obj.name}",
        )

    def replace_calc_object(self, name: str, obj: CalcObject) -> None:
        """Put ``obj`` in place of the object called ``name``; intentions on it follow a
        new name (one undo step)."""
        if name not in {c.name for c in self.design.calc_objects}:
            raise DesignError(f"no calculation object {name!r}")
        objs = tuple(obj if c.name == name else c for c in self.design.calc_objects)
        its = tuple(
            replace(i, grid=obj.name) if i.grid == name else i for i in self.design.intentions
        )
        self._set_design(
            replace(self.design, calc_objects=objs, intentions=its),
            f"edit calculation object {name}",
        )

    def remove_calc_object(self, name: str) -> None:
        """Delete a calculation object and the intentions on it."""
        objs = tuple(c for c in self.design.calc_objects if c.name != name)
        its = tuple(i for i in self.design.intentions if i.grid != name)
        self._set_design(
            replace(self.design, calc_objects=objs, intentions=its),
            f"remove calculation object {name}",
        )

    # -- daylight and climate -------------------------------------------------------------------
    def set_daylight(self, **fields) -> None:
        """Change the design's daylight and climate (weather, north_deg, occupancy,
        weekdays, ground_reflectance, overcast_lux, target_lux, min_level, standby_w,
        workplane, exterior_lux, transmittance, sunlight_date, sunlight_min_altitude:
        ``design.model.Daylight``); DesignError on
        a bad value, leaving the design unchanged. The weather file is not read here
        (``weather``)."""
        daylight = replace(self.design.daylight, **fields)
        if daylight != self.design.daylight:
            self._set_design(
                replace(self.design, daylight=daylight), f"climate: {', '.join(sorted(fields))}"
            )

    def weather(self) -> Weather:
        """The design's weather file, read (``climate.weather.Weather``: site, hours);
        WeatherError when it cannot be read."""
        return weather_of(self.design.daylight)


def _check_rename(names: list[str], name: str, new: str, what: str) -> None:
    """DesignError unless ``name`` is one of ``names`` and ``new`` is no other's."""
    if name not in names:
        raise DesignError(f"no {what} {name!r}")
    if new != name and new in names:
        raise DesignError(f"another {what} is already called {new!r}")
