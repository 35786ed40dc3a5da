"""Variational surface modeling (Welch & Witkin): a B-spline sheet under point and curve constraints."""

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _fairshape
from ._summary import Summary, SolveFailed


@dataclass
class SheetResult:
    """sheet: the solved sheet (a new fairshape.Sheet, refined where §4.4 asked); grid: it
    sampled at samples_per_span per base span, a (su·n + 1)×(sv·n + 1)×3 array (reshape(-1, 3):
    a sheet run's final.obj vertices); summary: termination, iterations, residual, message;
    max_constraint_error: the largest point distance / curve distance over the leaf cells (§4.4);
    constraint_residual ‖Ap − b‖_F; energy Q; constraint_rows, dropped_rows, spans_refined,
    refinement_rounds, analyze_s, solve_s, condition_estimate (None unless the solver gives it)."""

    sheet: _fairshape.Sheet
    grid: np.ndarray
    summary: Summary
    max_constraint_error: float
    constraint_residual: float
    energy: float
    constraint_rows: int
    dropped_rows: int
    spans_refined: int
    refinement_rounds: int
    analyze_s: float
    solve_s: float
    condition_estimate: Optional[float]


def _as2d(a, cols, what):
    A = np.asarray(a, dtype=np.float64)
    if A.size == 0:
        return np.zeros((0, cols))
    if A.ndim == 1:
        A = A.reshape(1, -1)
    if A.ndim != 2 or A.shape[1] != cols:
        raise _fairshape.InvalidInput(f"design_sheet: {what} must be k×{cols}, got shape {A.shape}")
    return A


def design_sheet(sheet, points_uv=(), targets=(), relative=False, curves=(), alpha=0.0, beta=1.0,
                 metric="thin_plate", formulation="mortar", solver="kkt", refinement_tolerance=0.0, max_level=4,
                 max_rounds=8, samples_per_span=6, implementation="optimized", check=True, **solver_options):
    """Solve a variational sheet (Welch & Witkin §4) under constraints, as one step of a sheet run.

    sheet: a fairshape.Sheet (spans, degree, size; its current shape is the start);
    points_uv: k×2 (u, v) in design units (the sheet's size), targets: k×3 world positions
    (relative=True: offsets from the sheet's current point there, a config's `by:`);
    curves: [(uv, space), ...], each an m×2 (u, v) polyline on the sheet held to a p×3 space
    polyline (a config's {type: curve} with its `uv:` and a `points:` curve), formulation
    'mortar' (weak rows, no locking) or 'paper' (eq. 7); alpha, beta: stretching and bending
    weights (numbers: α·I and β·1, or 2×2 matrices); metric 'thin_plate' (eq. 4) or
    'displacement'; solver: 'kkt' (eq. 9), 'qr_penalty' (eq. 10), 'range_space', ...
    (fairshape.qp_solvers()) with its options as keywords (a config's solver.<type> block; an
    unknown one raises InvalidConfig naming the valid ones); refinement_tolerance (0: off),
    max_level, max_rounds: §4.4's refinement. check=True raises SolveFailed (with .result)
    when the solve does not succeed. The GIL is released during the solve.
    """
    P = _as2d(points_uv, 2, "points_uv")
    T = _as2d(targets, 3, "targets")
    cs = []
    for c in curves:
        uv, space = c
        cs.append((_as2d(uv, 2, "a curve's uv"), _as2d(space, 3, "a curve's space points")))
    r = _fairshape._design_sheet(sheet, P, T, relative, cs, alpha, beta, metric, formulation, solver, solver_options,
                                 float(refinement_tolerance), max_level, max_rounds, implementation)
    summary = Summary.from_dict(r)
    s = r["sheet"]
    result = SheetResult(sheet=s, grid=s.grid(samples_per_span), summary=summary,
                         max_constraint_error=r["max_constraint_error"], constraint_residual=r["constraint_residual"],
                         energy=r["energy"], constraint_rows=r["constraint_rows"], dropped_rows=r["dropped_rows"],
                         spans_refined=r["spans_refined"], refinement_rounds=r["refinement_rounds"],
                         analyze_s=r["analyze_s"], solve_s=r["solve_s"], condition_estimate=r["condition_estimate"])
    if check and not summary.succeeded:
        raise SolveFailed(f"design_sheet: {summary.termination}: {summary.message}", result)
    return result


SheetResult.__module__ = "fairshape"
