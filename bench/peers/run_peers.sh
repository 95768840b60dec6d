#!/bin/bash
# Peers side by side: OpenFOAM's parcel tracking and MuJoCo's fluid model, on this
# machine, in this run. Writes OUTDIR/peers.json (read by the performance docs generator):
#   {"openfoam": {"dispersion_off": parcel-steps/s, "dispersion_on": ...},
#    "mujoco": {"rk4": body-steps/s, "euler": ...}, "n", "dt", "machine", "date", "load", ...}
# All rates are per core (one process, one thread), steady state.
#
#   bench/peers/run_peers.sh OUTDIR [--n N] [--dt DT] [--steps S] [--wind-case DIR]
#                            [--build DIR] [--skip-openfoam] [--skip-mujoco]
#
# OpenFOAM: icoUncoupledKinematicParcelFoam (v1912; the incompressible variant of
# uncoupledKinematicParcelFoam, as in validation/openfoam_parcels) tracks N glass spheres
# (500 um) released at rest in the wind scene's spawn box through the converged steady
# windCourtyard field (simpleFoam, k-epsilon): sphereDrag + gravity, dispersion none and
# stochasticDispersionRAS, no cloud functions, nothing written until the end. The rate comes from
# the solver's per-step ExecutionTime (CPU seconds) between step 5 and the last step, summed over
# the parcels in flight at each step, so start-up, injection and the final write are excluded.
# The field: --wind-case DIR (a solved case, copied; never written to), else
# foam_cases/windCourtyard is copied and solved with its Allrun (about 2 min CPU).
#
# MuJoCo: bench/peers/mujoco_harness (built when libmujoco-dev is installed) steps N free
# ellipsoids (the scene's seed pod, 400 kg/m^3) in air with fluidshape="ellipsoid", contacts off,
# RK4 and Euler; "rk4"/"euler" are the best case (one body per model); the one-model figures
# are kept under mujoco.one_model. mujoco_leaf: the same for the leaves scene's leaf (a box
# 6 x 4 x 0.04 cm, 600 kg/m^3, MuJoCo's ellipsoid fluid model of it).
#
# Run it niced on a shared machine: nice -n 19 bench/peers/run_peers.sh OUT
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT=${1:?usage: run_peers.sh OUTDIR [--n N] [--dt DT] [--steps S] [--wind-case DIR]}
shift
N=10000
DT=0.002
STEPS=100
WIND=""
BUILD="$ROOT/build"
DO_FOAM=1
DO_MUJOCO=1
while [ $# -gt 0 ]; do
  case "$1" in
    --n) N=$2; shift 2 ;;
    --dt) DT=$2; shift 2 ;;
    --steps) STEPS=$2; shift 2 ;;
    --wind-case) WIND=$2; shift 2 ;;
    --build) BUILD=$2; shift 2 ;;
    --skip-openfoam) DO_FOAM=0; shift ;;
    --skip-mujoco) DO_MUJOCO=0; shift ;;
    *) echo "run_peers.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
LOAD_START=$(cut -d' ' -f1-3 /proc/loadavg)

# OpenFOAM's environment without its etc/bashrc (foam_cases/RunFunctions)
. "$ROOT/foam_cases/RunFunctions"

latest_time() {  # the largest numeric time directory of a case
  (cd "$1" && ls -d [0-9]* 2>/dev/null | grep -E '^[0-9.eE+-]+$' | sort -g | tail -1)
}

solved_wind_case() {
  if [ -n "$WIND" ]; then
    [ -d "$WIND/constant/polyMesh" ] || { echo "run_peers.sh: $WIND: no constant/polyMesh" >&2; exit 1; }
    echo "$WIND"
    return
  fi
  local c="$OUT/windCourtyard"
  if [ ! -f "$c/log.simpleFoam" ]; then
    rm -rf "$c"
    cp -r "$ROOT/foam_cases/windCourtyard" "$c"
    FOAM_CASES_DIR="$ROOT/foam_cases" "$c/Allrun" >&2
  fi
  echo "$c"
}

# parcel case: N parcels from the wind scene's spawn box, dispersion model $2
parcel_case() {
  local base=$1 disp=$2 case=$3 lt
  rm -rf "$case"
  mkdir -p "$case/constant" "$case/system" "$case/0"
  cp -r "$base/constant/polyMesh" "$case/constant/"
  cp "$base/constant/turbulenceProperties" "$case/constant/"
  lt=$(latest_time "$base")
  for f in U k epsilon nut p; do cp "$base/$lt/$f" "$case/0/"; done
  local end
  end=$(awk -v d="$DT" -v s="$STEPS" 'BEGIN { printf "%.10g", d * s }')
  cat > "$case/system/controlDict" <<EOF
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application     icoUncoupledKinematicParcelFoam;
libs            ("libatmosphericModels.so");
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         $end;
deltaT          $DT;
writeControl    timeStep;
writeInterval   1000000;
purgeWrite      0;
writeFormat     binary;
writePrecision  10;
timeFormat      general;
timePrecision   8;
runTimeModifiable false;
EOF
  # transient schemes for the parcel solver (the validation study's, no placeholders in them)
  cp "$ROOT/validation/openfoam_parcels/case_template/system/fvSchemes" \
     "$ROOT/validation/openfoam_parcels/case_template/system/fvSolution" "$case/system/"
  cat > "$case/constant/transportProperties" <<EOF
FoamFile { version 2.0; format ascii; class dictionary; object transportProperties; }
transportModel  Newtonian;
rhoInf          1.204;
nu              1.5e-05;
EOF
  cat > "$case/constant/g" <<EOF
FoamFile { version 2.0; format ascii; class uniformDimensionedVectorField; object g; }
dimensions      [0 1 -2 0 0 0 0];
value           (0 0 -9.81);
EOF
  cat > "$case/constant/kinematicCloudProperties" <<EOF
FoamFile { version 2.0; format ascii; class dictionary; object kinematicCloudProperties; }
solution
{
    active true; coupled false; transient yes; cellValueSourceCorrection off; maxCo 0.3;
    sourceTerms { schemes { } }
    interpolationSchemes { rho cell; U cellPoint; mu cell; }
    integrationSchemes { U analytical; }
}
constantProperties { rho0 2500; youngsModulus 1e9; poissonsRatio 0.35; }
subModels
{
    particleForces { sphereDrag; gravity; }
    injectionModels
    {
        model1
        {
            type manualInjection; massTotal 0; parcelBasisType fixed; nParticle 1; SOI 0;
            positionsFile "kinematicCloudPositions"; U0 (0 0 0);
            sizeDistribution { type fixedValue; fixedValueDistribution { value 5e-4; } }
        }
    }
    dispersionModel $disp;
    patchInteractionModel standardWallInteraction;
    standardWallInteractionCoeffs { type stick; }
    surfaceFilmModel none;
    stochasticCollisionModel none;
    collisionModel none;
}
cloudFunctions { }
EOF
  # the wind scene's spawn box [-12,-8,14]..[-4,8,20] m (scenes/leaves_wind.json)
  awk -v n="$N" 'BEGIN {
      srand(2026);
      print "FoamFile { version 2.0; format ascii; class vectorField; object kinematicCloudPositions; }";
      print "(";
      for (i = 0; i < n; i++)
        printf "(%.6f %.6f %.6f)\n", -12 + 8 * rand(), -8 + 16 * rand(), 14 + 6 * rand();
      print ")" }' > "$case/constant/kinematicCloudPositions"
  /usr/bin/icoUncoupledKinematicParcelFoam -case "$case" > "$case/log.icoUncoupledKinematicParcelFoam" 2>&1 \
    || { echo "run_peers.sh: the parcel solver failed, see $case/log.icoUncoupledKinematicParcelFoam" >&2; exit 1; }
}

# parcel-steps per CPU second from a solver log: from the 5th step to the last, the parcels in
# flight at the start of each step over the ExecutionTime it took
foam_rate() {
  awk '
    /^Time = / { step++ }
    /Current number of parcels/ { np[step] = $NF }
    /^ExecutionTime = / { et[step] = $3 }
    END {
      a = 5; b = step;
      if (b <= a + 1) { print "too few steps" > "/dev/stderr"; exit 1 }
      s = 0; for (i = a + 1; i <= b; i++) s += np[i - 1];
      dtc = et[b] - et[a];
      if (dtc <= 0 || s <= 0) { print "no timing" > "/dev/stderr"; exit 1 }
      printf "%.6g %d %.4g\n", s / dtc, s, dtc
    }' "$1"
}

FOAM_OFF=null
FOAM_ON=null
FOAM_NOTE=""
if [ "$DO_FOAM" = 1 ]; then
  BASE=$(solved_wind_case)
  CELLS=$(sed -n 's/^ *cells: *//p' "$BASE/log.checkMesh" 2>/dev/null | head -1)
  parcel_case "$BASE" none "$OUT/parcels_off"
  read -r FOAM_OFF S_OFF T_OFF < <(foam_rate "$OUT/parcels_off/log.icoUncoupledKinematicParcelFoam")
  parcel_case "$BASE" stochasticDispersionRAS "$OUT/parcels_on"
  read -r FOAM_ON S_ON T_ON < <(foam_rate "$OUT/parcels_on/log.icoUncoupledKinematicParcelFoam")
  FOAM_NOTE="\"openfoam_detail\": {\"solver\": \"icoUncoupledKinematicParcelFoam (OpenFOAM v1912)\", \"field\": \"$BASE\", \"cells\": ${CELLS:-null}, \"parcel_steps_off\": $S_OFF, \"cpu_s_off\": $T_OFF, \"parcel_steps_on\": $S_ON, \"cpu_s_on\": $T_ON},"
fi

MJ_RK4=null
MJ_EULER=null
MJ_NOTE=""
if [ "$DO_MUJOCO" = 1 ]; then
  H="$BUILD/bin/mujoco_harness"
  [ -x "$H" ] || { echo "run_peers.sh: $H missing (install libmujoco-dev, build mujoco_harness)" >&2; exit 1; }
  MJ=$("$H" --n "$N" --dt "$DT" --steps "$STEPS")
  read -r MJ_RK4 MJ_EULER < <(echo "$MJ" | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)["one_body_per_model"]
print(d["rk4"], d["euler"])')
  MJ_NOTE="\"mujoco_detail\": $MJ,"
  # the leaves scene's falling plate (lrigid's rk4 against MuJoCo's RK4 on the same plates)
  MJL=$("$H" --n "$N" --dt "$DT" --steps "$STEPS" --body leaf)
  read -r MJL_RK4 MJL_EULER < <(echo "$MJL" | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)["one_body_per_model"]
print(d["rk4"], d["euler"])')
  MJ_NOTE="$MJ_NOTE \"mujoco_leaf\": {\"rk4\": $MJL_RK4, \"euler\": $MJL_EULER},"
  MJ_NOTE="$MJ_NOTE \"mujoco_leaf_detail\": $MJL,"
fi

LOAD_END=$(cut -d' ' -f1-3 /proc/loadavg)
MACHINE="$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1), $(nproc) cores"
cat > "$OUT/peers.json.tmp" <<EOF
{
  "openfoam": {"dispersion_off": $FOAM_OFF, "dispersion_on": $FOAM_ON},
  "mujoco": {"rk4": $MJ_RK4, "euler": $MJ_EULER},
  $FOAM_NOTE
  $MJ_NOTE
  "n": $N,
  "dt": $DT,
  "steps": $STEPS,
  "rates": "per core, CPU time of one process, steady state",
  "nice": $(nice),
  "machine": "$MACHINE",
  "date": "$(date -u +%Y-%m-%dT%H:%M:%SZ)",
  "load": "$LOAD_START (start) / $LOAD_END (end)"
}
EOF
mv "$OUT/peers.json.tmp" "$OUT/peers.json"
cat "$OUT/peers.json"
