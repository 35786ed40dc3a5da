# The constrained edit through the bindings gives the command line's final.obj to 1e-12.
import threading

import numpy as np
import pytest

import fairshape
from conftest import cli, obj_vertices

ENERGY = fairshape.energy("detail_preserving", alpha=0.1, beta=1.0)
OFFSET = [0.06, 0.0, 0.032]  # configs/smoke/cow_nose_pull.yaml's handle


def cli_edit(tmp_path, mode):
    out = tmp_path / "cli"
    cli("run", "configs/smoke/cow_nose_pull.yaml", "--out", out, "--set", "input.representation=catmull-clark",
        "--set", "input.levels=1", "--set", "energy=[{type: detail_preserving, alpha: 0.1, beta: 1.0}]",
        "--set", f"problem={{constraint_mode: {mode}}}")
    return obj_vertices(out / "final.obj")


def selections(h):
    """The config's region and nearest selections as index arrays, computed here with NumPy."""
    P = h.positions()
    lo, hi = P[:, 0].min(), P[:, 0].max()
    back = np.flatnonzero((P[:, 0] >= lo) & (P[:, 0] <= lo + 0.3 * (hi - lo)))
    nose = np.array([np.argmin(np.linalg.norm(P - [0.5, 0.0, 0.0], axis=1))])
    return back, nose


@pytest.mark.parametrize("mode", ["kkt", "paper"])
def test_edit_equals_cli(tmp_path, cow_hierarchy, mode):
    expected = cli_edit(tmp_path, mode)
    back, nose = selections(cow_hierarchy)
    r = fairshape.edit(cow_hierarchy, [ENERGY], [fairshape.fixed(back), fairshape.position(nose, OFFSET)], mode=mode)
    assert r.summary.termination == "converged" and r.summary.succeeded
    assert r.delta.shape == (cow_hierarchy.positions().shape[0], 3)
    assert np.abs(r.positions - expected).max() < 1e-12
    assert np.abs(r.hierarchy.positions() - expected).max() < 1e-12
    assert np.abs(r.delta[back]).max() < 1e-12 and np.allclose(r.delta[nose[0]], OFFSET, atol=1e-12)
    assert r.constraint_residual < 1e-10 and r.constrained_vertices >= len(back) + 1
    # Selections by region and nearest point, as in the config, give the same edit.
    s = fairshape.edit(cow_hierarchy, [ENERGY], [fairshape.constraint("fixed", region={"axis": "x", "from": 0.0, "to": 0.3}),
                                                 fairshape.constraint("position", nearest=[0.5, 0, 0], offset=OFFSET)],
                       mode=mode)
    assert np.abs(s.delta - r.delta).max() < 1e-12


def test_per_vertex_offsets(cow_hierarchy):
    back, _ = selections(cow_hierarchy)
    handles = np.array([100, 2000])
    offsets = np.array([[0.0, 0.05, 0.0], [0.0, 0.0, -0.04]])
    r = fairshape.edit(cow_hierarchy, [ENERGY], [fairshape.fixed(back), fairshape.position(handles, offsets)], mode="kkt")
    assert np.abs(r.delta[handles] - offsets).max() < 1e-12


def test_solver_options_are_checked(cow_hierarchy):
    back, nose = selections(cow_hierarchy)
    cons = [fairshape.fixed(back), fairshape.position(nose, OFFSET)]
    with pytest.raises(fairshape.InvalidConfig, match=r"solver.omega: unknown key.*sor"):
        fairshape.edit(cow_hierarchy, [ENERGY], cons, solver="sor", omega=1.5)
    with pytest.raises(fairshape.InvalidConfig, match="paper"):
        fairshape.edit(cow_hierarchy, [ENERGY], cons, mode="kkt", solver="sor")
    with pytest.raises(fairshape.InvalidConfig, match="range_space"):
        fairshape.edit(cow_hierarchy, [ENERGY], cons, mode="lagrange")
    with pytest.raises(fairshape.InvalidConfig, match="valid keys"):
        fairshape.edit(cow_hierarchy, [ENERGY], [fairshape.fixed(back, radius=2)])


def test_conflicting_constraints_raise_with_the_message(cow_hierarchy):
    with pytest.raises(fairshape.InvalidInput, match="incompatible targets"):
        fairshape.edit(cow_hierarchy, [ENERGY], [fairshape.fixed([5]), fairshape.position([5], OFFSET)])
    with pytest.raises(fairshape.InvalidInput, match="level 7"):
        fairshape.edit(cow_hierarchy, [ENERGY], [fairshape.fixed([5], level=7)])


def test_failed_solve_raises_unless_unchecked(cow_hierarchy):
    back, nose = selections(cow_hierarchy)
    cons = [fairshape.fixed(back), fairshape.position(nose, OFFSET)]
    opts = dict(solver="gauss_seidel", tolerance=1e-12, max_iterations=3)
    with pytest.raises(fairshape.SolveFailed, match="max_iterations") as e:
        fairshape.edit(cow_hierarchy, [ENERGY], cons, **opts)
    assert e.value.result.summary.iterations == 3
    r = fairshape.edit(cow_hierarchy, [ENERGY], cons, check=False, **opts)
    assert r.summary.termination == "max_iterations" and not r.summary.succeeded


def test_gil_is_released_during_the_edit(cow_hierarchy):
    back, nose = selections(cow_hierarchy)
    cons = [fairshape.fixed(back), fairshape.position(nose, OFFSET)]
    t = threading.Thread(target=fairshape.edit, args=(cow_hierarchy, [ENERGY], cons),
                         kwargs=dict(solver="gauss_seidel", tolerance=1e-9, max_iterations=3000, check=False))
    ticks = 0
    t.start()
    while t.is_alive():  # holding the GIL, the edit would leave this loop no time to count
        ticks += 1
    t.join()
    assert ticks > 10000, ticks


def test_a_reversed_normal_is_never_a_success(cow_hierarchy):
    """§4.2's tangent rows hold for −N as well as N: an answer with the reverse normal ends `folded`
    (rows='tangent'); rows 'auto' (the default) solves again with frame rows, which meet N itself."""
    back, nose = selections(cow_hierarchy)
    finest = cow_hierarchy.mesh(cow_hierarchy.levels)
    n0 = fairshape.limit_normals(finest, scheme=cow_hierarchy.scheme)[nose[0]]
    side = np.cross(n0, [0.0, 0.0, 1.0] if abs(n0[2]) < 0.9 else [1.0, 0.0, 0.0])
    target = -n0 + 0.18 * side / np.linalg.norm(side)  # about 170 degrees from the rest normal
    held = [fairshape.fixed(back), fairshape.fixed(nose)]

    def normal(**rows):
        return fairshape.constraint("normal", vertices=nose.tolist(), normal=target.tolist(), **rows)

    tangent = fairshape.edit(cow_hierarchy, [ENERGY], held + [normal(rows="tangent")], mode="kkt", check=False)
    assert tangent.summary.termination == "folded" and not tangent.summary.succeeded
    assert tangent.normal_error_deg > 90 and "met by the reverse" in tangent.summary.message
    with pytest.raises(fairshape.SolveFailed, match="folded"):
        fairshape.edit(cow_hierarchy, [ENERGY], held + [normal(rows="tangent")], mode="kkt")
    frame = fairshape.edit(cow_hierarchy, [ENERGY], held + [normal()], mode="kkt", check=False)
    assert "so solved again with frame rows" in frame.summary.message
    assert frame.normal_error_deg < 1e-3 and frame.constraint_residual < 1e-9
    assert frame.summary.succeeded == (frame.flipped_faces == 0)
