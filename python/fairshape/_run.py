"""`fairshape run` from Python: a config (a YAML file, or a dict of the same schema) run as
the command line runs it, its runs.csv returned as a pandas DataFrame."""

import json
import os
import tempfile

from . import _fairshape
from ._paths import CLI
from ._summary import RunFailed


def _absolute_defaults(config):
    # A dict has no folder of its own: its `defaults:` paths are relative to the current
    # directory (as input paths are in every config), made absolute before it is written out.
    d = dict(config)
    if "defaults" in d:
        items = d["defaults"] if isinstance(d["defaults"], list) else [d["defaults"]]
        d["defaults"] = [os.path.abspath(p) for p in items]
    return d


def _naming_the_dict(error, scratch):
    """The error with the scratch file's name replaced: the file is gone by the time the caller
    reads the message, and what they wrote was a dict."""
    renamed = type(error)(str(error).replace(scratch, "the config dict"))
    for attr in ("errno", "file", "line"):
        value = getattr(error, attr, None)
        if value is not None:
            setattr(renamed, attr, "the config dict" if value == scratch else value)
    return renamed


def _set_arg(key, value):
    return f"{key}={value if isinstance(value, str) else json.dumps(value)}"


def run(config, out=None, set=None, filters=None, jobs=1, resume=False, force=False, retry_failed=False,
        smoke=False, check=True):
    """Run an experiment config and return its runs.csv as a pandas DataFrame (one row per run).

    config: a path to a YAML config, or a dict of the same schema (written to a temporary
    file as JSON, which is YAML; its relative paths, `defaults:` included, are relative to
    the current directory). out: the output folder (default: a new temporary folder); the
    DataFrame's .attrs['out'] names it, with every file `fairshape run` writes (final.obj,
    iterations.csv, run.json, vtk/). set: {key.path: value} overrides (--set; a value that
    is not a string is written as JSON); filters: {key.path: value} (--filter); jobs, resume,
    force, retry_failed, smoke: as the command line's options.
    An invalid config raises InvalidConfig / InvalidInput with the command line's message and
    runs nothing. check=True raises RunFailed (with .runs) when some run failed (the CLI's exit
    3); check=False returns the table with the failures' termination and message.
    The runs happen in worker processes of the command line (fairshape._paths.CLI, or the
    FAIRSHAPE_CLI environment variable); the GIL is released meanwhile.
    """
    import pandas as pd

    if not os.path.exists(CLI):
        raise _fairshape.Error(f"run: the fairshape command line is not at {CLI} (set FAIRSHAPE_CLI)")
    out = os.fspath(out) if out is not None else tempfile.mkdtemp(prefix="fairshape-run-")
    sets = [_set_arg(k, v) for k, v in (set or {}).items()]
    filt = [_set_arg(k, v) for k, v in (filters or {}).items()]
    scratch = None
    if isinstance(config, dict):
        scratch = tempfile.NamedTemporaryFile("w", suffix=".yaml", prefix="fairshape-config-", delete=False)
        with scratch:
            json.dump(_absolute_defaults(config), scratch)
        path = scratch.name
    elif isinstance(config, (str, os.PathLike)):
        path = os.fspath(config)
    else:
        raise TypeError(f"config: expected a path or a dict, got {type(config).__name__}")
    try:
        status = _fairshape._run_sweep(path, out, sets, filt, jobs, resume, force, retry_failed, smoke, CLI)
    except _fairshape.Error as e:
        if scratch is None:
            raise
        raise _naming_the_dict(e, scratch.name) from None
    finally:
        if scratch is not None:
            os.unlink(scratch.name)
    if status == 128 + 2:
        raise KeyboardInterrupt(f"run interrupted; continue with resume=True, out={out!r}")
    if status >= 128:
        raise _fairshape.Error(f"run: interrupted by signal {status - 128}; continue with resume=True, out={out!r}")
    runs = pd.read_csv(os.path.join(out, "runs.csv"))
    runs.attrs["out"] = out
    runs.attrs["status"] = status
    if status == 3 and check:
        bad = runs[~runs["termination"].isin(["converged", "energy_stalled", "schedule_completed"])]
        lines = "; ".join(f"{r.run_id}: {r.termination}: {r.message}" for r in bad.itertuples())
        raise RunFailed(f"run: {len(bad)} of {len(runs)} run(s) failed ({lines})", runs)
    if status not in (0, 3):
        raise _fairshape.Error(f"run: the sweep ended with status {status}")
    return runs
