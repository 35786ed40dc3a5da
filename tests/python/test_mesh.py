# Meshes as arrays: shapes and dtypes, exact round trips through files, what is a view.
import numpy as np
import pytest

import fairshape
from conftest import cli


def test_arrays_have_documented_shapes(cow):
    assert cow.V.shape == (cow.n_vertices, 3) and cow.V.dtype == np.float64
    assert cow.F.shape == (cow.n_faces, 3) and cow.F.dtype == np.int32
    assert cow.F.min() == 0 and cow.F.max() == cow.n_vertices - 1


def test_mesh_from_arrays_equals_mesh_read(cow):
    m = fairshape.Mesh(cow.V.copy(), cow.F.copy())
    assert np.array_equal(m.V, cow.V) and np.array_equal(m.F, cow.F)
    m2 = fairshape.Mesh(cow.V.tolist(), cow.F.tolist())  # lists work too
    assert np.array_equal(m2.F, cow.F)


@pytest.mark.parametrize("ext", ["obj", "off", "ply", "vtp"])
def test_write_read_round_trip_is_exact(cow, tmp_path, ext):
    V = cow.V + np.pi * 1e-7  # digits a short format would lose
    m = fairshape.Mesh(V, cow.F)
    fairshape.write_mesh(m, str(tmp_path / f"cow.{ext}"))
    back = fairshape.read_mesh(str(tmp_path / f"cow.{ext}"))
    assert np.array_equal(back.V, V) and np.array_equal(back.F, cow.F)


def test_polygon_mesh_faces_are_lists(tmp_path):
    # A quad and a triangle sharing an edge: mixed sizes come back as lists of lists.
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0.5, 0]], dtype=float)
    F = [[0, 1, 2, 3], [1, 4, 2]]
    m = fairshape.Mesh(V, F)
    assert m.F == F
    fairshape.write_mesh(m, str(tmp_path / "mixed.obj"))
    assert fairshape.read_mesh(str(tmp_path / "mixed.obj")).F == F
    quads = fairshape.Mesh(V[:4], np.array([[0, 1, 2, 3]], dtype=np.int64))
    assert quads.F.shape == (1, 4)


def test_V_is_a_read_only_view_without_copy(cow):
    m = cow.copy()
    a, b = m.V, m.V
    assert np.shares_memory(a, b)  # both views of the mesh's own storage
    assert not a.flags.writeable  # writes go through the checked setter
    m.V = a + 1.0
    assert np.array_equal(m.V[0], cow.V[0] + 1.0) and np.array_equal(a[0], cow.V[0] + 1.0)
    assert not np.shares_memory(m.V, cow.V)  # copy() is deep


def test_V_outlives_its_mesh_variable(cow):
    V = cow.copy().V  # the view keeps the (otherwise unreferenced) mesh alive
    assert np.array_equal(V, cow.V)


def test_hierarchy_views_are_read_only_and_shared(cow_hierarchy):
    h = cow_hierarchy
    P = h.positions()
    assert np.shares_memory(P, h.positions())
    assert not P.flags.writeable
    with pytest.raises(ValueError):
        P[0, 0] = 1.0
    assert h.mesh().V is not P and not np.shares_memory(h.mesh().V, P)  # mesh() copies


def test_subdivide_nests_and_operators_reproduce_levels(cow):
    meshes, S = fairshape.subdivide(cow, 2, operators=True)
    assert len(meshes) == 3 and len(S) == 2
    for l in range(2):
        assert S[l].shape == (meshes[l + 1].n_vertices, meshes[l].n_vertices)
        assert np.allclose(S[l].sum(axis=1), 1.0)
        assert np.abs(S[l] @ meshes[l].V - meshes[l + 1].V).max() < 1e-12
    plain = fairshape.subdivide(cow, 2)
    assert isinstance(plain, list) and np.abs(plain[-1].V - meshes[-1].V).max() < 1e-12


def test_subdivide_equals_cli(cow, tmp_path):
    cli("subdivide", "--scheme", "loop", "--levels", 2, "data/cow.off", tmp_path / "fine.obj")
    fine = fairshape.subdivide(cow, 2, scheme="loop")[-1]
    assert np.array_equal(fine.V, fairshape.read_mesh(str(tmp_path / "fine.obj")).V)


def test_limit_positions_and_normals(cow):
    L = fairshape.limit_matrix(cow)
    P = fairshape.limit_positions(cow)
    assert np.abs(L @ cow.V - P).max() < 1e-12
    N = fairshape.limit_normals(cow)
    assert N.shape == cow.V.shape and np.allclose(np.linalg.norm(N, axis=1), 1.0)
    # Limit points of a subdivided mesh lie near the original's (the limit surface is shared).
    fine = fairshape.subdivide(cow, 1)[-1]
    assert np.abs(fairshape.limit_positions(fine)[: cow.n_vertices] - P).max() < 1e-12


def test_details_analysis_reproduces_finest(cow):
    h = fairshape.MultiresSurface(cow, 1)
    noisy = h.positions() + 1e-3 * np.random.default_rng(1).standard_normal(h.positions().shape)
    a = fairshape.MultiresSurface.analyze(cow, noisy, 1)
    assert np.abs(a.positions() - noisy).max() < 1e-10
    assert np.abs(a.details(1, "world")).max() > 1e-4  # the noise went into the details
    with pytest.raises(fairshape.InvalidInput, match="level 0"):
        a.details(0)
