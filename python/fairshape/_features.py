"""Fine level feature editing (Khodakovsky & Schröder) on a Loop hierarchy."""

from dataclasses import dataclass

import numpy as np

from . import _fairshape

# The session itself (python/src/features.cpp): set up from a feature config's keys, advanced by
# add / replace / move / set / remove, each step re-evaluating only the region it reaches.
FeatureSession = _fairshape.FeatureSession

_PARAMS = ("radius", "left_right_ratio", "height", "crease", "end_height_ratio", "flatness_angle_deg", "max_turn_deg",
           "quadratic", "quadratic_samples", "profile_tolerance", "width_tolerance")


def feature(points=None, faces=None, bary=None, level=0, name=None, closed=False, max_distance=0.02, **params):
    """A feature curve as a dict for fairshape.apply_features (a feature config's `features:` entry).

    Either points: k×3 world points, projected onto level `level` (each within max_distance ×
    the bounding-box diagonal), or faces (k face ids of that level) with bary (k×3 barycentric
    coordinates). params (world units, as in a config): radius (r, left side), left_right_ratio,
    height (negative: a groove), crease, end_height_ratio, flatness_angle_deg, max_turn_deg,
    quadratic, quadratic_samples, profile_tolerance, width_tolerance; an unknown one raises
    InvalidConfig naming the valid ones (when applied).
    """
    d = {"level": int(level), "closed": bool(closed), "max_distance": float(max_distance)}
    if name is not None:
        d["name"] = name
    if points is not None:
        d["points"] = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if faces is not None:
        d["faces"] = np.asarray(faces, dtype=np.int64).ravel()
        d["bary"] = np.asarray(bary, dtype=np.float64).reshape(-1, 3)
    d.update(params)
    return d


@dataclass
class FeatureResult:
    """positions: the finest level with every feature applied (n×3, a new array); hierarchy: it
    as a new MultiresSurface (every level perturbed); features: one dict per feature, a row of
    features.csv: name, level, height, radius_left, radius_right, fine / limit (each height_min,
    height_max, width_left, width_right, height_error, width_error, profile_error: errors as
    fractions of |height|, widths of the radius), within_tolerance, why (the first miss);
    within_tolerance: every feature's; placed: per feature its (faces k, bary k×3) on its level;
    flipped_faces: finest faces the features turned over against the surface without them, and
    folds, where ('' when none): a fold is a failed result whatever the profiles say."""

    positions: np.ndarray
    hierarchy: _fairshape.MultiresSurface
    features: list
    within_tolerance: bool
    placed: list
    flipped_faces: int = 0
    folds: str = ""


def apply_features(hierarchy, features, profile_on="limit", implementation="optimized"):
    """Apply feature curves (fairshape.feature(...) dicts) to a Loop hierarchy
    (fairshape.MultiresSurface(mesh, levels, scheme='loop')), coarse to fine (§2.5–2.6).

    profile_on: 'limit' (the limit surface at the finest vertices shows the profile exactly),
    'finest' (the finest control points) or 'drawn_level' (the paper: the drawn level's).
    Raises InvalidInput for a curve that leaves the surface or a non-Loop hierarchy, and
    fairshape's error for a feature that cannot be applied. The GIL is released while the
    features are placed, applied and measured.
    """
    if isinstance(features, dict):
        features = [features]
    r = _fairshape._apply_features(hierarchy, list(features), profile_on, implementation)
    return FeatureResult(positions=r["positions"], hierarchy=r["hierarchy"], features=list(r["features"]),
                         within_tolerance=r["within_tolerance"], placed=list(r["placed"]),
                         flipped_faces=r["flipped_faces"], folds=r["folds"])


FeatureResult.__module__ = "fairshape"
