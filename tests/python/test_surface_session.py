# fairshape.SurfaceEditSession: the bound session driven step by step gives `fairshape run` of the
# same config's steps bit for bit; its keys go through the run kind's reader.
import numpy as np
import pytest
import yaml

import fairshape
from conftest import cli, obj_vertices

CONFIG = {
    "name": "session",
    "seed": 1,
    "input": {"mesh": "data/cow.off", "representation": "catmull-clark", "levels": 1},
    "energy": [{"type": "detail_preserving", "alpha": 0.1, "beta": 1.0}],
    "constraints": [{"type": "fixed", "region": {"axis": "x", "from": 0.0, "to": 0.3}},
                    {"type": "position", "nearest": [0.5, 0.0, 0.0], "offset": [0.06, 0.0, 0.032]}],
    "problem": {"constraint_mode": "paper", "accuracy": "interactive", "coarse_level": 0},
    "output": {"vtk": "none", "iterations": False},
}
STEPS = [{"offsets": {1: [0.03, 0.0, 0.016]}}, {"offsets": {1: [0.06, 0.0, 0.032]}}, {"accuracy": "converged"}]


def cli_run(tmp_path, config):
    path = tmp_path / "session.yaml"
    path.write_text(yaml.safe_dump(config))
    out = tmp_path / "cli"
    cli("run", path, "--out", out)
    return obj_vertices(out / "final.obj")


def test_session_steps_equal_the_config_run(tmp_path):
    expected = cli_run(tmp_path, dict(CONFIG, steps=STEPS))
    s = fairshape.SurfaceEditSession(CONFIG)
    assert s.handles == [0, 1]
    s.move(1, [0.03, 0.0, 0.016])
    first = s.solve()
    assert first.accuracy == "interactive" and first.summary.succeeded and first.flipped_faces == 0
    prepared = s.preparations
    s.move(1, [0.06, 0.0, 0.032])
    s.solve()
    assert s.preparations == prepared  # a drag step: nothing analysed again
    last = s.solve("converged")
    assert last.accuracy == "converged" and last.constraint_residual < 1e-9
    assert np.array_equal(s.vertices, expected)
    # The config's own steps, replayed by the same session type, as `fairshape run` solves them.
    replayed = fairshape.SurfaceEditSession(CONFIG, steps=STEPS)
    assert [r.accuracy for r in replayed.replay()] == ["interactive", "interactive", "converged"]
    assert np.array_equal(replayed.vertices, expected)


def test_session_keys_are_the_configs(cow_hierarchy):
    with pytest.raises(fairshape.InvalidConfig, match=r"problem.acuracy: unknown key"):
        fairshape.SurfaceEditSession(dict(CONFIG, problem={"acuracy": "interactive"}))
    with pytest.raises(fairshape.InvalidConfig, match="given both"):
        fairshape.SurfaceEditSession(CONFIG, problem={})
    with pytest.raises(fairshape.InvalidConfig, match=r"steps\[0\].offsets.5: no such handle"):
        fairshape.SurfaceEditSession(CONFIG, steps=[{"offsets": {5: [0, 0, 0]}}])
    with pytest.raises(fairshape.InvalidConfig, match="input.mesh"):
        fairshape.SurfaceEditSession({k: v for k, v in CONFIG.items() if k != "input"}, hierarchy=cow_hierarchy,
                                     input={"mesh": "data/cow.off"})


def test_session_handles_move_add_remove(cow_hierarchy):
    back = fairshape.constraint("fixed", region={"axis": "x", "from": 0.0, "to": 0.3})
    nose = fairshape.constraint("position", nearest=[0.5, 0, 0], offset=[0.06, 0, 0.032])
    s = fairshape.SurfaceEditSession(energy=[fairshape.energy("detail_preserving", alpha=0.1, beta=1.0)],
                                     constraints=[back, nose], hierarchy=cow_hierarchy)
    before = s.solve()
    r = fairshape.edit(cow_hierarchy, [fairshape.energy("detail_preserving", alpha=0.1, beta=1.0)], [back, nose], mode="kkt")
    assert np.array_equal(before.delta, r.delta)  # fairshape.edit is one solve of a session
    h = s.add(fairshape.constraint("position", nearest=[0.45, 0.1, 0.0], offset=[0, 0.02, 0]))
    assert h == 2 and s.handles == [0, 1, 2]
    s.solve()
    s.remove(h)
    with pytest.raises(fairshape.InvalidInput, match="removed"):
        s.move(h, [0, 0, 0])
    assert np.array_equal(s.solve().delta, before.delta)
    with pytest.raises(fairshape.InvalidInput, match="ladder"):
        s.solve("improved")
    with pytest.raises(fairshape.InvalidConfig, match="interactive, improved, converged"):
        s.solve("fast")
