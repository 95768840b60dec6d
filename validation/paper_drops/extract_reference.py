#!/usr/bin/python3
"""Write the reference tables of validation/paper_drops and validation/falling_plates from the
public data of Howison, Hughes & Iida (Nature Machine Intelligence 2020), repository
github.com/th533/Falling-Paper, folder Classification/ (MATLAB .mat files, read with scipy).

    extract_reference.py DIR      # DIR: a checkout (or `git show` export) of Classification/

Writes (next to this script and into ../falling_plates/):
* paper_drops/reference.json: per shape (circle, square) and radius bin, the number of classified
  trajectory segments, the median descent speed dz/time (m/s), the median lateral displacement
  sqrt(dx² + dy²) (m) and the counts of their behaviour labels (1 tumbling, 2 chaotic,
  3 steady/periodic), from data{Circle,Square}Classified.mat;
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

HERE = os.path.dirname(os.path.abspath(__file__))
# radius bins (m): the radius is a circle's radius or a square's half side
BINS = [(0.015, 0.025), (0.025, 0.035), (0.035, 0.045), (0.045, 0.0501)]


def shape_table(path):
    d = scipy.io.loadmat(path, squeeze_me=True)
    R, b = d["radius"], d["behaviourAuto"]
    v = d["dz"] / d["time"]
    lat = np.hypot(d["dx"], d["dy"])
    rows = []
    for lo, hi in BINS:
        m = (R >= lo) & (R < hi)
        rows.append(dict(r_lo=lo, r_hi=min(hi, 0.05), n=int(m.sum()),
                         median_speed=float(np.median(v[m])),
                         median_lateral=float(np.median(lat[m])),
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
               circle=shape_table(os.path.join(src, "dataCircleClassified.mat")),
               square=shape_table(os.path.join(src, "dataSquareClassified.mat")))
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
