"""A model of the CPU seconds a search's batch costs, counted from what it computes.

``auto`` (optimize/portfolio.py) shares its budget between two searches by their gain
per unit of work. The work is counted, never timed, so the same project and seed give
the same run on any machine and under any load (docs/project-file.md promises it).
This module holds the count: a batch costs

    BATCH[search] + NEW_RUN (when it began an IPOP run)
    + GEMM x the multiply-adds of its light + COPY x the operator entries copied

where the light's work is tallied by ``LightTally`` as the candidates are lit: the
receivers' lux ``Phi[:, cols] @ V[cols]`` (rows x k x m multiply-adds, rows x k entries
copied out of Phi; the whole Phi @ V, nothing copied, when most columns are lit), the
match error's Gram product (k x k x m; Cholesky's half of nz x nz x m when most columns
are lit), the luminaire arrays' lattice blend (rows x lattice x m).

The constants are a least-squares fit of measured CPU per batch on the benchmark's
problems (``bench/auto_work.py`` refits and prints them; one BLAS thread). The
previous model, evaluations plus a fixed cost per batch, missed by up to 2.5x in either
direction: on experiment 4 (a lux field on 24,569 patches) a VNS candidate costs as
much as a CMA-ES one, while on experiment 1 (the match's Gram product) it costs a fifth,
and ``cma``'s own Python is about 3 ms a generation at any scale.
"""

from __future__ import annotations

GEMM = 1.4e-10
"""CPU seconds per multiply-add of the light's products (float32, one BLAS thread)."""
COPY = 1.8e-9
"""CPU seconds per operator entry copied out (``Phi[:, cols]``: a strided gather)."""
BATCH = {"cmaes": 3.3e-3, "vns": 1.5e-3}
"""CPU seconds of a batch beside its light: the search's own Python (``cma``'s ask and
tell; VNS's moves) and ``DesignProblem.evaluate``'s fixed costs (decoding, rules,
goals)."""
NEW_RUN = 7e-3
"""CPU seconds of beginning a CMA-ES run (an IPOP restart: ``cma``'s set-up)."""


class LightTally:
    """The light's work counted so far by one problem's evaluations: ``madds``
    multiply-adds and ``copies`` operator entries copied (see the module docstring)."""

    def __init__(self) -> None:
        self.madds = 0.0
        self.copies = 0.0

    def field(self, rows: int, nz: int, k: int, m: int) -> None:
        """Lux at ``rows`` receivers of m candidates lighting k of nz zone columns
        (``LightModel.illuminance``: the whole product when 3 k > nz)."""
        if 3 * k > nz:
            self.madds += rows * nz * m
        else:
            self.madds += rows * k * m
            self.copies += rows * k

    def gram(self, k: int, nz: int, m: int) -> None:
        """The match error's quadratic term of m candidates lighting k of nz columns
        (``MatchTarget.error``: a triangular product over all nz when 2 k > nz)."""
        if 2 * k > nz:
            self.madds += nz * nz * m / 2
        else:
            self.madds += k * k * m
            self.copies += k * k

    def product(self, rows: int, inner: int, m: int) -> None:
        """A dense (rows x inner) @ (inner x m) product (the arrays' lattice blend)."""
        self.madds += rows * inner * m

    def seconds(self) -> float:
        """The modelled CPU seconds of the light counted so far."""
        return GEMM * self.madds + COPY * self.copies


def batch_seconds(search: str, light: float, new_run: bool = False) -> float:
    """Modelled CPU seconds of one batch of ``search`` whose light cost ``light``
    (``LightTally.seconds`` over the batch): see the module docstring."""
    return BATCH[search] + (NEW_RUN if new_run else 0.0) + light
