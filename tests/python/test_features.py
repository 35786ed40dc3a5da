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


# The session (fairshape.FeatureSession, feature/feature_session.h) driven step by step gives the
# command line's run of the same design steps, bit for bit: a groove moved, a ridge raised, a
# feature added, a ridge removed — one edit per step, as the config schedules them.
SESSION_DEFAULTS = dict(radius=0.18, height=0.05, quadratic=True, profile_tolerance=0.5, width_tolerance=0.5)
RIDGE_A = dict(name="ridge_a", level=2, points=[[-0.8, -0.55, 0.0587], [-0.2, 0.1, 0.0042], [0.4, 0.25, 0.0155], [0.8, 0.7, 0.0474]])
RIDGE_B = dict(name="ridge_b", level=2, points=[[-0.75, 0.6, 0.0459], [0.0, 0.35, -0.0073], [0.7, -0.6, 0.0372]])
GROOVE = dict(name="groove", level=2, height=-0.04, radius=0.12,
              points=[[-0.6, -0.1, 0.0426], [0.1, -0.45, -0.0109], [0.75, 0.05, 0.0674]])
LATE = dict(name="late", level=2, height=-0.03, radius=0.1, points=[[-0.5, 0.8, -0.0084], [0.5, 0.8, -0.0084]])
SESSION_INPUT = dict(mesh="data/ks_patch.off", levels=3)


def _flow(d):
    return "{" + ", ".join(f"{k}: {v}" for k, v in d.items()) + "}"


@pytest.fixture(scope="module")
def stepped_cli(tmp_path_factory):
    d = tmp_path_factory.mktemp("feature_session")
    scheduled = [dict(RIDGE_A, until=4), dict(RIDGE_B, changes="[{step: 2, height: 0.1}]"),
                 dict(GROOVE, moves="[{step: 1, by: [0, -0.2, 0]}]"), dict(LATE, step=3)]
    config = d / "steps.yaml"
    config.write_text("name: steps\n"
                      f"input: {_flow(SESSION_INPUT)}\n"
                      f"feature_defaults: {_flow(SESSION_DEFAULTS)}\n"
                      "adaptive: {enabled: false}\noutput: {vtk: none}\n"
                      "features:\n" + "".join(f"  - {_flow(f)}\n" for f in scheduled))
    cli("run", config, "--out", d / "out")
    with open(d / "out" / "steps.csv") as f:
        steps = list(csv.DictReader(f))
    return obj_vertices(d / "out" / "final.obj"), steps


def test_feature_session_step_by_step_equals_the_cli_run(stepped_cli):
    expected, rows = stepped_cli
    s = fairshape.FeatureSession(input=SESSION_INPUT, feature_defaults=SESSION_DEFAULTS, features=[RIDGE_A, RIDGE_B, GROOVE])
    steps = [s.first_step, s.move("groove", by=[0, -0.2, 0]), s.set("ridge_b", height=0.1), s.add(**LATE), s.remove("ridge_a")]
    assert np.array_equal(s.positions(), expected)
    assert [r["evaluation"] for r in rows] == [t["evaluation"] for t in steps] == ["whole"] + ["region"] * 4
    for r, t in zip(rows, steps):
        assert int(r["vertices_recomputed"]) == t["vertices_recomputed"]
        assert r["vertices_changed"] == ("" if t["vertices_changed"] < 0 else str(t["vertices_changed"]))
        assert t["termination"] == "converged" and t["flipped_faces"] == 0 and t["profiles"] is None
    assert steps[1]["moved"] == ["groove"] and steps[2]["changed"] == ["ridge_b"] and steps[3]["added"] == ["late"]
    assert [p["name"] for p in steps[0]["placed"]] == ["ridge_a", "ridge_b", "groove"]
    assert all(0 < p["farthest"] < p["allowed"] for p in steps[0]["placed"])
    assert sorted(s.features) == ["groove", "late", "ridge_b"]
    assert s.features["ridge_b"]["height"] == 0.1
    # The profiles on request, as features.csv reports them.
    m = s.measure()
    assert m["termination"] == "converged" and [f["name"] for f in m["features"]] == ["ridge_b", "groove", "late"]
    step = s.set("late", height=-0.03, checks="profiles")
    assert step["profiles"]["termination"] == "converged" and len(step["profiles"]["features"]) == 3


def test_feature_session_errors():
    s = fairshape.FeatureSession(input=SESSION_INPUT, feature_defaults=SESSION_DEFAULTS, features=[GROOVE])
    before = s.positions()
    with pytest.raises(fairshape.InvalidConfig, match="'output' is not a session's key"):
        fairshape.FeatureSession(input=SESSION_INPUT, features=[GROOVE], output={"vtk": "none"})
    with pytest.raises(fairshape.InvalidConfig, match=r"features\[0\]: step, until, moves and changes"):
        fairshape.FeatureSession(input=SESSION_INPUT, features=[dict(GROOVE, until=2)])
    with pytest.raises(fairshape.InvalidConfig, match="unknown key.*radius"):
        s.set("groove", radious=0.1)
    with pytest.raises(fairshape.InvalidConfig, match="exists already"):
        s.add(**GROOVE)
    with pytest.raises(fairshape.InvalidInput, match="no feature named 'ridge'.*groove"):
        s.remove("ridge")
    with pytest.raises(fairshape.InvalidConfig, match="checks: unknown value 'all'"):
        s.set("groove", checks="all", height=-0.05)
    with pytest.raises(fairshape.InvalidInput, match="farther|surface"):
        s.replace("groove", points=[[0, 0, 5], [0.5, 0, 5]])
    assert np.array_equal(s.positions(), before)  # a refused step changes nothing
    assert s.move("groove", by=[0, 0.05, 0])["evaluation"] == "region"
