#!/bin/bash
# Tests of foam_cases/bin/foamWindCase (ctest label foam): a wind case around a geometry file.
#   wind_geometry_test.sh SOURCE_DIR WORK_DIR FOAM2GRID TEST
# TEST is one of
#   badGeometry  open, inverted, non-manifold, self-intersecting, empty, not-a-mesh, far too
#                large and far too small geometries: exit 3, a message naming the file and the
#                problem (and where), and nothing left behind (no case, no temporary directory)
#   lBuilding    a generated L-shaped building, wind towards 30 deg, -np 2, end to end: exit 0,
#                checkMesh 'Mesh OK', the converged run's checks, and in the grid every point
#                inside the building invalid, the points outside valid
#   objYup       the same L building exported as a Y-up OBJ (as Blender does) gives the same
#                case, file for file, as the Z-up STL (both written with --no-run: the solver and
#                the converter then get the same input)
#   sphere       a sphere sunk a little into the ground (--ground 0), wind along +x: end to end,
#                geometry inside invalid, and the approach profile 1 H downstream of the inlet
#                matches the log law within 5 % at 0.5 H, 1 H and 2 H
#   cube         a surface-mounted cube, wind along +x: the recirculation length behind it on
#                the centre line lies in the range reported for k-epsilon (see docs/own-geometry.md)
set -u
SRC=$1
WORK=$2
export FOAM2GRID=$(realpath "$3")
TEST=$4
export WM_PROJECT_DIR=/usr/share/openfoam
export PATH=/usr/bin:/bin:$PATH
BIN=$SRC/foam_cases/bin
CHECK="/usr/bin/python3 $SRC/tests/foam_cases/wind_grid_check.py"

fail() { echo "FAIL [$TEST]: $*" 1>&2; exit 1; }
note() { echo "[$TEST] $*"; }

mkdir -p "$WORK" || fail "cannot create $WORK"
cd "$WORK" || exit 1

# expectBad FILE PATTERN [options]: foamWindCase must exit 3 with PATTERN and leave nothing
expectBad() {
    local file=$1 pattern=$2; shift 2
    local out rc
    rm -rf bad_case .bad_case.tmp-*
    out=$("$BIN/foamWindCase" "$file" bad_case --no-grid "$@" 2>&1)
    rc=$?
    [ $rc -eq 3 ] || { echo "$out"; fail "$file: exit $rc, expected 3"; }
    echo "$out" | grep -q -E -- "$pattern" || { echo "$out"; fail "$file: message lacks '$pattern'"; }
    [ ! -e bad_case ] || fail "$file: a case was left behind"
    ! ls -d .bad_case.tmp-* > /dev/null 2>&1 || fail "$file: a temporary directory was left behind"
    note "$(echo "$out" | grep -E -- "$pattern" | head -n 1)"
}

# runCase GEOMETRY CASE [options]: foamWindCase must succeed and write a grid
runCase() {
    local geom=$1 case=$2; shift 2
    rm -rf "$case"
    local t0=$SECONDS
    "$BIN/foamWindCase" "$geom" "$case" "$@" > "$case.out" 2>&1 \
        || { cat "$case.out"; fail "foamWindCase $geom failed"; }
    note "foamWindCase $geom $* took $((SECONDS - t0)) s"
    grep -q '^Mesh OK' "$case/log.checkMesh" || fail "$case/log.checkMesh does not say 'Mesh OK'"
    grep -q 'all checks passed' "$case.out" || fail "the case's sanity checks did not pass"
    grep -q '^End' "$case/log.simpleFoam" || fail "$case/log.simpleFoam has no final End"
    [ -f "$case/grid.vti" ] || fail "no $case/grid.vti"
    note "$(grep '^Mesh OK' "$case.out")"
    note "iterations: $(grep -c '^Time = ' "$case/log.simpleFoam")"
}

case "$TEST" in
badGeometry)
    for s in broken-open broken-inverted broken-nonmanifold broken-selfintersecting cube; do
        "$BIN/foamMakeGeometry" "$s" "$s.stl" || fail "foamMakeGeometry $s"
    done
    expectBad broken-open.stl 'broken-open.stl: the surface is open: 4 edges .*\(-5 -5 0\)'
    expectBad broken-inverted.stl 'broken-inverted.stl: inverted: .*normals pointing inwards'
    expectBad broken-nonmanifold.stl 'broken-nonmanifold.stl: not manifold: 4 edges .*\(5 5 0\)'
    expectBad broken-selfintersecting.stl \
        'broken-selfintersecting.stl: self-intersecting: .*e\.g\. at \('
    : > empty.stl
    expectBad empty.stl 'empty.stl: the file is empty'
    echo 'hello, not a mesh' > notamesh.obj
    expectBad notamesh.obj 'notamesh.obj:1: not an OBJ file'
    printf 'v 0 0 0\nv 1 0 0\n' > novertices.obj
    expectBad novertices.obj 'novertices.obj: not a mesh: no triangles'
    expectBad cube.stl 'far too large .*--scale 0.001' --scale 1000
    expectBad cube.stl 'far too small' --scale 0.001
    expectBad cube.stl '--z0 5 m is too large' --z0 5
    # the usage errors: exit 2
    "$BIN/foamWindCase" cube.stl x --speed -1 > usage.out 2>&1
    [ $? -eq 2 ] || fail "--speed -1 did not exit 2"
    grep -q -- '--speed: -1 m/s, must be > 0' usage.out || fail "no message for --speed -1"
    ;;
lBuilding)
    "$BIN/foamMakeGeometry" lbuilding lbuilding.stl || fail "foamMakeGeometry"
    runCase lbuilding.stl lbuilding --direction 30 -np 2
    $CHECK inside lbuilding || fail "grid check"
    ;;
objYup)
    # both cases written without running OpenFOAM (--no-run): what the solver and foam2grid get
    # from the OBJ must be what they get from the STL, file for file
    "$BIN/foamMakeGeometry" lbuilding lbuilding_z.stl || fail "foamMakeGeometry"
    "$BIN/foamMakeGeometry" lbuilding lbuilding.obj || fail "foamMakeGeometry"
    rm -rf lbuilding_stl_case lbuilding_obj_case
    "$BIN/foamWindCase" lbuilding_z.stl lbuilding_stl_case --direction 30 -np 2 --no-run \
        > lbuilding_stl_case.out 2>&1 || { cat lbuilding_stl_case.out; fail "foamWindCase STL"; }
    "$BIN/foamWindCase" lbuilding.obj lbuilding_obj_case --up y --direction 30 -np 2 --no-run \
        > lbuilding_obj_case.out 2>&1 || { cat lbuilding_obj_case.out; fail "foamWindCase OBJ"; }
    [ -s lbuilding_obj_case/constant/triSurface/geometry.stl ] || fail "no geometry.stl"
    nfiles=0
    while read -r f; do
        nfiles=$((nfiles + 1))
        [ -f "lbuilding_stl_case/$f" ] || fail "$f is in the OBJ's case only"
        case $f in
        ./system/caseParameters)  # the provenance line names the file and the time
            diff <(grep -v '^// Written by' "lbuilding_obj_case/$f") \
                 <(grep -v '^// Written by' "lbuilding_stl_case/$f") > /dev/null \
                || fail "$f differs between the Y-up OBJ and the Z-up STL" ;;
        ./windCase.json) ;;  # below
        *) cmp -s "lbuilding_obj_case/$f" "lbuilding_stl_case/$f" \
               || fail "$f differs between the Y-up OBJ and the Z-up STL" ;;
        esac
    done < <(cd lbuilding_obj_case && find . -type f | sort)
    [ "$nfiles" -ge 15 ] || fail "only $nfiles files in the OBJ's case"
    [ "$(cd lbuilding_stl_case && find . -type f | wc -l)" -eq "$nfiles" ] \
        || fail "the STL's case has other files than the OBJ's"
    # the domain, wind and geometry bounds are the same; the source file and its up axis differ
    /usr/bin/python3 - lbuilding_obj_case/windCase.json lbuilding_stl_case/windCase.json <<'PY' \
        || fail "windCase.json differs beyond the geometry file"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a['up'] == 'y' and b['up'] == 'z', (a['up'], b['up'])
for d in (a, b):
    for key in ('geometry', 'up', 'timings'):
        d.pop(key, None)
assert a == b, sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k))
PY
    note "the Y-up OBJ's case is the Z-up STL's, $nfiles files"
    ;;
sphere)
    "$BIN/foamMakeGeometry" sphere sphere.stl || fail "foamMakeGeometry"
    runCase sphere.stl sphere --ground 0 -np 2
    $CHECK inside sphere || fail "grid check"
    $CHECK loglaw sphere || fail "log-law check"
    ;;
cube)
    "$BIN/foamMakeGeometry" cube cube.stl || fail "foamMakeGeometry"
    runCase cube.stl cube -np 2
    $CHECK recirculation cube 1.2 3.0 || fail "recirculation check"
    ;;
*)
    fail "unknown test '$TEST'"
    ;;
esac
note "passed"
