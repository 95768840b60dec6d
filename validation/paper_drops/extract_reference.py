#!/usr/bin/python3
"""Write the reference tables of validation/paper_drops and validation/falling_plates from the
public data of Howison, Hughes & Iida (Nature Machine Intelligence 2020), repository
github.com/th533/Falling-Paper, folder Classification/ (MATLAB .mat files, read with scipy).

    extract_reference.py DIR      # DIR: a checkout (or `git show` export) of Classification/

Writes (next to this script and into ../falling_plates/):
* paper_drops/reference.json: per shape (circle, square) and radius bin, the number of classified
  trajectory segments, the median descent speed dz/time (m/s), the median lateral displacement
  sqrt(dx² + dy²) (m) and the counts of their behaviour labels (1 tumbling, 2 chaotic,
  3 steady/periodic) and a bootstrap 90 % interval of the median lateral displacement, from
  data{Circle,Square}Classified.mat; and from the raw drops
  (data{Circle,Square}.mat, trimmed below 5 cm as the classification does): the number of drops
  released horizontally (initialCondition 0) and vertically (1), their median release height (m),
  the median planarity of their paths, sqrt(λ_min / λ_max) of the horizontal positions'
  covariance (0: the plate stays in one vertical plane), the median straightness (net horizontal
  displacement over the horizontal path length), the median horizontal path per metre of descent,
  the median whole-drop lateral displacement per release (horizontal, vertical), the tracked
  horizontal positions' noise level (m, from their second differences), and how fast the plate
  already moves at the first tracked sample (98 Hz, over the first two intervals):
  median descent and sideways speed per release;
* falling_plates/field1997.json: Field, Klaus, Moore & Nori (Nature 388, 1997)'s disk regime map
  as digitised by Howison et al. (Field1997_data.mat): points (Re, I*_d, regime 1 steady,
  2 periodic, 3 chaotic, 4 tumbling) and the three boundary lines.
The derived tables are committed, so the studies need neither scipy nor the repository.
"""
import json
import os
import sys

import numpy as np
import scipy.io

from paths import path_measures, planarity  # the measures run.py applies to the model's drops

HERE = os.path.dirname(os.path.abspath(__file__))
# radius bins (m): the radius is a circle's radius or a square's half side
BINS = [(0.015, 0.025), (0.025, 0.035), (0.035, 0.045), (0.045, 0.0501)]
FPS = 98.0   # the trajectories' frame rate (classifyBehaviour.m: time = samples / 98)


def drops_table(path):
    """per radius bin: release counts, median release height, planarity, straightness, horizontal
    path per descent and whole-drop lateral displacement (per release) of the raw drops"""
    d = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)
    drops = []
    for e in d["data"]:
        tr = np.asarray(e.trajectory, dtype=float)
        keep = np.nonzero(tr[:, 2] >= 0.05)[0]   # trimmed below 5 cm, as classifyBehaviour.m does
        tr = tr[:keep[-1] + 1] if len(keep) else tr[:0]
        drops.append((float(e.radius), int(e.initialCondition), tr,
                      np.asarray(e.trajectory, dtype=float)[:3]))
    rows = []
    for lo, hi in BINS:
        b = [x for x in drops if lo <= x[0] < hi]
        pm = [(x[1], path_measures(*x[2].T)) for x in b if len(x[2]) > 10]
        # white-noise level of the tracked horizontal positions: the second differences' MAD
        noise = [np.median(np.abs(np.diff(x[2][:, :2], 2, axis=0))) / 0.6745 / np.sqrt(6)
                 for x in b if len(x[2]) > 10]
        rows.append(dict(n_drops_horizontal=sum(x[1] == 0 for x in b),
                         median_position_noise=float(np.median(noise)),
                         n_drops_vertical=sum(x[1] == 1 for x in b),
                         median_release_height=float(np.median([x[2][0, 2] for x in b
                                                                if len(x[2])])),
                         median_planarity=float(np.median([planarity(x[2][:, 0], x[2][:, 1])
                                                           for x in b if len(x[2]) > 10])),
                         median_straightness=float(np.median([m[0] for _, m in pm])),
                         median_path_per_descent=float(np.median([m[1] for _, m in pm])),
                         median_lateral_horizontal_release=float(np.median(
                             [m[2] for ic, m in pm if ic == 0])),
                         median_lateral_vertical_release=float(np.median(
                             [m[2] for ic, m in pm if ic == 1]))))
        for ic, name in ((0, "horizontal"), (1, "vertical")):
            first = [x[3] for x in b if x[1] == ic and len(x[3]) == 3]
            rows[-1]["median_initial_descent_speed_" + name] = float(np.median(
                [(f[0, 2] - f[2, 2]) * FPS / 2 for f in first]))
            rows[-1]["median_initial_sideways_speed_" + name] = float(np.median(
                [np.hypot(*(f[2, :2] - f[0, :2])) * FPS / 2 for f in first]))
    return rows


def median_ci90(x, resamples=4000, seed=1):
    """the 5th and 95th percentiles of the median of x over bootstrap resamples: how well the
    sample fixes its median"""
    rng = np.random.default_rng(seed)
    meds = np.median(rng.choice(x, size=(resamples, len(x))), axis=1)
    return [float(q) for q in np.percentile(meds, [5, 95])]


def shape_table(path, raw):
    d = scipy.io.loadmat(path, squeeze_me=True)
    R, b = d["radius"], d["behaviourAuto"]
    v = d["dz"] / d["time"]
    lat = np.hypot(d["dx"], d["dy"])
    rows = []
    for (lo, hi), extra in zip(BINS, drops_table(raw)):
        m = (R >= lo) & (R < hi)
        rows.append(dict(**extra, r_lo=lo, r_hi=min(hi, 0.05), n=int(m.sum()),
                         median_speed=float(np.median(v[m])),
                         median_lateral=float(np.median(lat[m])),
                         median_lateral_ci90=median_ci90(lat[m]),
                         n_tumbling=int((b[m] == 1).sum()), n_chaotic=int((b[m] == 2).sum()),
                         n_steady_periodic=int((b[m] == 3).sum())))
    return rows


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    src = sys.argv[1]
    ref = dict(source="Howison, Hughes & Iida, Nature Machine Intelligence 2020; data "
                      "github.com/th533/Falling-Paper Classification/data*Classified.mat",
               paper=dict(areal_density=0.070, thickness=6.94e-5, density=1008.0),
               bins=BINS,
               circle=shape_table(os.path.join(src, "dataCircleClassified.mat"),
                                  os.path.join(src, "dataCircle.mat")),
               square=shape_table(os.path.join(src, "dataSquareClassified.mat"),
                                  os.path.join(src, "dataSquare.mat")))
    out = os.path.join(HERE, "reference.json")
    with open(out + ".tmp", "w") as f:
        json.dump(ref, f, indent=1)
    os.replace(out + ".tmp", out)
    fd = scipy.io.loadmat(os.path.join(src, "Field1997_data.mat"))
    pts = np.vstack([fd[k] for k in ("c", "tri", "s")])
    field = dict(source="Field, Klaus, Moore & Nori, Nature 388, 252 (1997), Fig. 1 as digitised "
                        "by Howison et al. (github.com/th533/Falling-Paper "
                        "Classification/Field1997_data.mat)",
                 istar="I*_d = pi rho_s h / (64 rho_f d)", re="Re = U d / nu (mean descent)",
                 regimes={"1": "steady", "2": "periodic", "3": "chaotic", "4": "tumbling"},
                 points=[[float(a), float(b_), int(c)] for a, b_, c in pts],
                 boundary_steady=fd["l1"][:, :2].tolist(),
                 boundary_periodic_chaotic=fd["l2"][:, :2].tolist(),
                 boundary_chaotic_tumbling=fd["l3"][:, :2].tolist())
    out = os.path.join(HERE, "..", "falling_plates", "field1997.json")
    with open(out + ".tmp", "w") as f:
        json.dump(field, f, indent=0)
    os.replace(out + ".tmp", out)
    print("wrote reference.json and ../falling_plates/field1997.json")


if __name__ == "__main__":
    main()
