# The curve editor (Sauvage et al.) through the bindings gives the command line's final.obj.
import threading

import numpy as np
import pytest

import fairshape
from conftest import cli, obj_vertices

WAVE = "data/curves/wave129.obj"


def wave():
    return obj_vertices(WAVE)[:, :2]  # the planar wave as an n×2 array


def cli_curve(tmp_path, name, config):
    path = tmp_path / f"{name}.yaml"
    path.write_text(config)
    out = tmp_path / name
    cli("run", path, "--out", out)
    return obj_vertices(out / "final.obj")


FIG3 = """name: py-curve
input: {curve: data/curves/wave129.obj}
edits:
  - level: 2
    wrinkle_level: 3
    moves: [{index: 3, by: [-0.06, 0.03]}, {index: 4, by: [-0.3, 0.0]}]
optimization:
  beta: 0.01
  solver: {type: %s, length_tolerance: 1.0e-12, stationarity_tolerance: 1.0e-8, max_solves: 2000%s}
output: {vtk: none}
"""


@pytest.mark.parametrize("solver,extra,kw", [("trust_region", "", {}),
                                             ("linearized", ", linearized: {linearization: newton}",
                                              {"linearization": "newton"})])
def test_edit_curve_equals_cli(tmp_path, solver, extra, kw):
    expected = cli_curve(tmp_path, solver, FIG3 % (solver, extra))
    c = fairshape.Curve(wave())
    assert c.levels == 7 and c.level(2).shape == (5, 2) and c.level(7).shape == (129, 2)
    r = fairshape.edit_curve(c, level=2, indices=[3, 4], offsets=[[-0.06, 0.03], [-0.3, 0.0]], wrinkle_level=3,
                             beta=0.01, solver=solver, length_tolerance=1e-12, stationarity_tolerance=1e-8,
                             max_solves=2000, check=False, **kw)
    assert r.points.shape == (129, 2)
    assert np.abs(r.points3 - expected).max() < 1e-10 and np.abs(r.points - expected[:, :2]).max() < 1e-10
    assert r.metrics["out_of_plane"] == np.abs(expected[:, 2]).max()
    assert r.summary.termination == expected_termination(tmp_path, solver)
    if r.summary.succeeded:
        assert r.length_error_max < 1e-10 and r.solves == r.summary.iterations > 0
        assert r.length_constraint == "segment_lengths"
    assert r.curve.levels == 7 and np.allclose(r.curve.points, r.points)


def expected_termination(tmp_path, solver):
    import csv
    with open(tmp_path / solver / "runs.csv") as f:
        return next(csv.DictReader(f))["termination"]


def test_closed_3d_curve_total_length(tmp_path):
    ring = obj_vertices("data/curves/ring128.obj")
    config = """name: py-ring
input: {curve: data/curves/ring128.obj}
edits: [{level: 1, moves: [{index: 2, by: [0.2, 0.1, 0.05]}]}]
editing: {solve_region: curve}
optimization:
  constraints: [{type: total_length}]
  solver: {type: trust_region, max_solves: 500}
output: {vtk: none}
"""
    expected = cli_curve(tmp_path, "ring", config)
    c = fairshape.Curve(ring, closed=True)
    r = fairshape.edit_curve(c, 1, [2], [0.2, 0.1, 0.05], length="total_length", solve_region="curve",
                             solver="trust_region", max_solves=500)
    assert r.points.shape == ring.shape and np.abs(r.points - expected).max() < 1e-10
    assert r.length_constraint == "total_length" and r.total_length_error < 1e-8


def test_levels_and_details_reconstruct():
    c = fairshape.Curve(wave(), levels=3)
    coarse, d = c.level(2), c.details(2)
    fine = c.level(3)
    assert np.abs(fine[0::2] - coarse).max() == 0
    assert np.abs(fine[1::2] - (d + 0.5 * (coarse[:-1] + coarse[1:]))).max() < 1e-15
    with pytest.raises(fairshape.InvalidInput, match="d\\^0..d\\^2"):
        c.details(3)


def test_curve_options_are_checked():
    c = fairshape.Curve(wave())
    with pytest.raises(fairshape.InvalidConfig, match=r"unknown key.*linearization"):
        fairshape.edit_curve(c, 2, [3], [0.1, 0], linearisation="newton")
    with pytest.raises(fairshape.InvalidConfig, match="known: .*trust_region"):
        fairshape.edit_curve(c, 2, [3], [0.1, 0], solver="newton")
    with pytest.raises(fairshape.InvalidConfig, match="solve_region"):
        fairshape.edit_curve(c, 2, [3], [0.1, 0], length="total_length", solver="trust_region")
    with pytest.raises(fairshape.InvalidInput, match="not on the level-2 polygon of 5 points"):
        fairshape.edit_curve(c, 2, [5], [0.1, 0])
    with pytest.raises(fairshape.InvalidInput, match="levels need"):
        fairshape.Curve(np.zeros((10, 2)), levels=2)
    with pytest.raises(fairshape.InvalidInput, match="n×2 or n×3"):
        fairshape.Curve(np.zeros((10, 4)))


def test_failed_curve_solve_raises_unless_unchecked():
    c = fairshape.Curve(wave())
    with pytest.raises(fairshape.SolveFailed, match="max_iterations") as e:
        fairshape.edit_curve(c, 0, [-1], chord_scale=0.7, solve_region="curve", solver="trust_region", max_solves=2)
    assert e.value.result.summary.iterations >= 2 and not e.value.result.summary.succeeded


def test_gil_is_released_during_the_curve_edit():
    c = fairshape.Curve(fairshape.Curve(wave()).points)
    t = threading.Thread(target=fairshape.edit_curve, args=(c, 0, [-1]),
                         kwargs=dict(chord_scale=0.7, beta=0.01, explicit_step="sweep", details="global",
                                     solve_region="curve", solver="trust_region", length_tolerance=1e-12,
                                     max_solves=5000, check=False))
    ticks = 0
    t.start()
    while t.is_alive():
        ticks += 1
    t.join()
    assert ticks > 1000, ticks


def test_drag_steps_and_pins_equal_cli(tmp_path):
    config = """name: py-drag
input: {curve: data/curves/wave129.obj}
edits: [{level: 3, wrinkle_level: 4, drag_steps: 3, moves: [{index: 4, by: [0.0, 0.25]}]}]
optimization:
  beta: 0.1
  constraints: [{type: segment_lengths}, {type: pin, points: endpoints}]
  solver: {type: linearized, max_solves: 500, linearized: {linearization: newton}}
# The drag asks for more length than the curve has near the handle (it is pulled back 4 % of the
# curve's size): the command line ends edit_undone unless allowed; the comparison is of the points.
editing: {partial_edit: accept}
output: {vtk: none}
"""
    expected = cli_curve(tmp_path, "drag", config)
    r = fairshape.edit_curve(wave(), 3, [4], [0.0, 0.25], wrinkle_level=4, drag_steps=3, beta=0.1,
                             constraints=[{"type": "pin", "points": "endpoints"}], max_solves=500,
                             linearization="newton", check=False)
    assert np.abs(r.points3 - expected).max() < 1e-10
    assert r.metrics["drag_steps_done"] == 3 or not r.summary.succeeded


SESSION = "tests/data/configs/curve_session_steps.yaml"  # the steps of the test below


def test_session_step_by_step_equals_cli(tmp_path):
    # The bound session, driven one editing loop at a time, ends where `fairshape run` of the
    # same steps ends, bit for bit (final.obj keeps 17 digits), with the run's verdict.
    out = tmp_path / "session"
    cli("run", SESSION, "--out", out)
    expected = obj_vertices(out / "final.obj")
    s = fairshape.CurveSession(wave(), optimization={"beta": 0.1, "solver": {
        "type": "linearized", "max_solves": 500, "linearized": {"linearization": "newton"}}})
    assert s.levels == 7
    for k in range(1, 4):
        step = s.drag_step(2, [{"index": 4, "by": [-0.15, 0.05]}], drag_steps=3, wrinkle_level=3)
        assert (step.index, step.drag_step, step.drag_steps) == (k - 1, k, 3)
        assert step.succeeded and step.checks["length_error_max"] < 1e-8
        assert step.checks["handle_reach"] == 1 if k < 3 else step.checks["handle_reach"] > 0.5
        assert step.points.shape == (129, 2) and np.array_equal(step.points, s.points)
    last = s.edit(3, [{"index": 8, "by": [-0.02, 0.0]}], wrinkle_level=4)
    assert last.index == 3 and last.solve_s > 0 and last.check_s >= 0
    assert last.checks["self_crossings"] == 0 and last.checks["out_of_plane"] < 1e-12
    assert np.array_equal(last.points3, expected)
    assert s.outcome().termination == expected_termination(tmp_path, "session")


def test_session_keywords_go_through_the_config_reader():
    with pytest.raises(fairshape.InvalidConfig, match="optimization.beta: 1.5 is out of range"):
        fairshape.CurveSession(wave(), optimization={"beta": 1.5})
    with pytest.raises(fairshape.InvalidConfig, match="optimisation: unknown key"):
        fairshape.CurveSession(wave(), optimisation={"beta": 0.1})
    with pytest.raises(fairshape.InvalidConfig, match="sweep: unknown key"):
        fairshape.CurveSession(wave(), sweep={"optimization.beta": [0.1, 0.2]})
    with pytest.raises(fairshape.InvalidConfig, match=r"editing.solve_region: unknown value 'window' \(valid: support, curve\)"):
        fairshape.CurveSession(wave(), editing={"solve_region": "window"})
    with pytest.raises(fairshape.InvalidConfig, match="solver.trust_region.*not the chosen one"):
        fairshape.CurveSession(wave(), optimization={"solver": {"type": "linearized", "trust_region": {"initial_radius": 0.5}}})
    s = fairshape.CurveSession(wave())
    with pytest.raises(fairshape.InvalidIndex, match="not on the level-2 polygon of 5 points"):
        s.edit(2, [{"index": 5, "by": [0.1, 0]}])
    with pytest.raises(fairshape.InvalidConfig, match="exactly one of `by` and `chord_scale`"):
        s.edit(2, [{"index": 3}])
    s.drag_step(3, [{"index": 4, "by": [0.0, 0.06]}], drag_steps=2)
    with pytest.raises(fairshape.InvalidInput, match="under way"):
        s.edit(2, [{"index": 3, "by": [0.1, 0]}])
