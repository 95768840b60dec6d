#!/bin/bash
# Checkpoints and --resume (docs/cli.md): a run killed with SIGKILL at random points
# several times and resumed each time writes results identical byte for byte to an
# uninterrupted run (summary.json: all but its timing fields), with threads and with 2 MPI
# ranks; a disk that fills up mid-run (a file-size limit) gives exit 4, leaves the last
# checkpoint intact, and the run resumes once space is back; resuming a finished run, another
# scene or another number of ranks is refused saying so.
# usage: resume_test.sh SOURCE_DIR LRIGID
set -euo pipefail
src=$1 lrigid=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
echo "resume_test: RANDOM seeded with ${RESUME_TEST_SEED:=$$}"
RANDOM=$RESUME_TEST_SEED

# water: near-neutral spheres with the Basset history and the seen turbulence, and plates;
# some land on the ground (landings.csv)
cat > scene.json <<'JSON'
{
  "fluid": { "density": 1000, "kinematic_viscosity": 1e-6,
             "uniform": { "U": [0.05, 0, 0], "k": 1e-4, "epsilon": 1e-5 } },
  "gravity": [0, 0, -9.81],
  "effects": ["gravity", "buoyancy", "added_mass", "drag", "mean_flow", "turbulence", "basset"],
  "integrator": { "scheme": "splitting", "dt": 0.002 },
  "duration": 1.6,
  "seed": 5,
  "ground": { "z": 0.99 },
  "bodies": [
    { "name": "bead", "shape": { "type": "sphere", "radius": 0.002 }, "density": 1100,
      "count": 151, "spawn_box": [[0, 0, 1], [0.1, 0.1, 1.1]] },
    { "name": "chip", "shape": { "type": "box", "size": [0.01, 0.006, 0.001] },
      "density": 1300, "count": 100, "spawn_box": [[0, 0, 1], [0.1, 0.1, 1.1]],
      "orientation": "random" }
  ],
  "output": { "dir": "out", "every": 0.08, "formats": ["csv", "pvd", "glb"],
              "checkpoint_every": 0 }
}
JSON

compare() {  # compare A B: every file identical, summary.json but for its timing fields
  local a=$1 b=$2 f
  [ "$(cd "$a" && find . -type f | sort)" = "$(cd "$b" && find . -type f | sort)" ] || {
    echo "FAIL: different file lists in $a and $b"; diff <(cd "$a" && find . | sort) \
      <(cd "$b" && find . | sort) || true; return 1; }
  for f in $(cd "$a" && find . -type f ! -name summary.json | sort); do
    cmp -s "$a/$f" "$b/$f" || { echo "FAIL: $f differs between $a and $b"; return 1; }
  done
  /usr/bin/python3 - "$a/summary.json" "$b/summary.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
skip = {"ranks", "threads", "wall_seconds", "body_steps_per_second"}
diff = sorted(k for k in set(a) | set(b) if k not in skip and a.get(k) != b.get(k))
if diff:
    sys.exit("FAIL: summary.json differs in %s" % ", ".join(diff))
PY
}

expect_fail() {  # expect_fail CODE TEXT command...: exits CODE and says TEXT
  local code=$1 text=$2 rc=0
  shift 2
  "$@" 2> err.txt || rc=$?
  [ "$rc" = "$code" ] || { echo "FAIL: $* exited $rc, not $code"; cat err.txt; exit 1; }
  grep -qF -- "$text" err.txt || { echo "FAIL: $* does not say '$text':"; cat err.txt; exit 1; }
}

"$lrigid" run scene.json -o ref --threads 2 --quiet
[ -s ref/landings.csv ] && [ "$(wc -l < ref/landings.csv)" -gt 1 ] || {
  echo "FAIL: nothing landed: the scene does not exercise landings"; exit 1; }
[ -d ref/checkpoint ] && { echo "FAIL: checkpoint_every 0 wrote checkpoints"; exit 1; }

# the process PID and all its descendants (mpirun's ranks may have their own process group)
family() {
  local p
  echo "$1"
  for p in $(ps -o pid= --ppid "$1"); do family "$p"; done
}

# step of the last checkpoint in DIR (-1: none)
last_step() {
  if [ -f "$1/checkpoint/latest.json" ]; then
    sed -n 's/.*"step": *\([0-9]*\).*/\1/p' "$1/checkpoint/latest.json"
  else
    echo -1
  fi
}

# kill_and_resume DIR KILLS launcher...: starts the run, kills it with SIGKILL at a random
# point (once a checkpoint past a random output step exists, then after 0-0.3 s more),
# resumes; KILLS times, then lets it finish. 800 steps, an output every 40; a kill lands before
# step 640 or so, so that the run is still going.
kill_and_resume() {
  local dir=$1 kills=$2 resumed=0 k rc pid
  killed=0
  shift 2
  for ((k = 0; ; ++k)); do
    local args=(run scene.json -o "$dir" --threads 2 --quiet --checkpoint-every 1e-9)
    [ -f "$dir/checkpoint/latest.json" ] && args+=(--resume "$dir") && resumed=$((resumed + 1))
    if [ "$k" -ge "$kills" ]; then
      "$@" "$lrigid" "${args[@]}"
      break
    fi
    setsid "$@" "$lrigid" "${args[@]}" & pid=$!
    local target=$(( 40 * (1 + RANDOM % 15) ))
    while kill -0 "$pid" 2> /dev/null && [ "$(last_step "$dir")" -lt "$target" ]; do
      sleep 0.02
    done
    sleep "0.0$(( RANDOM % 10 ))"
    # the whole family at once, children first seen, so that no rank goes on alone
    kill -9 $(family "$pid") 2>/dev/null || true
    rc=0; wait "$pid" || rc=$?
    # (mpirun may be killed after its ranks finished: then summary.json is there)
    if [ "$rc" = 0 ] || [ -e "$dir/summary.json" ]; then
      echo "resume_test: $dir finished before the kill"
      [ "$killed" -gt 0 ] && break
      rm -rf "$dir"; k=-1; continue  # never killed: start again
    fi
    killed=$((killed + 1))
    echo "resume_test: $dir killed after step $target; last checkpoint at step $(last_step "$dir")"
  done
  [ "$resumed" -ge 1 ] || { echo "FAIL: $dir was never resumed (kill earlier?)"; exit 1; }
  [ ! -e "$dir/checkpoint" ] || { echo "FAIL: $dir/checkpoint left after the finish"; exit 1; }
}

kill_and_resume threads 3 env
compare ref threads
echo "resume_test: killed $killed times with 2 threads, resumed: identical"

if command -v mpirun > /dev/null; then
  kill_and_resume ranks2 3 mpirun -np 2
  compare ref ranks2
  echo "resume_test: killed $killed times with 2 MPI ranks, resumed: identical"
else
  echo "FAIL: mpirun not found (scripts/install-deps installs it)"; exit 1
fi

# refusals, each saying why
expect_fail 3 "has finished" "$lrigid" run scene.json --resume ref
expect_fail 3 "no checkpoint" "$lrigid" run scene.json --resume nowhere
setsid "$lrigid" run scene.json -o half --threads 1 --quiet --checkpoint-every 1e-9 & pid=$!
for _ in $(seq 100); do [ -f half/checkpoint/latest.json ] && break; sleep 0.05; done
kill -9 -- "-$pid"; wait "$pid" || true
[ -f half/checkpoint/latest.json ] || { echo "FAIL: no checkpoint in half"; exit 1; }
expect_fail 3 "another scene" "$lrigid" run scene.json --resume half --seed 6
sed 's/"count": 100/"count": 99/' scene.json > other.json
expect_fail 3 "another scene" "$lrigid" run other.json --resume half
expect_fail 3 "started with 1 MPI rank(s): resume it with one process" mpirun -np 2 "$lrigid" run scene.json --resume half
expect_fail 4 "--resume half" "$lrigid" run scene.json -o half --checkpoint-every 1e-9
# another build: the same binary with another build-id (the linker's hash of what it linked,
# which is what identifies a build; a file without one is identified by its bytes)
cp "$lrigid" ./lrigid_other_build
id=$(readelf -n ./lrigid_other_build | sed -n 's/.*Build ID: //p')
if [ -n "$id" ]; then
  /usr/bin/python3 - "$id" <<'PY'
import sys
old = bytes.fromhex(sys.argv[1])
data = open("lrigid_other_build", "rb").read()
assert data.count(old) == 1, "the build-id should occur once"
open("lrigid_other_build", "wb").write(data.replace(old, bytes([old[0] ^ 1]) + old[1:]))
PY
else
  printf 'x' >> ./lrigid_other_build
fi
expect_fail 3 "another build" ./lrigid_other_build run scene.json --resume half
"$lrigid" run scene.json --resume half --quiet
compare ref half

# a disk that fills up: the trajectories cannot grow past half their size (ulimit -f, KiB).
# Without "pvd": every .vtp frame is one write of a fixed size (larger than half the
# trajectories here), so with it no file size would fail in the middle of the run.
sed 's/"formats": \["csv", "pvd", "glb"\]/"formats": ["csv", "glb"]/' scene.json > nopvd.json
grep -q '"formats": \["csv", "glb"\]' nopvd.json || { echo "FAIL: nopvd.json kept pvd"; exit 1; }
# disk_full_then_resume SCENE NAME THREADS: the uninterrupted run into ref_NAME; the run into
# full_NAME with its trajectories limited to half their size stops with exit 4 saying "disk
# full", leaves no summary.json and a checkpoint; resumed on THREADS threads it is ref_NAME
disk_full_then_resume() {
  local scene=$1 name=$2 threads=$3 limit rc=0
  "$lrigid" run "$scene" -o "ref_$name" --threads 2 --quiet
  limit=$(( $(stat -c %s "ref_$name/trajectories.csv") / 2048 ))
  ( ulimit -f "$limit"; exec "$lrigid" run "$scene" -o "full_$name" --threads 2 --quiet \
      --checkpoint-every 1e-9 2> err.txt ) || rc=$?
  [ "$rc" = 4 ] || { echo "FAIL: $name: a full disk gave exit $rc, not 4"; cat err.txt; exit 1; }
  grep -q "disk full" err.txt || { echo "FAIL: $name: the message does not say so"; cat err.txt; exit 1; }
  [ ! -e "full_$name/summary.json" ] || { echo "FAIL: $name: a failed run left summary.json"; exit 1; }
  step=$(last_step "full_$name")
  [ "$step" -gt 0 ] || { echo "FAIL: $name: no checkpoint before the disk filled up"; exit 1; }
  echo "resume_test: $name: disk full at $limit KiB, last checkpoint at $step"
  "$lrigid" run "$scene" --resume "full_$name" --quiet --threads "$threads"
  compare "ref_$name" "full_$name"
}
disk_full_then_resume nopvd.json nopvd 2
echo "resume_test: resumed after the disk filled up: identical"
# bodies colliding with each other, resumed on another thread count
cp "$src/tests/integration/body_contact_pile.json" pile.json
disk_full_then_resume pile.json pile 1
echo "resume_test: bodies colliding, cut at step $step and resumed on 1 thread: identical"
echo "resume_test: PASS"
