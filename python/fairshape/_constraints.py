"""Energy and constraint terms of an edit, as the dicts of the config schema.

Every registered type works through constraint() / energy() with its options as keywords
(fairshape.components() lists them); an unknown option is refused when the edit reads it.
"""

import numpy as np


def _ids(vertices):
    ids = np.asarray(vertices)
    if ids.ndim != 1 or ids.size == 0 or ids.dtype.kind not in "iu":
        raise ValueError(f"vertices: expected a non-empty 1-D integer array, got shape {ids.shape} dtype {ids.dtype}")
    return ids.tolist()


def constraint(type, **options):
    """Any registered constraint: {'type': type, **options} (as in a config's constraints: list)."""
    return dict(type=type, **options)


def energy(type, weight=1.0, **options):
    """Any registered energy term: {'type': type, 'weight': weight, **options}."""
    return dict(type=type, weight=weight, **options)


def fixed(vertices, level=-1, **options):
    """The vertices (a 1-D integer array of ids on `level`, -1 the finest) stay where they are."""
    return constraint("fixed", vertices=_ids(vertices), level=level, **options)


def position(vertices, offset, level=-1, **options):
    """The vertices move by `offset`: shape (3,) for all of them, or (k, 3), one row per vertex.

    Returns one constraint dict, or a list of k of them for per-vertex offsets (edit() accepts both).
    """
    ids = _ids(vertices)
    off = np.asarray(offset, dtype=np.float64)
    if off.shape == (3,):
        return constraint("position", vertices=ids, offset=off.tolist(), level=level, **options)
    if off.shape == (len(ids), 3):
        return [constraint("position", vertices=[i], offset=o.tolist(), level=level, **options) for i, o in zip(ids, off)]
    raise ValueError(f"offset: expected shape (3,) or ({len(ids)}, 3), got {off.shape}")
