# fairshape's errors arrive as exceptions of one hierarchy, with fairshape's own message.
import numpy as np
import pytest

import fairshape


def test_hierarchy_of_classes():
    for cls in (fairshape.InvalidInput, fairshape.InvalidConfig, fairshape.TopologyError, fairshape.SolverError,
                fairshape.FileError):
        assert issubclass(cls, fairshape.Error)
    for cls in (fairshape.ParseError, fairshape.OutputError, fairshape.MissingFileError):
        assert issubclass(cls, fairshape.FileError) and issubclass(cls, OSError)
    assert issubclass(fairshape.MissingFileError, FileNotFoundError)
    assert issubclass(fairshape.InvalidInput, ValueError) and issubclass(fairshape.InvalidConfig, ValueError)
    assert issubclass(fairshape.InvalidIndex, fairshape.InvalidInput) and issubclass(fairshape.InvalidIndex, IndexError)
    assert issubclass(fairshape.SolveFailed, fairshape.Error)


def test_parse_error_names_file_and_line():
    path = "tests/data/malformed/bad_number.off"
    with pytest.raises(fairshape.ParseError) as e:
        fairshape.read_mesh(path)
    assert e.value.file == path and e.value.line > 0
    assert str(e.value).startswith(f"{path}:{e.value.line}:")


def test_bad_face_index_is_invalid_input():
    with pytest.raises(fairshape.InvalidInput, match="9"):
        fairshape.Mesh(np.zeros((3, 3)), [[0, 1, 9]])


def test_non_manifold_is_topology_error():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0, -1, 0]], dtype=float)
    with pytest.raises(fairshape.TopologyError):
        fairshape.Mesh(V, [[0, 1, 2], [0, 1, 3], [0, 1, 4]])  # one edge in three faces


def test_missing_file_is_file_error(tmp_path):
    with pytest.raises(fairshape.FileError, match="nowhere.obj"):
        fairshape.read_mesh(str(tmp_path / "nowhere.obj"))


def test_unknown_names_list_the_choices(cow):
    with pytest.raises(fairshape.InvalidConfig, match="catmull-clark"):
        fairshape.subdivide(cow, 1, scheme="butterfly")
    with pytest.raises(fairshape.InvalidConfig, match="alpha"):
        fairshape.energy_hessian(cow, "detail_preserving", gamma=1.0)
    with pytest.raises(fairshape.InvalidConfig, match="detail_preserving"):
        fairshape.energy_hessian(cow, "no_such_energy")


def test_loop_on_quads_is_refused():
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    with pytest.raises(fairshape.InvalidInput, match="triangle"):
        fairshape.subdivide(fairshape.Mesh(V, [[0, 1, 2, 3]]), 1, scheme="loop")
