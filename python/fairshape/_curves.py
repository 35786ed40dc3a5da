"""Length-preserving multiresolution curve editing (Sauvage, Hahmann and Bonneau)."""

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _fairshape
from ._summary import Summary, SolveFailed


class Curve:
    """A multiresolution polyline: points (n×2 or n×3 float64), open or closed, decomposed by
    the lazy-wavelet filter bank into `levels` levels (−1: as many as n allows; an open curve of
    2^L·k + 1 points, a closed one of 2^L·k with k ≥ 3, has levels 0..L).

    .points is a read-only copy of the input (n×d); .level(j) the control points of level j
    (m_j×d, a new array; level(levels) is the curve itself); .details(j) the details d^j.
    """

    def __init__(self, points, closed=False, levels=-1, implementation="optimized"):
        P = np.array(points, dtype=np.float64)  # a copy: the curve does not change under its owner
        if P.ndim != 2 or P.shape[1] not in (2, 3):
            raise _fairshape.InvalidInput(f"Curve: expected an n×2 or n×3 array of points, got shape {P.shape}")
        P.setflags(write=False)
        self.points = P
        self.closed = bool(closed)
        self.implementation = implementation
        most = _fairshape.curve_max_levels(P.shape[0], self.closed)
        if levels > most:
            raise _fairshape.InvalidInput(
                f"Curve: {levels} levels need {'2^L·k points (k ≥ 3)' if self.closed else '2^L·k + 1 points'}; "
                f"{P.shape[0]} points allow {most}")
        self.levels = most if levels < 0 else int(levels)

    @property
    def dim(self):
        return self.points.shape[1]

    @property
    def n_points(self):
        return self.points.shape[0]

    def level(self, j):
        """Control points of level j (0 = coarsest .. levels): an m_j×d array."""
        X = _fairshape._curve_level(self.points, self.closed, self.levels, j, self.implementation)
        return X[:, :self.dim]

    def details(self, j):
        """Details d^j (j = 0 .. levels−1) of the lazy-wavelet analysis: level j+1's odd points
        minus the midpoints of level j's (an m×d array, m the number of level-(j+1) odd points)."""
        D = _fairshape._curve_details(self.points, self.closed, self.levels, j, self.implementation)
        return D[:, :self.dim]

    def __repr__(self):
        return f"Curve({self.n_points} points, {'closed' if self.closed else 'open'}, {self.levels} levels, {self.dim}-D)"


@dataclass
class CurveEditResult:
    """points: the edited curve C_F (n×d, a new array); points3: it as the library keeps it, n×3
    (a 2-D curve is edited as a space curve with z = 0; a solve may leave it: metrics['out_of_plane']
    is max |z|); curve: it as a new Curve (same levels);
    edited, attracting: the loop's C_D and C_A (n×d); summary: termination ('converged' is the
    only success), iterations = linear solves, residual = the solver's relative length error,
    message; the runs.csv metrics of a curve run: length_error_max (max relative segment-length
    change from the input), total_length_error, min_reduced_hessian_eig (None when not
    judged), stationarity, solves, outer_iterations, wrinkles, ...; metrics: all of them."""

    points: np.ndarray
    points3: np.ndarray
    curve: Curve
    edited: np.ndarray
    attracting: np.ndarray
    summary: Summary
    solves: int
    outer_iterations: int
    length_error_max: float
    total_length_error: float
    length_constraint: str
    min_reduced_hessian_eig: Optional[float]
    stationarity: Optional[float]
    metrics: dict


_LENGTHS = ("segment_lengths", "total_length")


def edit_curve(curve, level, indices, offsets=None, chord_scale=None, wrinkle_level=-1, length="segment_lengths",
               constraints=(), beta=0.5, smoothness="bending", solver="linearized", explicit_step="local",
               details="local_frames", solve_region="support", drag_steps=1, check=True, **solver_options):
    """One editing loop of Sauvage et al. §4.1 on `curve` (a Curve, or an n×2/n×3 array: an open
    Curve of as many levels as it allows), as an `edits:` entry of a curve config runs it.

    level: e, the level whose control points move (0 = coarsest); indices: k level-e control
    points (negative: from the end); offsets: k×d (or one d-vector for all) displacements, or
    chord_scale: k scales (or one) moving each point along the chord from control point 0 so
    the chord becomes that many times as long (give exactly one of offsets and chord_scale);
    wrinkle_level: w in [e, levels−1] for the explicit length step at level w+1 (−1: none);
    length: 'segment_lengths' (every segment's, the paper's), 'total_length', or a constraint
    dict ({'type': 'total_length', 'value': 2.0}); constraints: more constraint dicts
    ({'type': 'pin', 'points': 'endpoints'}, {'type': 'tangent', ...}); beta: eq. 2's
    (1−β)·smoothness + β·distance to C_A; smoothness: a registered curve energy;
    solver: 'linearized', 'trust_region', ... (fairshape.curve_components()['solvers']) with its
    options as keywords: length_tolerance=, stationarity_tolerance=, max_solves=,
    second_order='inertia'|'dense'|'off' (how the answer is judged at second order) and the
    solver's own (linearization='newton', initial_radius=, ...); an unknown one raises
    InvalidConfig naming the valid ones. explicit_step 'local'|'sweep', details
    'local_frames'|'global', solve_region 'support'|'curve': the config's editing: block.
    drag_steps: the move split into that many loops, each from the previous result.
    check=True raises SolveFailed (with .result) unless the solve converged.
    The GIL is released during the loop.
    """
    if not isinstance(curve, Curve):
        curve = Curve(curve)
    idx = np.atleast_1d(np.asarray(indices, dtype=np.int64)).ravel()
    if (offsets is None) == (chord_scale is None):
        raise _fairshape.InvalidConfig("edit_curve: give exactly one of offsets and chord_scale")
    if offsets is not None:
        off = np.asarray(offsets, dtype=np.float64)
        if off.ndim == 1:
            off = np.tile(off, (len(idx), 1))
        scales = [0.0] * len(idx)
    else:
        off = np.zeros((len(idx), 3))
        scales = np.broadcast_to(np.asarray(chord_scale, dtype=np.float64), (len(idx),)).tolist()
        if any(s <= 0 for s in scales):
            raise _fairshape.InvalidConfig("edit_curve: chord_scale must be > 0")
    if isinstance(length, str):
        if length not in _LENGTHS:
            raise _fairshape.InvalidConfig(f"length '{length}': expected one of {', '.join(_LENGTHS)} (or a constraint dict)")
        length = {"type": length}
    if isinstance(constraints, dict):
        constraints = [constraints]
    cons = [dict(length)] + [dict(c) for c in constraints]
    r = _fairshape._edit_curve(curve.points, curve.closed, curve.levels, level, wrinkle_level, idx.tolist(), off,
                               scales, drag_steps, smoothness, float(beta), cons, solver, solver_options,
                               explicit_step, details, solve_region, curve.implementation)
    d = curve.dim
    final = r["final"][:, :d]
    summary = Summary.from_dict(r)
    metrics = {k: v for k, v in r.items() if k not in ("final", "edited", "attracting", "reference")}
    metrics["out_of_plane"] = float(np.abs(r["final"][:, 2]).max()) if d == 2 and len(final) else 0.0
    result = CurveEditResult(points=final, points3=r["final"], curve=Curve(final, curve.closed, curve.levels, curve.implementation),
                             edited=r["edited"][:, :d], attracting=r["attracting"][:, :d], summary=summary,
                             solves=r["solves"], outer_iterations=r["outer_iterations"],
                             length_error_max=r["length_error_max"], total_length_error=r["total_length_error"],
                             length_constraint=r["length_constraint"],
                             min_reduced_hessian_eig=r["min_reduced_hessian_eig"], stationarity=r["stationarity"],
                             metrics=metrics)
    if check and not summary.succeeded:
        raise SolveFailed(f"edit_curve: {summary.termination}: {summary.message}", result)
    return result


for _cls in (Curve, CurveEditResult):
    _cls.__module__ = "fairshape"
