# The checks at the door of every binding: an index outside its range is an InvalidIndex (an
# IndexError) naming the range, never a crash or a read out of bounds; a float argument that
# is not finite is refused by name; a view of fairshape's data cannot be written around the
# checks; a symmetric solver refuses a non-symmetric or empty system, and a solve whose own
# residual misses its tolerance never reports success.
import errno

import numpy as np
import pytest
import scipy.sparse as sp

import fairshape

TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
TETRA_F = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]


@pytest.fixture
def tetra():
    return fairshape.Mesh(TETRA_V, TETRA_F)


@pytest.mark.parametrize("v", [4, 99, 100000, -1, 2**40])
def test_vertex_neighbors_checks_its_index(tetra, v):
    with pytest.raises(IndexError, match=r"v = .* is out of range \(valid: 0\.\.3, the 4 vertices\)") as e:
        tetra.vertex_neighbors(v)
    assert isinstance(e.value, fairshape.InvalidIndex) and isinstance(e.value, fairshape.InvalidInput)
    assert sorted(tetra.vertex_neighbors(3)) == [0, 1, 2]


def test_hierarchy_levels_are_checked_as_indices(tetra):
    h = fairshape.MultiresSurface(tetra, 1)
    with pytest.raises(IndexError, match=r"level = 1 is out of range \(valid: 0\.\.0"):
        h.subdivision_operator(1)
    with pytest.raises(IndexError, match=r"valid: 0\.\.0"):
        h.subdivision_operator(-1)
    with pytest.raises(IndexError, match="levels 0..1"):
        h.positions(5)
    assert h.subdivision_operator(0).shape == (h.mesh(1).n_vertices, 4)


def test_float_arguments_must_be_finite(tetra):
    for bad in (np.nan, np.inf):
        with pytest.raises(ValueError, match="energy_hessian: weight = (nan|inf): must be a finite number"):
            fairshape.energy_hessian(tetra, "surface_thin_plate", weight=bad)
    h = fairshape.MultiresSurface(tetra, 1)
    X = h.positions(0).copy()
    X[2, 1] = np.nan
    with pytest.raises(ValueError, match=r"set_level_positions: X: every entry must be finite; entry \(2, 1\) is nan"):
        h.set_level_positions(0, X)
    with pytest.raises(ValueError, match="u_axis"):
        fairshape.Sheet(u_axis=(np.nan, 0, 0))


def test_mesh_V_cannot_be_written_around_its_check(tetra):
    with pytest.raises(ValueError, match="read-only"):
        tetra.V[0, 0] = np.nan
    assert np.isfinite(tetra.V).all()
    bad = TETRA_V.copy()
    bad[1, 1] = np.nan
    with pytest.raises(fairshape.InvalidInput, match="finite"):
        tetra.V = bad
    moved = TETRA_V + 1.0
    tetra.V = moved  # the checked way to move the vertices
    assert np.array_equal(tetra.V, moved)


def test_symmetric_solvers_refuse_a_non_symmetric_matrix():
    A = sp.csc_matrix(np.array([[2.0, 1.0], [0.0, 2.0]]))
    for solver in ("cholesky", "conjugate_gradient"):
        with pytest.raises(ValueError, match=rf"solver '{solver}' needs a symmetric A") as e:
            fairshape.solve(A, [1.0, 1.0], solver=solver, check=False)
        assert "A[0, 1] = 1" in str(e.value) and "A[1, 0] = 0" in str(e.value)


def test_symmetric_solvers_refuse_an_empty_matrix():
    with pytest.raises(ValueError, match=r"A is empty \(0×0\); solver 'cholesky'"):
        fairshape.solve(sp.csc_matrix((0, 0)), np.zeros(0), check=False)


def test_a_residual_above_the_tolerance_is_not_a_success():
    # Symmetric positive definite with condition number 1e15: CHOLMOD factors it, and its answer
    # leaves a relative residual near 1e-2 (machine epsilon times the condition number).
    rng = np.random.default_rng(3)
    Q, _ = np.linalg.qr(rng.standard_normal((10, 10)))
    A = (Q * np.logspace(0, -15, 10)) @ Q.T
    A = sp.csc_matrix((A + A.T) / 2)
    b = rng.standard_normal(10)
    x, s = fairshape.solve(A, b, check=False)
    residual = np.linalg.norm(A @ x - b) / np.linalg.norm(b)
    assert residual > 1e-6, residual  # the case this test is about
    assert not s.succeeded and s.termination == "numerical_failure", s
    assert "misses the tolerance 1e-06" in s.message, s.message
    with pytest.raises(fairshape.SolveFailed, match="misses the tolerance"):
        fairshape.solve(A, b)


def test_file_errors_are_oserrors_and_a_missing_file_is_file_not_found(tmp_path):
    missing = str(tmp_path / "nowhere.obj")
    with pytest.raises(FileNotFoundError, match="nowhere.obj") as e:
        fairshape.read_mesh(missing)
    assert isinstance(e.value, fairshape.MissingFileError) and isinstance(e.value, fairshape.FileError)
    assert e.value.errno == errno.ENOENT and str(e.value).startswith(missing)
    assert issubclass(fairshape.FileError, OSError) and issubclass(fairshape.FileError, fairshape.Error)
    assert not hasattr(fairshape, "IOError")  # never again a name that shadows the builtin
    with pytest.raises(OSError):
        fairshape.read_mesh(str(tmp_path))  # a directory: a FileError, not FileNotFoundError
