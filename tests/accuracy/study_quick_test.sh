#!/bin/bash
# The accuracy study tool and its report on a reduced sweep (seconds).
# Checks: the tool writes a CSV with every planned point measured (valid, finite, no failed
# body); euler's deterministic error grows with dt; single precision (splitting_float) stays
# within 1e-3 of double and is measured apart from it; the report writes a non-empty PNG, a
# tolerance table lrigid can read and a document; a bad argument fails with exit code 2.
# usage: study_quick_test.sh SOURCE_DIR STUDY_BINARY WORK_DIR
set -u
src=$1
tool=$2
work=$3
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$work"
mkdir -p "$work"
"$tool" --quick --source-dir "$src" --out "$work" 2> "$work/log" || { cat "$work/log"; fail "study"; }
[ -s "$work/accuracy.csv" ] || fail "no accuracy.csv"
/usr/bin/python3 - "$work/accuracy.csv" <<'PY' || fail "csv checks"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
det = [r for r in rows if r["sweep"] == "dt_det" and r["metric"] == "trajectory"]
det1 = [r for r in rows if r["sweep"] == "dt_det" and r["metric"] == "trajectory_t1"]
assert len(det1) == 15, len(det1)
for a, b in zip(det, det1):             # the first compared time is one of the times
    assert float(b["error"]) <= float(a["error"]), (a, b)
sto = [r for r in rows if r["sweep"] == "dt_stoch" and r["metric"] == "strong"]
assert len(det) == 15, len(det)         # 4 integrators and splitting in float x 3 dt
assert len(sto) == 12, len(sto)
for r in det + sto:
    assert r["valid"] == "1" and r["failed"] == "0", r
    assert math.isfinite(float(r["error"])) and float(r["error"]) > 0, r
    assert int(r["body_steps"]) > 0, r
e = sorted((float(r["dt"]), float(r["error"])) for r in det if r["integrator"] == "euler")
assert e[0][1] < e[1][1] < e[2][1], e   # first-order scheme: error grows with dt
prec = [r for r in rows if r["sweep"] == "precision" and r["metric"] == "trajectory"]
assert len(prec) == 3, len(prec)
for r in prec:                          # float really ran, and costs little on this scene
    assert r["integrator"] == "splitting_float", r
    assert 0 < float(r["error"]) < 1e-3, r
ref = [r for r in rows if r["sweep"] == "reference_det"][0]
assert float(ref["error"]) < 0.1 * min(x[1] for x in e), ref  # the reference is resolved
PY
/usr/bin/python3 "$src/bench/accuracy/make_report.py" --csv "$work/accuracy.csv" --out "$work" \
  --doc "$work/accuracy.md" > "$work/report.log" 2>&1 || { cat "$work/report.log"; fail "report"; }
[ -s "$work/error_vs_cost.png" ] || fail "no png"
[ -s "$work/accuracy.md" ] || fail "no document"
grep -q "cheapest way to" "$work/accuracy.md" || fail "no headline in the document"
grep -q "What single precision costs" "$work/accuracy.md" || fail "no float section"
/usr/bin/python3 -c "
import json, sys
t = json.load(open(sys.argv[1]))
assert t['kinds']['uniform-air'], t
" "$work/tolerance_table.json" || fail "tolerance table"
"$tool" --no-such-flag > /dev/null 2>&1
[ $? -eq 2 ] || fail "bad argument should exit with 2"
echo "study_quick: ok"
