# H from the bindings is the command line's H (`fairshape energy`), read back by SciPy.
import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

import fairshape
from conftest import cli


@pytest.mark.parametrize("mesh,level,alpha,beta", [("data/cow.off", 1, 0.1, 1.0), ("data/torus_quad.off", 2, 0.5, 0.25)])
def test_hessian_equals_cli(tmp_path, mesh, level, alpha, beta):
    out = tmp_path / "H.mtx"
    cli("energy", mesh, "--level", level, "--alpha", alpha, "--beta", beta, "--out", out)
    H_cli = sp.csr_matrix(scipy.io.mmread(str(out)))
    m = fairshape.read_mesh(mesh)
    fine = fairshape.subdivide(m, level)[-1]
    H = fairshape.stretch_bend_hessian(fine, alpha, beta)
    assert isinstance(H, sp.csr_matrix) and H.dtype == np.float64
    assert H.shape == H_cli.shape == (fine.n_vertices, fine.n_vertices)
    scale = abs(H_cli).max()
    assert abs(H - H_cli).max() <= 1e-12 * scale
    # The properties that make it an energy: symmetric, constants in its null space.
    assert abs(H - H.T).max() <= 1e-12 * scale
    assert np.abs(H @ np.ones(H.shape[0])).max() <= 1e-9 * scale


def test_registered_energies_by_name(cow):
    H = fairshape.energy_hessian(cow, "membrane", weight=2.0)
    H1 = fairshape.energy_hessian(cow, "membrane")
    assert abs(H - 2.0 * H1).max() <= 1e-12 * abs(H).max()
    D = fairshape.energy_hessian(cow, "detail_preserving", alpha=0.1, beta=1.0)
    assert abs(D - fairshape.stretch_bend_hessian(cow, 0.1, 1.0)).max() <= 1e-12 * abs(D).max()


def test_components_list_registries():
    c = fairshape.components()
    assert {"energies", "constraints", "solvers"} <= set(c)
    assert "detail_preserving" in c["energies"] and "multigrid" in c["solvers"]
    assert "alpha" in c["energies"]["detail_preserving"]["options"]
