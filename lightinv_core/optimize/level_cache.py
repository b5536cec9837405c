"""The costly parts of a multilevel stage, kept with the radiosity operator across runs.

A level's receivers cost two things: the patches' clusters at divisor d (bisection and,
on triangle surfaces, k-means) and Phi's rows at the representatives (O(nnz(F)) per row
or per zone patch: 16 s of CPU for the patio's n/16 in the Optimizers 2 issue). Both
depend only on the operator (its patches and factors), not on the design, so they are
kept in a table keyed weakly by the operator object: every ``DesignProblem`` built on
it, in any ``LightModel`` (the window makes one per run), reuses them, and they go
when the operator goes. A problem's own parts (grid points, arrays' responses) are
assembled per problem and cost O(receivers).

``BUILDS`` counts the builds (tests check that a second solve makes none;
bench/optimizers.py reports their CPU time).
"""

from __future__ import annotations

import threading
import weakref
from collections import Counter, OrderedDict

import numpy as np

from lightinv_core.light.model import LightModel, Receivers
from lightinv_core.operator.clustering import cluster_patches

RECEIVER_SETS = 16
"""Receiver sets kept per operator (least recently used dropped first): each design's
intentions pick their own representatives, and a set is at most ``BASIS_BYTES``."""
BUILDS: Counter = Counter()
"""Builds so far: ``"labels"`` (clusterings) and ``"receivers"`` (Phi's rows)."""


class _Parts:
    """The labels per cluster count and the receiver sets of one operator."""

    def __init__(self) -> None:
        self.labels: dict[int, np.ndarray] = {}
        self.receivers: OrderedDict[bytes, Receivers] = OrderedDict()


_TABLE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_LOCK = threading.Lock()


def _parts(light: LightModel) -> _Parts:
    with _LOCK:
        got = _TABLE.get(light.op)
        if got is None:
            got = _TABLE[light.op] = _Parts()
        return got


def cluster_labels(light: LightModel, clusters: int) -> np.ndarray:
    """Labels (n,) of the patches of ``light`` in about ``clusters`` spatial clusters
    (``operator.clustering.cluster_patches``), made once per operator."""
    parts = _parts(light)
    with _LOCK:
        got = parts.labels.get(clusters)
    if got is None:
        # Built outside the lock: another thread's run must not wait on this one.
        got = cluster_patches(light.patches, clusters)[0]
        got.setflags(write=False)
        BUILDS["labels"] += 1
        with _LOCK:
            got = parts.labels.setdefault(clusters, got)
    return got


def receivers(light: LightModel, rows: np.ndarray) -> Receivers:
    """``light.receivers(rows)`` (Phi's rows at patches ``rows``), made once per
    operator and receiver set; the ``RECEIVER_SETS`` most recently used are kept."""
    rows = np.ascontiguousarray(rows, dtype=np.int64)
    key = rows.tobytes()
    parts = _parts(light)
    with _LOCK:
        got = parts.receivers.get(key)
        if got is not None:
            parts.receivers.move_to_end(key)
            return got
    got = light.receivers(rows)
    if got.Phi_rows is not None:
        got.Phi_rows.setflags(write=False)  # shared by every later run
    BUILDS["receivers"] += 1
    with _LOCK:
        parts.receivers[key] = got
        while len(parts.receivers) > RECEIVER_SETS:
            parts.receivers.popitem(last=False)
    return got


def forget(light: LightModel) -> None:
    """Drop what is kept for the operator of ``light`` (the bench times cold builds)."""
    with _LOCK:
        _TABLE.pop(light.op, None)
