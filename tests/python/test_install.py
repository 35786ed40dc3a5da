# The installed package: `cmake --install` puts fairshape under <prefix>/<site dir>, and a
# script run outside the source and build trees imports it from there alone, finds the
# installed command line, and gives the build tree's answers.
import os
import subprocess
import sys

import numpy as np
import pytest

import fairshape

BUILD = os.environ.get("FAIRSHAPE_BUILD_DIR")
SITE = os.environ.get("FAIRSHAPE_PYTHON_INSTALL_DIR")

SCRIPT = r"""
import os, sys, numpy as np, fairshape
assert fairshape.__file__.startswith(sys.argv[1]), fairshape.__file__
from fairshape import _paths
assert os.path.samefile(_paths.CLI, sys.argv[2] + '/bin/fairshape'), _paths.CLI
h = fairshape.MultiresSurface(fairshape.read_mesh(sys.argv[3]), 1)
r = fairshape.edit(h, [fairshape.energy('detail_preserving')], [fairshape.fixed(np.arange(50)),
                   fairshape.position([900], [0.0, 0.1, 0.0])], mode='kkt')
np.save(sys.argv[4], r.positions)
runs = fairshape.run({'name': 'installed', 'input': {'mesh': sys.argv[3], 'representation': 'mesh'},
                      'energy': [{'type': 'membrane'}], 'constraints': [{'type': 'fixed', 'vertices': [0]},
                      {'type': 'position', 'vertices': [7], 'offset': [0, 0, 0.02]}]}, out=sys.argv[5])
assert runs.loc[0, 'termination'] == 'converged', runs
# The demo (configs/demo.yaml at its CI size) through the installed command line, and its
# detail-preserving edit again through the installed bindings.
demo = fairshape.run(sys.argv[6], out=sys.argv[7], smoke=True)
assert (demo['termination'] == demo['expect'].replace('success', 'converged')).all(), demo  # the thin plates fold
rest, _ = fairshape.remesh(fairshape.read_mesh(sys.argv[3]), base_faces=200, levels=2)
P = rest.positions()
lo, hi = P[:, 0].min(), P[:, 0].max()
back = np.flatnonzero(P[:, 0] <= lo + 0.3 * (hi - lo))
nose = np.argmin(np.linalg.norm(P - [0.5, 0.0, 0.0], axis=1))
r = fairshape.edit(rest, [fairshape.energy('detail_preserving', alpha=0.1, beta=1.0)],
                   [fairshape.fixed(back), fairshape.position([nose], [0.15, 0.0, 0.08])], solver='cholesky')
again = fairshape.MultiresSurface.analyze(rest.mesh(0), r.hierarchy.positions(), rest.levels)
np.save(sys.argv[8], [fairshape.relative_detail_change(rest, again)])
"""


@pytest.mark.skipif(not BUILD or not SITE, reason="set by ctest: FAIRSHAPE_BUILD_DIR, FAIRSHAPE_PYTHON_INSTALL_DIR")
def test_installed_package_works_alone(tmp_path, cow):
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", BUILD, "--prefix", str(prefix)], check=True, capture_output=True)
    site = prefix / SITE
    assert (site / "fairshape" / "__init__.py").exists() and list((site / "fairshape").glob("_fairshape*.so"))
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "FAIRSHAPE_CLI")}
    env["PYTHONPATH"] = str(site)
    cow_path = os.path.abspath("data/cow.off")
    demo_config = os.path.abspath("configs/demo.yaml")
    p = subprocess.run([sys.executable, "-c", SCRIPT, str(site), str(prefix), cow_path, str(tmp_path / "x.npy"),
                        str(tmp_path / "run"), demo_config, str(tmp_path / "demo"), str(tmp_path / "change.npy")],
                       env=env, cwd=tmp_path, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    # The installed tree reproduces the demo's numbers: every deterministic column of runs.csv
    # equals the build tree's run of the same config, and the bindings' edit its detail change.
    import pandas as pd
    here = fairshape.run(demo_config, out=tmp_path / "demo_here", smoke=True)
    there = pd.read_csv(tmp_path / "demo" / "runs.csv")
    timing = [c for c in here.columns if c.endswith("_s") or c.endswith("_mb") or c in ("fairshape_version", "message")]
    assert len(here) == len(there) == 3
    for column in [c for c in here.columns if c not in timing]:
        a, b = here[column].tolist(), there[column].tolist()
        if pd.api.types.is_float_dtype(here[column]):
            assert np.allclose(a, b, rtol=1e-12, atol=0, equal_nan=True), (column, a, b)
        else:
            assert a == b, (column, a, b)
    preserving = here[here["param.energy"].astype(str).str.contains("detail_preserving")]
    assert len(preserving) == 1
    assert abs(np.load(tmp_path / "change.npy")[0] - preserving["detail_change"].iloc[0]) < 1e-6 * preserving["detail_change"].iloc[0]
    h = fairshape.MultiresSurface(cow, 1)
    r = fairshape.edit(h, [fairshape.energy("detail_preserving")], [fairshape.fixed(np.arange(50)),
                       fairshape.position([900], [0.0, 0.1, 0.0])], mode="kkt")
    assert np.abs(np.load(tmp_path / "x.npy") - r.positions).max() < 1e-12
