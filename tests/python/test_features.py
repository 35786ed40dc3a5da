# Feature curves (Khodakovsky & Schröder) through the bindings give the command line's final.obj
# and features.csv.
import csv
import threading

import numpy as np
import pytest

import fairshape
from conftest import cli, obj_vertices

DEFAULTS = dict(quadratic=True)  # fig14's feature_defaults
FIG14 = [fairshape.feature([[-0.85, -0.3, 0.0813], [0.0, 0.05, -0.0002], [0.85, 0.3, 0.0813]], level=1, name="ridge",
                           radius=0.45, height=0.12, **DEFAULTS),
         fairshape.feature([[-0.5, -0.8, -0.0084], [-0.3, 0.0, 0.0108], [-0.45, 0.8, -0.0141]], level=3,
                           name="groove_a", radius=0.07, height=-0.02, max_distance=0.1, **DEFAULTS),
         fairshape.feature([[0.45, -0.8, -0.0141], [0.3, 0.0, 0.0108], [0.5, 0.8, -0.0084]], level=3,
                           name="groove_b", radius=0.07, height=-0.02, max_distance=0.1, **DEFAULTS)]
COLUMNS = ["height_min", "height_max", "width_left", "width_right", "height_error", "width_error", "profile_error"]


@pytest.fixture(scope="module")
def patch():
    return fairshape.MultiresSurface(fairshape.read_mesh("data/ks_patch.off"), 4, scheme="loop")


@pytest.fixture(scope="module")
def fig14_cli(tmp_path_factory):
    out = tmp_path_factory.mktemp("fig14") / "cli"
    cli("run", "configs/khodakovsky-schroder/fig14.yaml", "--out", out, "--set", "adaptive.enabled=false",
        "--set", "output.vtk=none")
    with open(out / "features.csv") as f:
        rows = {r["feature"]: r for r in csv.DictReader(f)}
    return obj_vertices(out / "final.obj"), rows


def test_features_equal_cli(patch, fig14_cli):
    expected, rows = fig14_cli
    r = fairshape.apply_features(patch, FIG14)
    assert r.positions.shape == expected.shape == (patch.positions().shape[0], 3)
    assert np.abs(r.positions - expected).max() < 1e-10
    assert np.abs(r.hierarchy.positions() - expected).max() < 1e-10
    assert [f["name"] for f in r.features] == ["ridge", "groove_a", "groove_b"]
    assert r.flipped_faces == 0 and r.folds == ""
    for f in r.features:
        row = rows[f["name"]]
        for where in ("fine", "limit"):
            for c in COLUMNS:
                assert f[where][c] == pytest.approx(float(row[f"{c}_{where}"]), rel=1e-6, abs=1e-12), (f["name"], where, c)
        assert f["within_tolerance"] == (row["within_tolerance"] == "1")
    # The surface points as placed give the same surface.
    again = [dict(fairshape.feature(faces=faces, bary=bary, level=f["level"], name=f.get("name"),
                                    **{k: v for k, v in f.items() if k not in ("points", "level", "name", "closed")}))
             for f, (faces, bary) in zip(FIG14, r.placed)]
    s = fairshape.apply_features(patch, again)
    assert np.abs(s.positions - r.positions).max() < 1e-12


def test_a_feature_too_tall_for_its_surface_is_seen_to_fold(patch):
    tall = dict(FIG14[0], height=5.0)
    r = fairshape.apply_features(patch, [tall])
    assert r.flipped_faces > 0
    assert "faces flipped" in r.folds


def test_feature_errors(patch):
    with pytest.raises(fairshape.InvalidConfig, match="unknown key.*radius"):
        fairshape.apply_features(patch, [fairshape.feature([[0, 0, 0], [0.5, 0, 0]], radious=0.1)])
    with pytest.raises(fairshape.InvalidInput, match="farther|surface"):
        fairshape.apply_features(patch, [fairshape.feature([[0, 0, 5], [0.5, 0, 5]], radius=0.1)])
    with pytest.raises(fairshape.InvalidConfig, match="exactly one of points"):
        fairshape.apply_features(patch, [{"level": 0}])
    with pytest.raises(fairshape.InvalidConfig, match="finest|limit"):
        fairshape.apply_features(patch, FIG14[:1], profile_on="coarse")
    cc = fairshape.MultiresSurface(fairshape.read_mesh("data/ks_patch.off"), 1)
    with pytest.raises(fairshape.InvalidInput, match="Loop"):
        fairshape.apply_features(cc, FIG14[:1])


def test_gil_is_released_while_features_are_applied(patch):
    t = threading.Thread(target=fairshape.apply_features, args=(patch, FIG14))
    ticks = 0
    t.start()
    while t.is_alive():
        ticks += 1
    t.join()
    assert ticks > 1000, ticks
