"""Static options of the journal bearing's two films: :class:`JournalOptions` (the infinitely
long bearing) and :class:`FiniteJournalOptions` (``journal_bearing(..., length=L)``)."""
from __future__ import annotations

import dataclasses

from ..._core import checks
from ...films.film2d import SPACINGS


KRYLOV_MIN_N = 1024  # linear_solver="auto": dense LU up to this many elements, GMRES above


@dataclasses.dataclass(frozen=True)
class JournalOptions:
    """Static options of :func:`journal_bearing`: ``n`` elements (even, >= 16), Newton
    tolerance ``tol`` (max-norm of the scaled equations; None: 1e-10 in float64, raised to
    the round-off floor 4 eps (n / 2 pi)^2 of the cell balances above n ~ 4000 (a second
    difference of pressures over a cell width squared); 1e-4 in float32), ``max_iter``
    Newton steps per solve, at most ``stages`` continuation solves,
    ``strategy`` "auto" (direct Newton, continuation if that fails), "newton" or
    "continuation"; ``linear_solver`` of each Newton step: "dense" (LU of the AD Jacobian,
    O(n^3)), "krylov" (matrix-free GMRES preconditioned by the film's tridiagonal Jacobian
    plus the bodies' compliance on its lowest ``krylov_modes`` Fourier modes, O(n log n)
    per product) or "auto" (Krylov above n = 1024)."""

    n: int = 256
    tol: float | None = None
    max_iter: int = 40
    stages: int = 40
    strategy: str = "auto"
    linear_solver: str = "auto"
    krylov_modes: int = 32

    def __post_init__(self):
        checks.option_count("n", self.n, 16)
        if self.n % 2:
            raise ValueError(f"n must be even, got {self.n}")
        if self.tol is not None:
            checks.option_number("tol", self.tol)
        checks.option_count("max_iter", self.max_iter)
        checks.option_count("stages", self.stages)
        checks.one_of("strategy", self.strategy, ("auto", "newton", "continuation"))
        checks.one_of("linear_solver", self.linear_solver, ("auto", "dense", "krylov"))
        checks.option_count("krylov_modes", self.krylov_modes, 2)

    @property
    def krylov(self) -> bool:
        return self.linear_solver == "krylov" or (self.linear_solver == "auto" and self.n > KRYLOV_MIN_N)


KRYLOV_MIN_CELLS = 512    # linear_solver="auto": a dense LU with deformable bodies up to this many cells


@dataclasses.dataclass(frozen=True)
class FiniteJournalOptions:
    """Static options of the finite bearing (``journal_bearing(..., length=L)``): ``n`` cells in
    theta (even, >= 8), ``m`` axial intervals (even, >= 2: m + 1 nodes, the end ones at ambient
    pressure), axial ``spacing`` "uniform" or "cosine" (nodes clustered at the ends, for long
    bearings whose pressure drops to ambient within about R of the ends), Newton tolerance
    ``tol`` (max-norm of the scaled equations; None: 1e-10 in float64, 1e-4 in float32),
    ``max_iter`` Newton steps, ``nested``: whether a cold solve on a grid of at least 2048 cells
    starts from a coarser grid's solution (True; False: from the rigid estimate, where a coarse
    grid cannot carry the load: a soft body's thin film), and, with deformable bodies, the
    ``linear_solver`` of each Newton step, of the implicit derivatives and of the dynamic
    coefficients' whirl solves: "dense" (LU of the AD Jacobian, O(N^3) for N = n (m - 1)
    cells), "krylov" (matrix-free GMRES, O(N log N) per product, preconditioned by the film's
    block-tridiagonal Jacobian with each node's own compliance: :func:`linear_model`) or "auto"
    (Krylov above KRYLOV_MIN_CELLS cells). Rigid bodies: the exact block solve, or GMRES with a
    multigrid V-cycle on grids wider than EXACT_WIDTH cells (:func:`linear_model`). The default
    64 x 16 is for a quick look; K and C under Reynolds conditions change by at most 0.33% from
    128 x 32 to the next grid and 0.06% from 256 x 64 (docs/benchmarks_history.md, grid study)."""

    n: int = 64
    m: int = 16
    spacing: str = "uniform"
    tol: float | None = None
    max_iter: int = 60
    linear_solver: str = "auto"
    nested: bool = True

    def __post_init__(self):
        checks.option_count("n", self.n, 8)
        checks.option_count("m", self.m, 2)
        if self.n % 2 or self.m % 2:
            raise ValueError(f"n and m must be even, got n={self.n}, m={self.m}")
        checks.one_of("spacing", self.spacing, SPACINGS)
        if self.tol is not None:
            checks.option_number("tol", self.tol)
        checks.option_count("max_iter", self.max_iter)
        checks.one_of("linear_solver", self.linear_solver, ("auto", "dense", "krylov"))
        if not isinstance(self.nested, bool):
            raise ValueError(f"nested must be True or False, got {self.nested!r}")

    @property
    def krylov(self) -> bool:
        """Whether deformable bodies' Newton steps and derivatives are solved by GMRES."""
        return self.linear_solver == "krylov" or (self.linear_solver == "auto"
                                                  and self.n * (self.m - 1) > KRYLOV_MIN_CELLS)
