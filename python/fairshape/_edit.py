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


@dataclass
class SessionStep:
    """One solve of a SurfaceEditSession, measured on its result: summary (a fold or a normal
    met by its reverse ends it `folded`, never a success); accuracy: the mode it was solved with
    ('single-level', 'interactive', 'improved', 'converged'); delta: the edit level's n×3
    deformation (a new array); energy of the result; constraint_residual ‖AΔP − C‖_F;
    flipped_faces and normal_error_deg (−1 without a normal constraint) of the finest level;
    analyze_s (the prepared problem's set-up), solve_s and check_s (this step's solve and checks)."""

    summary: Summary
    accuracy: str
    delta: np.ndarray
    level: int
    n_dofs: int
    energy: float
    constraint_residual: float
    constrained_vertices: int
    flipped_faces: int
    normal_error_deg: float
    analyze_s: float
    solve_s: float
    check_s: float
    rotation_rounds: int


def _step(r):
    return SessionStep(summary=Summary.from_dict(r), accuracy=r["accuracy"], delta=r["delta"], level=r["level"],
                       n_dofs=r["n_dofs"], energy=r["energy"], constraint_residual=r["constraint_residual"],
                       constrained_vertices=r["constrained_vertices"], flipped_faces=r["flipped_faces"],
                       normal_error_deg=r["normal_error_deg"], analyze_s=r["analyze_s"], solve_s=r["solve_s"],
                       check_s=r["check_s"], rotation_rounds=r["rotation_rounds"])


class SurfaceEditSession:
    """Boier-Martin et al.'s edit, step by step, with the prepared problem (H, the propagated
    rows, the factorizations and multigrid set-ups) kept between steps.

    Built from a surface-edit config's keys — a dict `config` and/or keywords (input=, energy=,
    constraints=, problem=, solver=, implementation=, seed=, ...) — read by the run kind's own
    reader, so an unknown key or value is refused naming the valid ones. hierarchy: a
    MultiresSurface to edit instead of `input.mesh` (`input` then holds only edit_level).
    search_dirs: where a relative input.mesh is looked for after the working directory.

    Handles are the constraints, numbered 0, 1, … in the order the session made them:
    move(handle, offset) sets where its points go (their displacement from rest; a drag step:
    nothing is analysed again), scale(s) sets every target to s × its configured offset (the
    config's problem.drag_steps), add(constraint dict) returns a new handle, remove(handle).
    solve(mode=None) solves with problem.accuracy, or §5's 'interactive' | 'improved' |
    'converged' on the config's ladder; it returns a SessionStep and raises SolveFailed unless
    it succeeded (check=False returns it anyway). replay() solves the config's `steps:` in turn,
    as `fairshape run` does. vertices: the finest level now (a new array); hierarchy: a new
    MultiresSurface of it. The GIL is released while the session assembles and solves.
    """

    def __init__(self, config=None, *, hierarchy=None, search_dirs=(), **keys):
        cfg = dict(config or {})
        clash = sorted(set(cfg) & set(keys))
        if clash:
            raise _fairshape.InvalidConfig(f"{', '.join(clash)}: given both in config and as a keyword")
        cfg.update(keys)
        if isinstance(cfg.get("steps"), (list, tuple)):  # handles as YAML keys: {1: [...]} reads as {'1': [...]}
            cfg["steps"] = [dict(st, offsets={str(h): o for h, o in st["offsets"].items()})
                            if isinstance(st, dict) and isinstance(st.get("offsets"), dict) else st for st in cfg["steps"]]
        self._session = _fairshape._SurfaceEditSession(cfg, hierarchy, [".", *(str(d) for d in search_dirs)])

    def move(self, handle, offset):
        self._session.move(int(handle), np.asarray(offset, dtype=np.float64).reshape(3))

    def scale(self, s):
        self._session.scale(float(s))

    def add(self, constraint):
        return self._session.add(dict(constraint))

    def remove(self, handle):
        self._session.remove(int(handle))

    def solve(self, mode=None, check=True):
        step = _step(self._session.solve(mode))
        if check and not step.summary.succeeded:
            raise SolveFailed(f"edit: {step.summary.termination}: {step.summary.message}", step)
        return step

    def replay(self, check=True):
        steps = [_step(r) for r in self._session.replay()]
        failed = [s for s in steps if not s.summary.succeeded]
        if check and failed:
            raise SolveFailed(f"edit: {failed[0].summary.termination}: {failed[0].summary.message}", steps)
        return steps

    @property
    def vertices(self):
        return self._session.vertices

    @property
    def hierarchy(self):
        return self._session.hierarchy

    @property
    def level(self):
        return self._session.level

    @property
    def handles(self):
        return self._session.handles

    @property
    def preparations(self):
        """How many times a solve prepared its problem: a drag step adds none."""
        return self._session.preparations


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
    One solve of a SurfaceEditSession (keep the session to edit step by step).
    The GIL is released during assembly and solve.
    """
    energies = _flatten(energies, "energies")
    constraints = _flatten(constraints, "constraints")
    if not energies:
        raise _fairshape.InvalidConfig("energies: at least one energy term is required, e.g. "
                                       "[{'type': 'detail_preserving', 'alpha': 0.1, 'beta': 1.0}]")
    levels = hierarchy.levels
    lvl = level if level >= 0 else levels + 1 + level
    if not 0 <= lvl <= levels:
        raise _fairshape.InvalidIndex(f"edit: level {level} is not in the hierarchy (levels 0..{levels}, or -1 for the finest)")
    problem = {"constraint_mode": mode, "formulation": formulation}
    config = {"name": "edit", "implementation": implementation, "input": {"edit_level": lvl}, "energy": energies,
              "constraints": constraints, "problem": problem}
    if mode == "paper":
        if "type" in options:
            raise _fairshape.InvalidConfig("solver options: give the solver by solver=NAME, not type=")
        config["solver"] = {"type": solver or "cholesky", **options}
    elif solver is not None:
        raise _fairshape.InvalidConfig(f"solver='{solver}': mode '{mode}' solves the whole constrained system itself; "
                                       "the solver is used by mode 'paper' only")
    elif options:
        problem[mode] = dict(options)  # problem.<mode>: the QP mode's own options
    session = SurfaceEditSession(config, hierarchy=hierarchy)
    step = session.solve(check=False)
    rest = hierarchy.positions(step.level)
    result = EditResult(delta=step.delta, positions=rest + step.delta, hierarchy=session.hierarchy, summary=step.summary,
                        level=step.level, n_dofs=step.n_dofs, constrained_vertices=step.constrained_vertices,
                        constraint_residual=step.constraint_residual, analyze_s=step.analyze_s, solve_s=step.solve_s,
                        flipped_faces=step.flipped_faces, normal_error_deg=step.normal_error_deg)
    if check and not step.summary.succeeded:
        raise SolveFailed(f"edit: {step.summary.termination}: {step.summary.message}", result)
    return result
