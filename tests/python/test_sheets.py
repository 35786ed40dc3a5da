# Variational sheets (Welch & Witkin) through the bindings give the command line's final.obj.
import csv
import threading

import numpy as np
import pytest

import fairshape
from conftest import cli, obj_vertices

CORNERS = [[0.125, 0.125], [1.875, 0.125], [0.125, 1.875], [1.875, 1.875]]
PEAK_UV, PEAK = [1.0, 0.7], [1.0, 0.7, 0.4]
CURVE_UV = [[0.4, 1.3], [1.0, 1.5], [1.6, 1.3]]
CURVE = [[0.4, 1.3, 0.1], [0.7, 1.45, 0.35], [1.0, 1.5, 0.45], [1.3, 1.45, 0.35], [1.6, 1.3, 0.1]]


def config(solver, refinement=0.0):
    flow = lambda rows: "[" + ", ".join("[" + ", ".join(repr(float(x)) for x in r) + "]" for r in rows) + "]"
    corners = "\n".join(f"  - {{type: point, uv: {flow([c])[1:-1]}, by: [0, 0, 0]}}" for c in CORNERS)
    return f"""name: py-sheet
sheets: [{{name: s, spans: [8, 8], size: [2, 2]}}]
energy: {{alpha: 0.01, beta: 1}}
curves: [{{name: ridge, points: {flow(CURVE)}}}]
constraints:
{corners}
  - {{type: point, uv: {flow([PEAK_UV])[1:-1]}, target: {flow([PEAK])[1:-1]}}}
  - {{type: curve, curve: ridge, uv: {flow(CURVE_UV)}}}
refinement: {{tolerance: {refinement}}}
solver: {{type: {solver}}}
output: {{samples_per_span: 4, vtk: none}}
"""


def cli_sheet(tmp_path, solver, refinement=0.0):
    path = tmp_path / f"{solver}.yaml"
    path.write_text(config(solver, refinement))
    out = tmp_path / solver
    cli("run", path, "--out", out)
    with open(out / "runs.csv") as f:
        row = next(csv.DictReader(f))
    return obj_vertices(out / "final.obj"), row


def solve(solver="kkt", refinement=0.0, **kw):
    sheet = fairshape.Sheet(spans=(8, 8), size=(2, 2))
    uv = np.array(CORNERS + [PEAK_UV])
    targets = np.vstack([sheet.evaluate(CORNERS), PEAK])  # `by: [0, 0, 0]` holds the corners where they are
    return fairshape.design_sheet(sheet, uv, targets, curves=[(CURVE_UV, CURVE)], alpha=0.01, beta=1.0, solver=solver,
                                  refinement_tolerance=refinement, samples_per_span=4, **kw)


@pytest.mark.parametrize("solver", ["kkt", "qr_penalty", "range_space"])
def test_sheet_equals_cli(tmp_path, solver):
    expected, row = cli_sheet(tmp_path, solver)
    r = solve(solver)
    assert r.grid.shape == (33, 33, 3)
    assert np.abs(r.grid.reshape(-1, 3) - expected).max() < 1e-10
    assert r.summary.succeeded and r.summary.termination == row["termination"]
    assert r.max_constraint_error == pytest.approx(float(row["max_constraint_error"]), rel=1e-6)
    assert r.constraint_rows == int(row["constraint_rows"]) and r.sheet.dofs == int(row["dofs"])
    assert np.allclose(r.sheet.evaluate([PEAK_UV]), [PEAK], atol=1e-9)


def test_relative_targets_and_refinement(tmp_path):
    expected, row = cli_sheet(tmp_path, "kkt", refinement=0.002)
    sheet = fairshape.Sheet(spans=(8, 8), size=(2, 2))
    r = fairshape.design_sheet(sheet, CORNERS, np.zeros((4, 3)), relative=True, curves=[(CURVE_UV, CURVE)],
                               alpha=0.01, refinement_tolerance=0.002, samples_per_span=4)
    p = fairshape.design_sheet(r.sheet, [PEAK_UV], [PEAK], curves=[(CURVE_UV, CURVE)], alpha=0.01)
    assert p.summary.succeeded
    full = solve(refinement=0.002)
    assert np.abs(full.grid.reshape(-1, 3) - expected).max() < 1e-10
    assert full.sheet.dofs == int(row["dofs"]) > sheet.dofs and full.spans_refined == int(row["spans_refined"]) > 0
    assert full.max_constraint_error == pytest.approx(float(row["max_constraint_error"]), rel=1e-6)


def test_sheet_errors():
    sheet = fairshape.Sheet(spans=(4, 4))
    with pytest.raises(fairshape.InvalidInput, match="outside the sheet's domain"):
        fairshape.design_sheet(sheet, [[1.5, 0.5]], [[0, 0, 0]])
    with pytest.raises(fairshape.InvalidConfig, match="unknown qp solver|known"):
        fairshape.design_sheet(sheet, [[0.5, 0.5]], [[0, 0, 1]], solver="lagrange")
    with pytest.raises(fairshape.InvalidConfig, match="unknown key"):
        fairshape.design_sheet(sheet, [[0.5, 0.5]], [[0, 0, 1]], solver="qr_penalty", omega=2)
    with pytest.raises(fairshape.InvalidInput, match="k×3"):
        fairshape.design_sheet(sheet, [[0.5, 0.5]], [[0, 1]])


def test_gil_is_released_during_the_sheet_solve():
    sheet = fairshape.Sheet(spans=(48, 48), size=(2, 2))
    t = threading.Thread(target=fairshape.design_sheet, args=(sheet, CORNERS + [PEAK_UV], np.vstack([np.zeros((4, 3)), PEAK])),
                         kwargs=dict(curves=[(CURVE_UV, CURVE)], alpha=0.01))
    ticks = 0
    t.start()
    while t.is_alive():
        ticks += 1
    t.join()
    assert ticks > 1000, ticks


def test_traced_curve_moved_equals_cli(tmp_path):
    """A `from_surface` curve with an edit (a cosine bump in t), traced and bumped in Python."""
    arc_uv = [[0.375, 0.5], [0.625, 0.9], [1, 1.05], [1.375, 0.9], [1.625, 0.5]]
    path = tmp_path / "arc.yaml"
    path.write_text(f"""name: py-arc
sheets: [{{name: s, spans: [8, 8], size: [2, 2]}}]
energy: {{alpha: 0.01, beta: 1}}
curves:
  - {{name: arc, from_surface: {{sheet: s, uv: {arc_uv}}}, samples: 65, edits: [{{step: 0, t: 0.5, radius: 0.6, by: [0, 0, 0.6]}}]}}
constraints:
{chr(10).join(f"  - {{type: point, uv: {c}, by: [0, 0, 0]}}" for c in CORNERS)}
  - {{type: curve, curve: arc}}
solver: {{type: kkt}}
output: {{samples_per_span: 4, vtk: none}}
""")
    cli("run", path, "--out", tmp_path / "arc")
    expected = obj_vertices(tmp_path / "arc" / "final.obj")
    sheet = fairshape.Sheet(spans=(8, 8), size=(2, 2))
    X = sheet.trace(arc_uv, 65)
    assert X.shape == (65, 3)
    t = np.linspace(0, 1, 65)
    d = np.abs(t - 0.5) / 0.6
    X += np.where(d < 1, 0.5 * (1 + np.cos(np.pi * d)), 0)[:, None] * [0, 0, 0.6]
    r = fairshape.design_sheet(sheet, CORNERS, np.zeros((4, 3)), relative=True, curves=[(arc_uv, X)], alpha=0.01,
                               samples_per_span=4)
    assert np.abs(r.grid.reshape(-1, 3) - expected).max() < 1e-10


# The session (fairshape.SheetSession): a config's steps, and the same steps by hand.
SESSION = {
    "name": "py-session",
    "sheets": [{"name": "s", "spans": [8, 8], "size": [2, 2]}],
    "energy": {"alpha": 0.01, "beta": 1},
    "curves": [{"name": "ridge", "points": CURVE}],
    "solver": {"type": "kkt"},
    "output": {"samples_per_span": 4, "vtk": "none"},
}
SCHEDULE = [{"type": "point", "uv": c, "by": [0, 0, 0]} for c in CORNERS] + [
    {"type": "point", "uv": [1, 0.75], "by": [0, 0, 0.25], "moves": [{"step": 1, "by": [0, 0.125, 0.25]}]},
    {"type": "point", "uv": [0.5, 1], "by": [0, 0, -0.125], "until": 2},
    {"type": "curve", "curve": "ridge", "uv": CURVE_UV},
]
ACTIONS = [{"step": 3, "do": "install_rest_shape"}, {"step": 4, "do": "melt_rest_shape"}]


def cli_session(tmp_path):
    """The scheduled session as a config, and its final.obj vertices from `fairshape run`."""
    import yaml
    config = dict(SESSION, constraints=SCHEDULE, actions=ACTIONS)
    path = tmp_path / "session.yaml"
    path.write_text(yaml.safe_dump(config))
    cli("run", path, "--out", tmp_path / "out")
    return config, obj_vertices(tmp_path / "out" / "final.obj")


def test_session_advances_through_a_config_like_the_cli(tmp_path):
    config, expected = cli_session(tmp_path)
    s = fairshape.SheetSession(**config)
    assert s.steps == 5
    energies = []
    while s.next_step < s.steps:
        st = s.advance()
        assert st.succeeded, st.result.message
        energies.append(st.result.energy)
    assert np.array_equal(s.sheet().grid(4).reshape(-1, 3), expected)
    assert energies[3] == pytest.approx(0, abs=1e-9)  # installed: the minimizer of eq. 6 about itself
    with pytest.raises(fairshape.InvalidInput, match="steps are done"):
        s.advance()


def test_session_steps_by_hand_equal_the_config_run(tmp_path):
    _, expected = cli_session(tmp_path)
    s = fairshape.SheetSession(**SESSION)
    for c in CORNERS:
        assert s.add(type="point", uv=c, by=[0, 0, 0]).succeeded
    lifted = s.add(type="point", uv=[1, 0.75], by=[0, 0, 0.25])
    h = lifted.added[0]
    second = s.add(type="point", uv=[0.5, 1], by=[0, 0, -0.125]).added[0]
    assert s.add(type="curve", curve="ridge", uv=CURVE_UV).succeeded
    asked = next(c.asked for c in lifted.checks if c.handle == h)
    drag = s.move(h, asked + np.array([0, 0.125, 0.25]), curve_probe=False)
    check = next(c for c in drag.checks if c.handle == h)
    assert np.abs(check.achieved - check.asked).max() < 1e-9  # measured on the sheet
    assert drag.solve_s > 0 and drag.check_s > 0
    s.remove(second)
    assert s.install_rest_shape().energy == pytest.approx(0, abs=1e-9)
    melted = s.melt()
    assert s.handles == [0, 1, 2, 3, 4, 6]
    assert np.array_equal(s.sheet().grid(4).reshape(-1, 3), expected)
    # A refinement step by constraint error (§4.4).
    before = s.sheet().dofs
    r = s.refine(0.25 * melted.max_constraint_error)
    assert r.sheets[0].spans_refined > 0 and s.sheet().dofs > before


def test_session_refuses_what_the_config_refuses():
    with pytest.raises(fairshape.InvalidConfig, match="alpah"):
        fairshape.SheetSession(sheets=[{"name": "s"}], energy={"alpah": 1})
    s = fairshape.SheetSession(**SESSION)
    with pytest.raises(fairshape.InvalidConfig, match="bogus"):
        s.add(type="point", uv=[1, 1], by=[0, 0, 0], bogus=1)
    with pytest.raises(fairshape.InvalidConfig, match="outside the sheet's domain"):
        s.add(type="point", uv=[3, 1], by=[0, 0, 0])
    with pytest.raises(fairshape.InvalidConfig, match="step"):
        s.add(type="point", uv=[1, 1], by=[0, 0, 0], step=2)
    with pytest.raises(fairshape.InvalidConfig, match="pointt"):
        s.add(type="pointt", uv=[1, 1])
    with pytest.raises(fairshape.InvalidInput, match="no constraint 5"):
        s.move(5, [0, 0, 0])
    assert s.handles == []
