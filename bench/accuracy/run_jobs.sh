#!/bin/bash
# The accuracy study's processes side by side (called by run_study.sh): every scene's stochastic
# sweep, its other sweeps, and the grid sweep, each in its own process (one thread: the cost is
# the process's CPU time); logs in WORK/log.<job>, one line per finished job in WORK/jobs.txt.
# usage: run_jobs.sh BUILD SRC WORK STOCH_SCHEMES GRID_NAME GRID_SCENE GRID_LIST
# rk4's stochastic sweep costs as much again as euler's and splitting's together (4 force
# evaluations per step at the finest steps): run_study.sh passes ACCURACY_STOCH_INTEGRATORS.
set -uo pipefail
build=$1 src=$2 work=$3 stoch_schemes=$4 name=$5 scene=$6 list=$7
jobs_=()
for s in uniform_box leaves_wind debris_tank; do jobs_+=("$s.det" "$s.stoch"); done
jobs_+=(grid)
pids=()
for j in "${jobs_[@]}"; do
  case $j in
    grid) args=(--scenes none --grids "$name:$scene:$list") ;;
    *.det) args=(--scenes "${j%.det}" --sweeps det,effects) ;;
    *.stoch) args=(--scenes "${j%.stoch}" --sweeps stoch --integrators "$stoch_schemes") ;;
  esac
  "$build/bin/accuracy_study" --source-dir "$src" --out "$work/$j" "${args[@]}" \
    > "$work/log.$j" 2>&1 &
  pids+=($!)
done
: > "$work/jobs.txt"
for k in "${!jobs_[@]}"; do
  if wait "${pids[$k]}"; then
    took=$(sed -n 's/.* in \([0-9.]*\) s$/\1/p' "$work/log.${jobs_[$k]}" | tail -1)
    echo "run_study: ${jobs_[$k]} ${took%.*} s"
    echo "${jobs_[$k]} ${took%.*} s" >> "$work/jobs.txt"
  else
    # a scene whose field is missing is skipped (its log says why); the others still report
    echo "run_study: ${jobs_[$k]} failed, see $work/log.${jobs_[$k]}" >&2
    rm -f "$work/${jobs_[$k]}/accuracy.csv"
  fi
done
exit 0
