"""Where the operator's precompute runs: in this process, or on a Dask cluster.

A build is a few maps over fixed pieces of work, the same pieces wherever they run:
the ray batches of the form factors (batch b always draws its rays from (seed, b)),
row blocks of the cluster form factors W and their cluster sums, row blocks of
Y = W M^-1, and cluster blocks of the zone transfer G. Results are put together in
the pieces' order on the client, so a build on a cluster gives the same operator,
bit for bit, as one in this process (with the same libraries on the same kind of CPU:
BLAS kernels differ between CPU types). No piece's bits depend on the threads it runs
on: a worker runs BLAS on one thread, this process on all cores, so the one BLAS
product of the pieces (Y = W M^-1) is summed in parts short enough that BLAS never
splits them (``lowrank.INNER_BLOCK``); the other pieces split their work in fixed parts.

``runner(None)`` runs the pieces here; ``runner("tcp://host:port")`` sends them to the
Dask scheduler at that address (``dask.distributed``, the ``cluster`` extra, imported
only then). Progress counts finished pieces; a cancel drops every piece not yet done.
"""

from __future__ import annotations

import re
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from lightinv_core.errors import CancelledError, LightInvError

SCHEDULER = re.compile(r"^(tcp|tls|ucx|inproc)://\S+$")
"""What a scheduler address looks like: tcp://host:port (tls://, ucx:// and Dask's
in-process inproc:// work too)."""
CONNECT_TIMEOUT = 10.0  # s
POLL = 0.05  # s between cancel checks while waiting for a piece
SCATTER_BYTES = 1 << 20  # array arguments above this are scattered, not put in the graph

ProgressFn = Callable[[float], None]
CancelFn = Callable[[], bool]


def check_scheduler(address: str) -> str:
    """``address`` if it looks like a Dask scheduler address, else LightInvError."""
    if not isinstance(address, str) or not SCHEDULER.match(address.strip()):
        raise LightInvError(
            f"scheduler address {address!r} is not of the form tcp://host:port "
            "(the address `dask scheduler` prints)"
        )
    return address.strip()


class LocalRunner:
    """Runs every piece here, in order (each piece uses this machine's cores itself)."""

    address = None
    blocks_per_piece = 1  # small pieces: a cancel is heard within one block

    def share(self, obj: Any) -> Any:
        """An object every piece may read (here: the object itself)."""
        return obj

    def map(
        self,
        fn: Callable,
        items: Sequence,
        *shared: Any,
        on_result: Callable[[int, Any], None],
        progress: ProgressFn | None = None,
        cancel: CancelFn | None = None,
    ) -> None:
        """``on_result(i, fn(items[i], *shared))`` for each piece in order."""
        for i, item in enumerate(items):
            if cancel is not None and cancel():
                raise CancelledError("operator build cancelled")
            on_result(i, fn(item, *shared))
            if progress is not None:
                progress((i + 1) / len(items))

    def close(self) -> None:
        """Nothing to release."""


class DaskRunner:
    """Sends the pieces to a Dask scheduler and takes their results back in order."""

    blocks_per_piece = 4  # fewer, larger pieces: less scheduling per unit of work

    def __init__(self, address: str):
        address = check_scheduler(address)
        try:
            from distributed import Client
        except ImportError:
            raise LightInvError(
                "running the precompute on a cluster (--scheduler) needs dask.distributed: "
                "pip install 'lightinv[cluster]'"
            ) from None
        try:
            self.client = Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
        except (OSError, TimeoutError) as exc:
            raise LightInvError(f"cannot reach the Dask scheduler at {address}: {exc}") from None
        self.address = address
        self._shared: dict[int, tuple[Any, Any]] = {}

    def share(self, obj: Any) -> Any:
        """A future of ``obj`` on every worker (scattered once per object and build, read
        by every piece)."""
        if id(obj) not in self._shared:
            fut = self.client.scatter(obj, broadcast=True, hash=False)
            self._shared[id(obj)] = (obj, fut)  # obj kept: its id stays its own
        return self._shared[id(obj)][1]

    def _argument(self, item: Any) -> Any:
        big = isinstance(item, np.ndarray) and item.nbytes > SCATTER_BYTES
        return self.client.scatter(item, hash=False) if big else item

    def map(
        self,
        fn: Callable,
        items: Sequence,
        *shared: Any,
        on_result: Callable[[int, Any], None],
        progress: ProgressFn | None = None,
        cancel: CancelFn | None = None,
    ) -> None:
        """Submit every piece, then ``on_result(i, result)`` in order as they finish.
        A cancel (polled every ``POLL`` s) cancels the pieces not yet taken back."""
        futures = [
            self.client.submit(fn, self._argument(item), *shared, pure=False) for item in items
        ]
        try:
            for i, fut in enumerate(futures):
                while not fut.done():
                    if cancel is not None and cancel():
                        raise CancelledError("operator build cancelled")
                    time.sleep(POLL)
                on_result(i, fut.result())  # a piece's error is raised here
                fut.release()
                if progress is not None:
                    progress((i + 1) / len(items))
        except BaseException:
            self.client.cancel(futures)
            raise

    def close(self) -> None:
        """Release the shared objects and disconnect (the cluster keeps running)."""
        if self._shared:
            self.client.cancel([fut for _, fut in self._shared.values()])
            self._shared.clear()
        self.client.close()


def runner(scheduler: str | None) -> LocalRunner | DaskRunner:
    """The runner of a build: here (``None``) or on the Dask scheduler at ``scheduler``."""
    return LocalRunner() if scheduler is None else DaskRunner(scheduler)


# -- the pieces (module-level functions: a worker imports and runs them) ---------------------

_CASTER_LOCK = threading.Lock()
_CASTERS: dict[str, Any] = {}


def _caster(patches):
    """This worker's ray caster of ``patches`` (one kept: its Embree scene is built once)."""
    from lightinv_core.transport.raycast import RayCaster

    key = patches.digest()
    with _CASTER_LOCK:
        if key not in _CASTERS:
            _CASTERS.clear()
            _CASTERS[key] = RayCaster(patches)
        return _CASTERS[key]


def trace_piece(batches: range, patches, rays: int, seed: int) -> list:
    """Form-factor rows of ray batches ``batches`` (``transport.formfactors.trace_pieces``)."""
    from lightinv_core.transport.formfactors import trace_pieces

    return trace_pieces(patches, rays, seed, batches, caster=_caster(patches))


def pieces(total: int, size: int) -> list[range]:
    """``range(total)`` cut into consecutive ranges of ``size`` (the last shorter)."""
    return [range(a, min(total, a + size)) for a in range(0, total, size)]
