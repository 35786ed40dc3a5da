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


@dataclass
class CurveStep:
    """One editing loop of a CurveSession (Sauvage et al. §4.1), measured on its result.

    index: 0, 1, ... in the session's order (the config's edit k); drag_step of drag_steps: its
    place in a drag; summary: the solve's outcome, then the step's checks' (edit_undone: the
    handles were pulled back or returned; constraints_unmet: attracting-curve lengths the
    explicit step could not place, or a planar curve that left its plane; folded: new
    self-crossings), the message saying why; points: C_F (n×d, a new array), points3: it n×3;
    reference, edited, attracting: C_R, C_D, C_A (n×d); checks: what the step measured
    (length_error_max against the session's original curve, total_length_error, handle_reach,
    out_of_plane, self_crossings, min_reduced_hessian_eig per the solver's second_order, ...);
    solve_converged: the solve alone converged (a run stops at the first that did not);
    solve_s: the editing loop's seconds, check_s: the checks'."""

    index: int
    drag_step: int
    drag_steps: int
    summary: Summary
    points: np.ndarray
    points3: np.ndarray
    reference: np.ndarray
    edited: np.ndarray
    attracting: np.ndarray
    checks: dict
    solve_converged: bool
    solves: int
    outer_iterations: int
    moved_points: list
    solve_s: float
    check_s: float
    explicit_s: float

    @property
    def succeeded(self):
        return self.summary.succeeded


class CurveSession:
    """A length-preserving editing session (Sauvage, Hahmann and Bonneau) on `curve` (a Curve, or
    an n×2/n×3 array: an open Curve of as many levels as it allows): the hierarchy, objective and
    solver prepared once, then edits one editing loop at a time, each from the curve the previous
    one left, every one keeping the lengths of the curve the session started from.

    Keywords are a curve config's blocks, read by the same reader as `fairshape run`:
    editing={'explicit_step': 'local', 'details': 'local_frames', 'solve_region': 'support',
    'plane': 'keep', 'partial_edit': 'fail'}, optimization={'beta': 0.5, 'smoothness': 'bending',
    'constraints': [{'type': 'segment_lengths'}, ...], 'solver': {'type': 'linearized', ...}};
    an unknown key raises InvalidConfig naming the valid ones.

    .edit(level, moves, wrinkle_level=-1): one editing loop; moves as a config's
    [{'index': i, 'by': [x, y(, z)]} | {'index': i, 'chord_scale': s}]. .drag_step(level, moves,
    drag_steps, wrinkle_level=-1): the next of drag_steps equal shares of the moves (a config's
    drag_steps); the last one judges how much of the whole drag the handles kept. Both return a
    CurveStep and release the GIL while they run. .curve: the current curve (a new Curve);
    .outcome(): the session's verdict so far, as a run's termination and message (a Summary).
    """

    def __init__(self, curve, **options):
        if not isinstance(curve, Curve):
            curve = Curve(curve)
        self._dim = curve.dim
        self._closed = curve.closed
        self._implementation = curve.implementation
        self._session = _fairshape._CurveSession(curve.points, curve.closed, curve.levels, curve.implementation, options)

    @property
    def levels(self):
        return self._session.levels

    @property
    def points(self):
        return self._session.points[:, :self._dim]

    @property
    def curve(self):
        return Curve(self.points, self._closed, self.levels, self._implementation)

    def edit(self, level, moves, wrinkle_level=-1):
        return self._step(self._session.edit({"level": level, "wrinkle_level": wrinkle_level, "moves": list(moves)}))

    def drag_step(self, level, moves, drag_steps, wrinkle_level=-1):
        return self._step(self._session.drag_step({"level": level, "wrinkle_level": wrinkle_level, "moves": list(moves),
                                                   "drag_steps": drag_steps}))

    def outcome(self):
        return Summary.from_dict(self._session.outcome())

    def _step(self, r):
        d = self._dim
        return CurveStep(index=r["index"], drag_step=r["drag_step"], drag_steps=r["drag_steps"], summary=Summary.from_dict(r),
                         points=r["final"][:, :d], points3=r["final"], reference=r["reference"][:, :d],
                         edited=r["edited"][:, :d], attracting=r["attracting"][:, :d], checks=r["checks"],
                         solve_converged=r["solve_converged"], solves=r["solves"], outer_iterations=r["outer_iterations"], moved_points=r["moved_points"],
                         solve_s=r["solve_s"], check_s=r["check_s"], explicit_s=r["explicit_s"])


_LENGTHS = ("segment_lengths", "total_length")
# The tolerances every length solver shares (a config's solver: block); the rest are the chosen
# solver's own (its sub-block).
_SHARED_SOLVER_KEYS = ("length_tolerance", "stationarity_tolerance", "max_solves", "second_order")


def edit_curve(curve, level, indices, offsets=None, chord_scale=None, wrinkle_level=-1, length="segment_lengths",
               constraints=(), beta=0.5, smoothness="bending", solver="linearized", explicit_step="local",
               details="local_frames", solve_region="support", drag_steps=1, check=True, **solver_options):
    """One edit of Sauvage et al. §4.1 on `curve` (a Curve, or an n×2/n×3 array: an open Curve of
    as many levels as it allows) through a CurveSession, as an `edits:` entry of a curve config
    runs it.

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
    drag_steps: the move split into that many loops, each from the previous result (stopping at
    a solve that fails, as a run does). The summary is the session's verdict, as a run's.
    check=True raises SolveFailed (with .result) unless it succeeded.
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
        if off.shape != (len(idx), off.shape[1]) or off.shape[1] not in (2, 3):
            raise _fairshape.InvalidInput(f"edit_curve: offsets must be k×2 or k×3 for k = {len(idx)} indices, got {off.shape}")
        moves = [{"index": int(i), "by": o} for i, o in zip(idx, off)]
    else:
        scales = np.broadcast_to(np.asarray(chord_scale, dtype=np.float64), (len(idx),))
        if any(s <= 0 for s in scales):
            raise _fairshape.InvalidConfig("edit_curve: chord_scale must be > 0")
        moves = [{"index": int(i), "chord_scale": float(s)} for i, s in zip(idx, scales)]
    if isinstance(length, str):
        if length not in _LENGTHS:
            raise _fairshape.InvalidConfig(f"length '{length}': expected one of {', '.join(_LENGTHS)} (or a constraint dict)")
        length = {"type": length}
    if isinstance(constraints, dict):
        constraints = [constraints]
    known = _fairshape.curve_components()["solvers"]
    if solver not in known:  # the keyword's own name (the session's reader names optimization.solver.type)
        raise _fairshape.InvalidConfig(f"solver '{solver}': not a registered length solver (known: {', '.join(known)})")
    solver_block = {"type": solver}
    own = {k: v for k, v in solver_options.items() if k not in _SHARED_SOLVER_KEYS}
    solver_block.update({k: v for k, v in solver_options.items() if k in _SHARED_SOLVER_KEYS})
    if own:
        solver_block[solver] = own
    session = CurveSession(curve, editing={"explicit_step": explicit_step, "details": details, "solve_region": solve_region},
                           optimization={"beta": beta, "smoothness": smoothness, "solver": solver_block,
                                         "constraints": [dict(length)] + [dict(c) for c in constraints]})
    for _ in range(drag_steps):
        step = session.drag_step(level, moves, drag_steps, wrinkle_level)
        if not step.solve_converged:  # a run stops at the first solve that fails
            break
    totals = session._session.outcome()
    summary = Summary.from_dict(totals)
    d = curve.dim
    metrics = dict(step.checks)
    metrics.update(levels=curve.levels, termination=summary.termination, succeeded=summary.succeeded,
                   iterations=summary.iterations, residual=summary.residual, message=summary.message,
                   solves=summary.iterations, drag_steps_done=step.index + 1, moved_points=step.moved_points,
                   outer_iterations=totals["outer_iterations"], explicit_s=totals["explicit_s"], solve_s=totals["solve_s"],
                   time_s=totals["time_s"])
    metrics["out_of_plane"] = float(np.abs(step.points3[:, 2]).max()) if d == 2 and len(step.points) else 0.0
    result = CurveEditResult(points=step.points, points3=step.points3, curve=session.curve, edited=step.edited,
                             attracting=step.attracting, summary=summary, solves=summary.iterations,
                             outer_iterations=totals["outer_iterations"], length_error_max=step.checks["length_error_max"],
                             total_length_error=step.checks["total_length_error"],
                             length_constraint=step.checks["length_constraint"],
                             min_reduced_hessian_eig=step.checks["min_reduced_hessian_eig"],
                             stationarity=step.checks["stationarity"], metrics=metrics)
    if check and not summary.succeeded:
        raise SolveFailed(f"edit_curve: {summary.termination}: {summary.message}", result)
    return result


for _cls in (Curve, CurveEditResult, CurveSession, CurveStep):
    _cls.__module__ = "fairshape"
