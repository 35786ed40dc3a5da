# fairshape.run: a config file or dict run as `fairshape run` runs it, runs.csv as a DataFrame.
import json
import os

import numpy as np
import pandas as pd
import pytest

import fairshape
from conftest import cli, obj_vertices

SMALL = {
    "name": "python_run",
    "seed": 1,
    "input": {"mesh": "data/cow.off", "representation": "catmull-clark", "levels": 1},
    "energy": [{"type": "detail_preserving", "alpha": 0.1, "beta": 1.0}],
    "constraints": [{"type": "fixed", "region": {"axis": "x", "from": 0.0, "to": 0.3}},
                    {"type": "position", "nearest": [0.5, 0.0, 0.0], "offset": [0.15, 0.0, 0.08]}],
    "problem": {"constraint_mode": "kkt"},
    "defaults": ["configs/base/output.yaml"],
}


def test_run_dict_equals_cli_and_bindings(tmp_path, cow_hierarchy):
    runs = fairshape.run(SMALL, out=tmp_path / "py")
    assert isinstance(runs, pd.DataFrame) and len(runs) == 1
    assert runs.loc[0, "termination"] == "converged" and runs.attrs["status"] == 0
    assert {"run_id", "iterations", "residual", "detail_change", "solve_s"} <= set(runs.columns)
    config = tmp_path / "small.yaml"
    config.write_text(json.dumps(dict(SMALL, defaults=[os.path.abspath("configs/base/output.yaml")])))
    cli("run", config, "--out", tmp_path / "cli")
    py_final = obj_vertices(tmp_path / "py" / "final.obj")
    assert np.abs(py_final - obj_vertices(tmp_path / "cli" / "final.obj")).max() < 1e-12
    r = fairshape.edit(cow_hierarchy, SMALL["energy"], SMALL["constraints"], mode="kkt")
    assert np.abs(r.positions - py_final).max() < 1e-12
    # A subdivided (not remeshed) cow has no details: both say so with NaN.
    change = fairshape.relative_detail_change(cow_hierarchy, r.hierarchy)
    assert np.isnan(change) and np.isnan(runs.loc[0, "detail_change"])


def test_misspelt_key_of_a_dict_is_named_not_a_temporary_file(tmp_path):
    config = {k: v for k, v in SMALL.items() if k != "energy"}
    config["enregy"] = SMALL["energy"]
    with pytest.raises(fairshape.InvalidConfig, match="enregy") as e:  # the misspelling, named
        fairshape.run(config, out=tmp_path / "bad")
    message = str(e.value)
    assert "energy" in message.replace("enregy", "")  # the valid key
    assert message.startswith("the config dict") and "fairshape-config-" not in message


def test_run_sweep_with_sets(tmp_path):
    runs = fairshape.run("configs/smoke/cow_nose_pull.yaml", out=tmp_path / "s",
                         set={"solver": {"type": "conjugate_gradient", "tolerance": 1e-9, "max_iterations": 5000}})
    assert runs.loc[0, "termination"] == "converged" and runs.loc[0, "iterations"] > 1


def test_invalid_config_raises_and_runs_nothing(tmp_path):
    with pytest.raises(fairshape.InvalidConfig, match="bogus: unknown key"):
        fairshape.run(dict(SMALL, bogus=1), out=tmp_path / "bad")
    assert not (tmp_path / "bad" / "runs.csv").exists()


def test_failed_run_raises_run_failed(tmp_path):
    failing = dict(SMALL, problem={"constraint_mode": "paper"},
                   solver={"type": "gauss_seidel", "tolerance": 1e-12, "max_iterations": 2})
    with pytest.raises(fairshape.RunFailed, match="max_iterations") as e:
        fairshape.run(failing, out=tmp_path / "f")
    assert e.value.runs.loc[0, "termination"] == "max_iterations"
    runs = fairshape.run(failing, out=tmp_path / "g", check=False)
    assert runs.attrs["status"] == 3
