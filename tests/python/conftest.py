# Shared fixtures of the Python suite (ctest python.pytest runs it from the source root with
# PYTHONPATH=build/python and FAIRSHAPE_CLI set to the build's command line).
import os
import subprocess

import numpy as np
import pytest

import fairshape

CLI = os.environ.get("FAIRSHAPE_CLI", fairshape._paths.CLI if hasattr(fairshape, "_paths") else "build/bin/fairshape")


def cli(*args, cwd=None):
    """Runs the command line; returns the completed process (raises with its stderr on failure)."""
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, cwd=cwd)
    if p.returncode != 0:
        raise AssertionError(f"fairshape {' '.join(map(str, args))}: exit {p.returncode}\n{p.stderr}")
    return p


def obj_vertices(path):
    return np.array([[float(t) for t in line.split()[1:4]] for line in open(path) if line.startswith("v ")])


@pytest.fixture(scope="session")
def cow():
    return fairshape.read_mesh("data/cow.off")


@pytest.fixture(scope="session")
def cow_hierarchy(cow):
    """The cow subdivided once (Catmull-Clark): 11.6k vertices, an edit in about a second."""
    return fairshape.MultiresSurface(cow, 1)
