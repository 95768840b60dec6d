"""The shape of a falling plate's path, measured the same way on Howison et al.'s recorded drops
(extract_reference.py) and on the model's (run.py). Positions in m, z up."""
import math

import numpy as np


def planarity(x, y):
    """sqrt(λ_min / λ_max) of the covariance of a path's horizontal positions: 0 when it stays in
    one vertical plane, 1 when it spreads equally in every horizontal direction; nan below 3
    samples, 0 for a path that does not move sideways"""
    if len(x) < 3:
        return math.nan
    lo, hi = np.linalg.eigvalsh(np.cov(np.vstack([x, y])))
    return math.sqrt(max(lo, 0.0) / hi) if hi > 0 else 0.0


def path_measures(x, y, z):
    """(straightness, horizontal path per descent, net lateral displacement) of a path: the net
    horizontal displacement over the horizontal path length (1: one direction all the way; 1 for
    a path that does not move sideways), that length per metre of descent, and the net
    displacement (m)"""
    x, y, z = (np.asarray(a, dtype=float) for a in (x, y, z))
    path = float(np.sum(np.hypot(np.diff(x), np.diff(y))))
    net = math.hypot(x[-1] - x[0], y[-1] - y[0])
    return net / path if path > 0 else 1.0, path / (z[0] - z[-1]), net
