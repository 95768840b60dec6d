#!/usr/bin/python3
"""Study 7: foam2grid against OpenFOAM's own sampling on the real scenes.

The converter's accuracy test (tests/converters/foam2grid/accuracy_test.cpp) compares it with
OpenFOAM's `sets` function object (cellPoint interpolation, run by postProcess) on the tiny case.
Here the same comparison runs on the shipped scene cases, at fewer random valid grid points:
the case is run by its Allrun, converted by foam2grid, and OpenFOAM samples U, k, epsilon, nut at
the grid points. Reference: OpenFOAM's value; tolerance 1e-6 of the field's range over the grid
(|U| max, or max − min), as in the converter's test: foam2grid stores float32 (relative rounding
6e-8), and reproduces the same cellPoint interpolation, so anything above float rounding is a
converter error. A point counts when OpenFOAM returns it (points on a wall can be dropped by the
sampler; at least 90 % must come back).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lib"))
import vcommon as vc  # noqa: E402
from vcommon import np, plt  # noqa: E402

TOL = 1e-6
SRC = "OpenFOAM v1912 postProcess, sets (cloud, cellPoint)"


def read_grid(path):
    import vtk
    from vtk.util import numpy_support as ns
    r = vtk.vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    pd = img.GetPointData()
    arr = {n: ns.vtk_to_numpy(pd.GetArray(n)).astype(float) for n in
           ("U", "k", "epsilon", "nut", "valid")}
    return img.GetDimensions(), img.GetOrigin(), img.GetSpacing(), arr


def sample_openfoam(case, pts, tag):
    d = os.path.join(case, "system", "validationProbes_%s" % tag)
    with open(d, "w") as o:
        o.write("FoamFile { version 2.0; format ascii; class dictionary; object probes; }\n"
                "functions\n{\n  vprobes\n  {\n    type sets;\n    libs (\"libsampling.so\");\n"
                "    interpolationScheme cellPoint;\n    setFormat raw;\n"
                "    writeControl writeTime;\n    fields (U k epsilon nut);\n    sets\n    (\n"
                "      pts\n      {\n        type cloud;\n        axis xyz;\n        points\n"
                "        (\n")
        for p in pts:
            o.write("          (%.17g %.17g %.17g)\n" % tuple(p))
        o.write("        );\n      }\n    );\n  }\n}\n")
    vc.run(["/usr/bin/postProcess", "-case", case, "-dict", d, "-latestTime", "-fields",
            "(U k epsilon nut)"], log=os.path.join(case, "log.postProcess.validation"),
           env=vc.foam_env())
    outdir = os.path.join(case, "postProcessing", "vprobes", vc.latest_time(case))
    U = np.loadtxt(os.path.join(outdir, "pts_U.xy"), ndmin=2)
    S = np.loadtxt(os.path.join(outdir, "pts_epsilon_k_nut.xy"), ndmin=2)
    return U, S


def compare(st, args, name, spacing, npts, seed):
    case = vc.foam_case(args, name)
    grid = st.path("%s.vti" % name)
    vc.run([args.foam2grid, case, "-o", grid, "--spacing", str(spacing), "--quiet"])
    dims, origin, h, arr = read_grid(grid)
    nx, ny, nz = dims
    valid = np.nonzero(arr["valid"] > 0)[0]
    rng = np.random.default_rng(seed)
    ids = rng.choice(valid, size=min(npts, len(valid)), replace=False)
    i, j, k = ids % nx, (ids // nx) % ny, ids // (nx * ny)
    pts = np.stack([origin[0] + i * h[0], origin[1] + j * h[1], origin[2] + k * h[2]], axis=1)
    U, S = sample_openfoam(case, pts, name)
    key = {tuple(np.round(p, 9)): n for n, p in enumerate(pts)}
    Ug = arr["U"].reshape(-1, 3)
    ranges = {"U": np.max(np.linalg.norm(Ug[valid], axis=1)),
              "k": np.ptp(arr["k"][valid]), "epsilon": np.ptp(arr["epsilon"][valid]),
              "nut": np.ptp(arr["nut"][valid])}
    err = {f: [] for f in ranges}
    pairs = {f: [] for f in ranges}
    for row in U:
        n = key.get(tuple(np.round(row[:3], 9)))
        if n is None:
            continue
        e = np.max(np.abs(Ug[ids[n]] - row[3:6])) / ranges["U"]
        err["U"].append(e)
        pairs["U"].append((np.linalg.norm(row[3:6]), np.linalg.norm(Ug[ids[n]])))
    for row in S:
        n = key.get(tuple(np.round(row[:3], 9)))
        if n is None:
            continue
        for f, col in (("epsilon", 3), ("k", 4), ("nut", 5)):
            err[f].append(abs(arr[f][ids[n]] - row[col]) / ranges[f])
            pairs[f].append((row[col], arr[f][ids[n]]))
    nback = len(err["U"])
    st.check("%s: points returned by OpenFOAM's sampler" % name, nback / len(pts), 1.0, 0.1,
             SRC, tol_text="≥ 90 %% of %d" % len(pts),
             verdict="PASS" if nback >= 0.9 * len(pts) else "FAIL")
    for f in ranges:
        m = max(err[f]) if err[f] else float("nan")
        st.check("%s: max |foam2grid − OpenFOAM| / range, %s (%d points)" % (name, f, len(err[f])),
                 m, 0.0, TOL, SRC, tol_text="≤ 1e-6 of range (float32 output)")
    return pairs


def main():
    args = vc.parse_args()
    st = vc.Study("converter_probes", "Converter vs OpenFOAM sampling on the scene cases", args)
    fig, axs = plt.subplots(1, 2, figsize=(8, 3.5))
    for (name, spacing, npts), ax in zip((("windCourtyard", 1.0, 300), ("tiny", 0.01, 200)),
                                         axs):
        try:
            pairs = compare(st, args, name, spacing, npts, 7)
        except RuntimeError as e:
            st.fail("%s: case run / conversion / sampling" % name, str(e).splitlines()[0][:200])
            continue
        a = np.array(pairs["k"])
        if len(a):
            ax.plot(a[:, 0], a[:, 1], "o", ms=3)
            lim = [a.min(), a.max()]
            ax.plot(lim, lim, "k-", lw=0.8)
        ax.set_title("%s: k at grid points" % name)
        ax.set_xlabel("OpenFOAM sets, cellPoint [m²/s²]")
        ax.set_ylabel("foam2grid [m²/s²]")
    st.savefig(fig, "k_scatter.png", "k at random grid points: foam2grid against OpenFOAM's own "
               "cellPoint sampling")
    st.note("tankJet (transient, 20 s of pimpleFoam) is not included: its run alone would take "
            "most of the validation budget on 2 cores.")
    st.finish()


if __name__ == "__main__":
    main()
