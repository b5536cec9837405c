"""A tiny change-notification registry: named events, plain-Python callbacks.

The editing model says what changed by name; a view (the Qt adapter, a notebook, a
test) connects callbacks to the names it cares about. Callbacks run synchronously, in
connection order, on the thread that made the change.
"""

from __future__ import annotations

from collections.abc import Callable

EVENTS = ("scene", "operator", "design", "selection", "lighting", "path", "results")
"""What can change: the scene (and its patches), the operator (light available), the
design (sources, rules, intentions, goals, current source), the picked patches, the
lighting shown, the file state (path, dirty flag, run settings) and the results."""


class Events:
    """Callbacks per event name; ``emit(name)`` calls each one (no arguments)."""

    def __init__(self, names: tuple[str, ...] = EVENTS):
        self._callbacks: dict[str, list[Callable[[], None]]] = {n: [] for n in names}
        self.counts: dict[str, int] = dict.fromkeys(names, 0)
        """How many times each event was emitted (tests, diagnostics)."""

    @property
    def names(self) -> tuple[str, ...]:
        """The event names, in declaration order."""
        return tuple(self._callbacks)

    def connect(self, name: str, callback: Callable[[], None]) -> None:
        """Call ``callback()`` whenever ``name`` is emitted (KeyError for an unknown name)."""
        self._check(name)
        self._callbacks[name].append(callback)

    def disconnect(self, name: str, callback: Callable[[], None]) -> None:
        """Stop calling ``callback`` for ``name`` (ValueError if it was not connected)."""
        self._check(name)
        self._callbacks[name].remove(callback)

    def emit(self, name: str) -> None:
        """Tell every callback of ``name`` that it changed."""
        self._check(name)
        self.counts[name] += 1
        # A callback may connect or disconnect others: iterate over a copy.
        for callback in tuple(self._callbacks[name]):
            callback()

    def _check(self, name: str) -> None:
        if name not in self._callbacks:
            raise KeyError(f"unknown event {name!r} (events: {', '.join(self._callbacks)})")
