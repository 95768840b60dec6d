#!/bin/bash
# Integration tests of the OpenFOAM cases in foam_cases/ (ctest label foam).
#   foam_case_test.sh SOURCE_DIR WORK_DIR TEST
# SOURCE_DIR is the project root, WORK_DIR a scratch directory in the build tree (the cases are
# copied there; nothing runs inside the source tree). TEST is one of
#   tiny             Allrun of foam_cases/tiny succeeds; the written fields and the solver log
#                    are then checked independently of Allrun's own checks (OpenFOAM's
#                    fieldMinMax function object, grep for nan/inf, residuals from the log)
#   tinyParallel     Allrun -np 2 of tiny matches the serial run to solver tolerance
#   tinyTransient    Allrun of foam_cases/tinyTransient succeeds; all 5 times 0.2..1 s written,
#                    each checked independently as above, and the run reached endTime
#   brokenNegativeK  a copy of tiny with k = -0.015 (inlet and initial): Allrun must fail,
#                    naming the file 0/k, the value and the rule
#   brokenMissingField  a copy of tiny without 0.orig/epsilon: Allrun must fail naming it
#   brokenNotConverged  a copy of tiny stopped after 20 iterations: Allrun must fail, 'not
#                    converged'
#   brokenTooFewWrites  a copy of tinyTransient writing every 0.5 s: Allrun must fail, 'only'
# Exits 0 on success, 1 with a message on the first failed assertion.
set -u
SRC=$1
WORK=$2
TEST=$3

export WM_PROJECT_DIR=/usr/share/openfoam
export PATH=/usr/bin:/bin:$PATH
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# the copied cases find RunFunctions here (the tests do not rely on where the build tree is)
export FOAM_CASES_DIR=$SRC/foam_cases
BIN=$SRC/foam_cases/bin

fail() { echo "FAIL [$TEST]: $*" 1>&2; exit 1; }
note() { echo "[$TEST] $*"; }

# fresh copy of foam_cases/<case> as $WORK/$TEST/<dest>
copyCase() {
    local case=$1 dest=${2:-$1}
    rm -rf "${WORK:?}/$TEST/$dest"
    mkdir -p "$WORK/$TEST" || fail "cannot create $WORK/$TEST"
    cp -r "$SRC/foam_cases/$case" "$WORK/$TEST/$dest" || fail "cannot copy foam_cases/$case"
    [ ! -d "$WORK/$TEST/$dest/0" ] || fail "foam_cases/$case contains a 0/ directory: run its Allclean"
    echo "$WORK/$TEST/$dest"
}

# run Allrun in a case, output to allrun.out; returns Allrun's exit status
runAllrun() {
    local dir=$1; shift
    ( cd "$dir" && ./Allrun "$@" ) > "$dir/allrun.out" 2>&1
}

# time directories > 0 of a case, sorted
timesOf() { ( cd "$1" && foamListTimes -noZero 2>/dev/null | grep -E '^[0-9.e+-]+$' ); }

# independent field checks at time $2: every field present, no nan/inf in the file text,
# and min(k), min(epsilon) > 0 from OpenFOAM's fieldMinMax (internal and boundary values)
checkFieldsAt() {
    local dir=$1 t=$2 f file
    for f in U p k epsilon nut; do
        file=$dir/$t/$f
        [ -f "$file" ] || [ -f "$file.gz" ] || fail "$dir/$t: field $f not written"
        if zcat -f "$file"* | grep -q -i -E '(^|[ (])[-+]?(nan|inf)'; then
            fail "$file contains nan or inf"
        fi
    done
    ( cd "$dir" && postProcess -time "$t" -func 'fieldMinMax(k,epsilon)' ) \
        > "$dir/log.fieldMinMax.$t" 2>&1 || fail "postProcess fieldMinMax failed at $t, see $dir/log.fieldMinMax.$t"
    for f in k epsilon; do
        local v
        v=$(sed -n "s/^ *min($f) = \([^ ]*\) .*/\1/p" "$dir/log.fieldMinMax.$t" | tail -n 1)
        [ -n "$v" ] || fail "no min($f) in $dir/log.fieldMinMax.$t"
        awk -v v="$v" 'BEGIN { exit !(v > 0) }' || fail "min($f) = $v at time $t, must be > 0"
        note "time $t: min($f) = $v > 0"
    done
}

# independent residual check: the last initial residual of each field in the log <= threshold
checkResiduals() {
    local log=$1; shift
    grep -q '^SIMPLE solution converged in' "$log" || fail "$log: no 'SIMPLE solution converged'"
    grep -q '^End' "$log" || fail "$log: no final End"
    local pair name thr last
    for pair in "$@"; do
        name=${pair%%=*}; thr=${pair#*=}
        last=$(grep "Solving for $name," "$log" | tail -n 1 | sed 's/.*Initial residual = \([^,]*\),.*/\1/')
        [ -n "$last" ] || fail "$log: no residual for $name"
        awk -v r="$last" -v t="$thr" 'BEGIN { exit !(r <= t) }' \
            || fail "$log: last initial residual of $name = $last > $thr"
        note "last initial residual $name = $last <= $thr"
    done
}

# Allrun must fail, and its output must match the pattern $2
expectFailure() {
    local dir=$1 pattern=$2
    if runAllrun "$dir"; then
        fail "Allrun of the broken case $dir succeeded"
    fi
    grep -q -E "$pattern" "$dir/allrun.out" \
        || { cat "$dir/allrun.out"; fail "Allrun failed but its output lacks '$pattern'"; }
    note "Allrun failed as expected: $(grep -E "$pattern" "$dir/allrun.out" | head -n 1)"
}

case "$TEST" in
tiny)
    d=$(copyCase tiny) || exit 1
    runAllrun "$d" || { cat "$d/allrun.out"; fail "Allrun of tiny failed"; }
    t=$(timesOf "$d" | tail -n 1)
    [ -n "$t" ] || fail "tiny wrote no time directory"
    # as residualControl in tiny/system/fvSolution
    checkResiduals "$d/log.simpleFoam" Ux=1e-5 Uy=1e-5 Uz=1e-5 p=1e-4 k=1e-5 epsilon=1e-5
    checkFieldsAt "$d" "$t"
    # the wake: k must vary strongly (max/min > 5)
    kmin=$(sed -n 's/^ *min(k) = \([^ ]*\) .*/\1/p' "$d/log.fieldMinMax.$t")
    kmax=$(sed -n 's/^ *max(k) = \([^ ]*\) .*/\1/p' "$d/log.fieldMinMax.$t")
    awk -v a="$kmin" -v b="$kmax" 'BEGIN { exit !(b > 5 * a) }' \
        || fail "k varies too little: min $kmin, max $kmax"
    note "k from $kmin to $kmax"
    grep -q 'y+' "$d/allrun.out" || fail "Allrun did not report y+"
    ;;
tinyParallel)
    s=$(copyCase tiny serial) || exit 1
    p=$(copyCase tiny parallel) || exit 1
    runAllrun "$s" || { cat "$s/allrun.out"; fail "serial Allrun failed"; }
    runAllrun "$p" -np 2 || { cat "$p/allrun.out"; fail "Allrun -np 2 failed"; }
    [ -d "$p/processor1" ] || fail "Allrun -np 2 did not decompose"
    grep -q 'Running simpleFoam (2 processes)' "$p/allrun.out" || fail "Allrun -np 2 did not run in parallel"
    # converged to initial residuals <= 1e-5: the two runs agree to 1e-4 of each field's scale
    /usr/bin/python3 "$BIN/foamCompareFields" "$s" "$p" -tol 1e-4 \
        || fail "serial and parallel results differ"
    ;;
tinyTransient)
    d=$(copyCase tinyTransient) || exit 1
    runAllrun "$d" || { cat "$d/allrun.out"; fail "Allrun of tinyTransient failed"; }
    times=$(timesOf "$d" | tr '\n' ' ')
    [ "$times" = "0.2 0.4 0.6 0.8 1 " ] || fail "written times are '$times', expected 0.2 0.4 0.6 0.8 1"
    grep -q '^End' "$d/log.pimpleFoam" || fail "log.pimpleFoam has no final End"
    last=$(grep '^Time = ' "$d/log.pimpleFoam" | tail -n 1)
    [ "$last" = "Time = 1" ] || fail "last step is '$last', expected 'Time = 1'"
    for t in $times; do checkFieldsAt "$d" "$t"; done
    ;;
brokenNegativeK)
    d=$(copyCase tiny) || exit 1
    sed -i 's/^kInlet  *0.015;/kInlet          -0.015;/' "$d/0.orig/k"
    grep -q '^kInlet  *-0.015;' "$d/0.orig/k" || fail "could not break 0.orig/k"
    expectFailure "$d" 'FAILED: .*0/k: internalField min k = -0.015, must be > 0'
    ;;
brokenMissingField)
    d=$(copyCase tiny) || exit 1
    rm "$d/0.orig/epsilon"
    expectFailure "$d" '0/epsilon: field epsilon missing'
    ;;
brokenNotConverged)
    d=$(copyCase tiny) || exit 1
    sed -i 's/^endTime  *1000;/endTime         20;/; s/^writeInterval  *1000;/writeInterval   20;/' \
        "$d/system/controlDict"
    expectFailure "$d" 'not converged after 20 iterations'
    ;;
brokenTooFewWrites)
    d=$(copyCase tinyTransient) || exit 1
    sed -i 's/^writeInterval  *0.2;/writeInterval   0.5;/' "$d/system/controlDict"
    expectFailure "$d" 'only 2 time directories written'
    ;;
*)
    fail "unknown test '$TEST'"
    ;;
esac
note "passed"
