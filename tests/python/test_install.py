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
                      {'type': 'position', 'vertices': [7], 'offset': [0, 0, 0.1]}]}, out=sys.argv[5])
assert runs.loc[0, 'termination'] == 'converged', runs
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
    p = subprocess.run([sys.executable, "-c", SCRIPT, str(site), str(prefix), cow_path, str(tmp_path / "x.npy"),
                        str(tmp_path / "run")], env=env, cwd=tmp_path, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    h = fairshape.MultiresSurface(cow, 1)
    r = fairshape.edit(h, [fairshape.energy("detail_preserving")], [fairshape.fixed(np.arange(50)),
                       fairshape.position([900], [0.0, 0.1, 0.0])], mode="kkt")
    assert np.abs(np.load(tmp_path / "x.npy") - r.positions).max() < 1e-12
