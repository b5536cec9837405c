"""A tiny change-notification registry: named events, each with its payload type.

The editing model says what changed by name and passes the new state as one frozen
payload (changes.py); a view (the Qt adapter, a notebook, a test) connects callbacks
to the names it cares about. Callbacks run synchronously, in connection order, on the
thread that made the change, each called with the payload.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from lightinv_core.editing.changes import (
    DesignChanged,
    LightingChanged,
    OperatorChanged,
    PathChanged,
    ResultsChanged,
    SceneChanged,
    SelectionChanged,
)

EVENT_TYPES: dict[str, type] = {
    "scene": SceneChanged,
    "operator": OperatorChanged,
    "design": DesignChanged,
    "selection": SelectionChanged,
    "lighting": LightingChanged,
    "path": PathChanged,
    "results": ResultsChanged,
}
"""What can change, and the payload each change carries: the scene (and its patches),
the operator (light available), the design (sources, rules, intentions, goals, current
source), the picked patches, the lighting shown, the file state (path, dirty flag, run
settings) and the results."""
EVENTS = tuple(EVENT_TYPES)
"""The event names, in declaration order."""

Callback = Callable[[Any], None]


class Events:
    """Callbacks per event name; ``emit(name, payload)`` calls each with the payload."""

    def __init__(self, types: Mapping[str, type] = EVENT_TYPES):
        self._types = dict(types)
        self._callbacks: dict[str, list[Callback]] = {n: [] for n in self._types}
        self.counts: dict[str, int] = dict.fromkeys(self._types, 0)
        """How many times each event was emitted (tests, diagnostics)."""

    @property
    def names(self) -> tuple[str, ...]:
        """The event names, in declaration order."""
        return tuple(self._callbacks)

    def payload_type(self, name: str) -> type:
        """The type of the payload event ``name`` carries."""
        self._check(name)
        return self._types[name]

    def connect(self, name: str, callback: Callback) -> None:
        """Call ``callback(payload)`` whenever ``name`` is emitted (KeyError for an
        unknown name)."""
        self._check(name)
        self._callbacks[name].append(callback)

    def disconnect(self, name: str, callback: Callback) -> None:
        """Stop calling ``callback`` for ``name`` (ValueError if it was not connected)."""
        self._check(name)
        self._callbacks[name].remove(callback)

    def emit(self, name: str, payload: Any) -> None:
        """Tell every callback of ``name`` what changed (TypeError when ``payload`` is not
        of the event's type: a view relies on it)."""
        self._check(name)
        kind = self._types[name]
        if not isinstance(payload, kind):
            raise TypeError(f"event {name!r} carries a {kind.__name__}, not {payload!r}")
        self.counts[name] += 1
        # A callback may connect or disconnect others: iterate over a copy.
        for callback in tuple(self._callbacks[name]):
            callback(payload)

    def _check(self, name: str) -> None:
        if name not in self._callbacks:
            raise KeyError(f"unknown event {name!r} (events: {', '.join(self._callbacks)})")
