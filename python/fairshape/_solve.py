"""A registered linear solver on A x = b (A symmetric positive definite)."""

import numpy as np

from . import _fairshape
from ._summary import Summary, SolveFailed


def solve(A, b, solver="cholesky", prolongations=None, x0=None, implementation="optimized", check=True, **options):
    """Solve A x = b with a registered solver ('cholesky', 'gauss_seidel', 'sor',
    'conjugate_gradient', 'multigrid', 'multigrid_cg'; fairshape.components()['solvers']).

    A: n×n symmetric scipy.sparse matrix (converted to CSC float64; every registered solver
    assumes symmetry, so a non-symmetric or empty A raises InvalidInput, a ValueError, naming the
    solver and the unequal entries); b: n or n×k float64 (k right-hand
    sides); prolongations (multigrid, multigrid_cg): [P_0, ..., P_{L-1}], P_l an n_{l+1}×n_l
    sparse matrix, the last ending at n (a hierarchy's subdivision_operator(l)); x0: start of
    iterative solvers (b's shape); **options: the config's solver: block (tolerance=,
    max_iterations=, multigrid={'cycle': 'v', ...}); an unknown one raises InvalidConfig.
    Returns (x, Summary), x with b's shape (a new array). A solve whose relative residual
    misses its tolerance (tolerance=, else the solver's default, else 1e-6 for a direct solver)
    is numerical_failure, never succeeded. check=True raises SolveFailed on a failed solve. The GIL is released during the solve.
    """
    import scipy.sparse as sp

    A = sp.csc_matrix(A, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    vector = b.ndim == 1
    B = b.reshape(-1, 1) if vector else b
    X0 = None if x0 is None else np.asarray(x0, dtype=np.float64).reshape(B.shape)
    P = [sp.csc_matrix(p, dtype=np.float64) for p in (prolongations or [])]
    x, s = _fairshape._solve(A, B, solver, P, X0, implementation, options)
    summary = Summary.from_dict(s)
    x = x.reshape(-1) if vector else x
    if check and not summary.succeeded:
        raise SolveFailed(f"solve: {summary.termination}: {summary.message}", (x, summary))
    return x, summary
