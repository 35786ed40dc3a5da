# Registered linear solvers on an SPD system, multigrid with a hierarchy's operators.
import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as sla

import fairshape


@pytest.fixture(scope="module")
def system(cow):
    meshes, S = fairshape.subdivide(cow, 2, operators=True)
    H = fairshape.stretch_bend_hessian(meshes[-1], 0.1, 1.0)
    A = (H + 1e-3 * H.diagonal().mean() * sp.identity(H.shape[0])).tocsc()  # SPD: H plus a small mass term
    b = np.random.default_rng(7).standard_normal(A.shape[0])
    return A, b, S


def test_cholesky_equals_scipy(system):
    A, b, _ = system
    x, s = fairshape.solve(A, b)
    assert x.shape == b.shape and s.termination == "converged"
    ref = sla.spsolve(A, b)
    assert np.abs(x - ref).max() <= 1e-9 * np.abs(ref).max()


def test_multigrid_cg_with_level_operators(system):
    A, b, S = system
    x, s = fairshape.solve(A, b, solver="multigrid_cg", prolongations=S, tolerance=1e-10, max_iterations=300)
    assert s.succeeded and s.iterations > 1 and s.residual <= 1e-10
    ref = sla.spsolve(A, b)
    assert np.abs(x - ref).max() <= 1e-7 * np.abs(ref).max()


def test_multigrid_cycles_beat_gauss_seidel_sweeps(system):
    A, b, S = system
    cycles = [fairshape.solve(A, b, solver="multigrid", prolongations=S, tolerance=1e-12, max_iterations=k, check=False)[1]
              for k in (5, 50)]
    sweeps = fairshape.solve(A, b, solver="gauss_seidel", tolerance=1e-12, max_iterations=50, check=False)[1]
    assert cycles[0].termination == "max_iterations" and cycles[0].iterations == 5
    assert cycles[1].residual < 0.5 * cycles[0].residual  # the cycles keep reducing the residual
    assert cycles[1].residual < 0.2 * sweeps.residual     # the levels reach the smooth error sweeps leave


def test_multigrid_needs_levels_and_others_refuse_them(system):
    A, b, S = system
    with pytest.raises(fairshape.InvalidInput, match="prolongations"):
        fairshape.solve(A, b, solver="multigrid")
    with pytest.raises(fairshape.InvalidInput, match="not multilevel"):
        fairshape.solve(A, b, solver="cholesky", prolongations=S)
    with pytest.raises(fairshape.InvalidConfig, match="valid keys"):
        fairshape.solve(A, b, solver="conjugate_gradient", omega=1.2)
