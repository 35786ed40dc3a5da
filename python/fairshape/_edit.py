"""The constrained edit (Boier-Martin et al. §4.3) on a level of a MultiresSurface."""

from dataclasses import dataclass

import numpy as np

from . import _fairshape
from ._summary import Summary, SolveFailed


@dataclass
class EditResult:
    """delta: n×3 float64 deformation of the edited level (a new array); positions: that level's
    rest positions + delta; hierarchy: a new MultiresSurface with the edit synthesized to the
    finest level (local details kept); summary: how the solve ended; plus timings (s), the
    constraint residual ‖AΔP − C‖_F and counts. flipped_faces: faces of the finest level turned
    over against the rest surface; normal_error_deg: the largest angle of a normal constraint's
    achieved normal from its target (−1 without one). Either a fold or a normal met by its
    reverse ends the edit `folded`, never a success."""

    delta: np.ndarray
    positions: np.ndarray
    hierarchy: _fairshape.MultiresSurface
    summary: Summary
    level: int
    n_dofs: int
    constrained_vertices: int
    constraint_residual: float
    analyze_s: float
    solve_s: float
    flipped_faces: int
    normal_error_deg: float


def _flatten(terms, what):
    if isinstance(terms, dict):
        terms = [terms]
    out = []
    for t in terms:
        if isinstance(t, (list, tuple)):
            out.extend(t)
        elif isinstance(t, dict):
            out.append(t)
        else:
            raise TypeError(f"{what}: expected dicts (fairshape.{what[:-1]}(...)), got {type(t).__name__}")
    return out


def edit(hierarchy, energies, constraints, level=-1, mode="paper", solver=None, formulation="displacement",
         implementation="optimized", check=True, **options):
    """Minimize ½ Σ_c ΔP_cᵀ H ΔP_c − gᵀΔP subject to A ΔP = C on one level of `hierarchy`.

    energies: energy dicts (fairshape.energy('detail_preserving', alpha=0.1, beta=1.0), ...);
    constraints: constraint dicts (fairshape.fixed(ids), fairshape.position(ids, offset),
    fairshape.constraint('normal', ...)), ids on their own level (default the finest);
    level: the level solved (-1 the finest); mode: 'paper' (§4.3: constrained vertices by
    least squares, the free ones by `solver`), 'kkt', 'qr_penalty' or 'range_space' (exact
    constrained solvers); solver (paper mode only, default 'cholesky'): a registered solver;
    formulation: 'displacement' or 'position' (energies of P_rest + ΔP); **options: the solver's
    options as in a config's solver: block (paper mode: tolerance=, max_iterations=,
    sor={'omega': 1.5}, ...) or the QP mode's problem.<mode> block. An unknown option raises
    InvalidConfig naming the valid ones.
    check=True raises SolveFailed (with .result) when the solve does not succeed.
    The GIL is released during assembly and solve.
    """
    energies = _flatten(energies, "energies")
    constraints = _flatten(constraints, "constraints")
    r = _fairshape._edit(hierarchy, energies, constraints, level, mode, solver, formulation, implementation, options)
    summary = Summary.from_dict(r)
    rest = hierarchy.positions(r["level"])
    result = EditResult(delta=r["delta"], positions=rest + r["delta"], hierarchy=r["hierarchy"], summary=summary,
                        level=r["level"], n_dofs=r["n_dofs"], constrained_vertices=r["constrained_vertices"],
                        constraint_residual=r["constraint_residual"], analyze_s=r["analyze_s"], solve_s=r["solve_s"],
                        flipped_faces=r["flipped_faces"], normal_error_deg=r["normal_error_deg"])
    if check and not summary.succeeded:
        raise SolveFailed(f"edit: {summary.termination}: {summary.message}", result)
    return result
