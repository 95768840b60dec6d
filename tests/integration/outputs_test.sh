#!/bin/bash
# The output folder and resume (docs/outputs.md): a run replaces or removes only what
# lrigid wrote there (its manifest) and refuses, before it starts, a name taken by something
# else; a kill at any rename of the finish leaves the earlier result or a finish that the next
# lrigid completes, never a mixture; a resume checks the checkpoint and the output so far
# against their checksums, refuses with exit 3 and changes nothing when they differ, and works
# again once they are put back.
# usage: outputs_test.sh SOURCE_DIR LRIGID
set -euo pipefail
src=$1 lrigid=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; [ -f err.txt ] && cat err.txt; exit 1; }

expect_fail() {  # expect_fail CODE TEXT command...: exits CODE and says TEXT
  local code=$1 text=$2 rc=0
  shift 2
  "$@" 2> err.txt || rc=$?
  [ "$rc" = "$code" ] || fail "$* exited $rc, not $code"
  grep -qF -- "$text" err.txt || fail "$* does not say '$text'"
}
# a listing of DIR with each file's checksum: what "changes nothing" compares
snapshot() { (cd "$1" && find . -printf '%y %p\n' | sort && find . -type f -exec md5sum {} + | sort -k2); }

cat > small.json <<'JSON'
{
  "fluid": { "density": 1.2, "kinematic_viscosity": 1.5e-5,
             "uniform": { "U": [1, 0, 0], "k": 0.1, "epsilon": 0.05 } },
  "gravity": [0, 0, -9.81],
  "effects": "auto",
  "integrator": { "scheme": "splitting", "dt": 0.001 },
  "duration": 0.1, "seed": 1,
  "ground": { "z": 0.9 },
  "bodies": [ { "name": "bead", "shape": { "type": "sphere", "radius": 0.003 }, "density": 30,
                "count": 5, "spawn_box": [[0, 0, 1], [0.1, 0.1, 1.1]] } ],
  "output": { "dir": "out", "every": 0.01, "formats": ["csv", "pvd", "glb"],
              "checkpoint_every": 0 }
}
JSON

# ---- 1. the output folder is the user's ----
# a folder of the user's where the run writes its frames: refused before the run, even with
# --force, and nothing of it touched (mine.obj is still there)
mkdir -p out/shapes; echo x > out/shapes/mine.obj
expect_fail 4 "out/shapes" "$lrigid" run small.json -o out --quiet
expect_fail 4 "out/shapes" "$lrigid" run small.json -o out --quiet --force
[ "$(cat out/shapes/mine.obj)" = x ] || fail "out/shapes/mine.obj was changed or removed"
[ ! -e out/summary.json ] || fail "a refused run wrote summary.json"
# a file of the user's at a result's name: refused, then replaced with --force
rm -rf out; mkdir out; echo mine > out/trajectories.csv; echo notes > out/notes.txt
expect_fail 4 "out/trajectories.csv" "$lrigid" run small.json -o out --quiet
[ "$(cat out/trajectories.csv)" = mine ] || fail "the refused run changed trajectories.csv"
"$lrigid" run small.json -o out --quiet --force 2> err.txt || fail "--force did not replace it"
head -1 out/trajectories.csv | grep -q '^body,type,t' || fail "--force did not write the results"
[ "$(cat out/notes.txt)" = notes ] || fail "notes.txt, not lrigid's, was changed"
[ -f out/lrigid-manifest.json ] || fail "no manifest"
# a second run into lrigid's own results: no --force needed; an earlier result it does not
# write again (animation.glb) goes, the user's files stay
sed 's/"formats": \["csv", "pvd", "glb"\]/"formats": ["csv", "pvd"]/; s/"seed": 1/"seed": 2/' \
  small.json > noglb.json
"$lrigid" run noglb.json -o out --quiet 2> err.txt || fail "a rerun into lrigid's own results"
[ ! -e out/animation.glb ] || fail "the earlier run's animation.glb was left with another run's results"
[ "$(cat out/notes.txt)" = notes ] || fail "notes.txt changed"
# a file of the user's put into lrigid's frames folder: refused, kept
echo y > out/bodies/mine.txt
expect_fail 4 "out/bodies/mine.txt" "$lrigid" run small.json -o out --quiet
[ "$(cat out/bodies/mine.txt)" = y ] || fail "out/bodies/mine.txt changed"
# a scene whose mesh lies in shapes/ with output.dir ".": refused before the run, the mesh
# intact
mkdir -p meshscene/shapes
cp "$src/tests/data/meshes/tetra.obj" meshscene/shapes/leaf.obj
sed 's|"shape": { "type": "sphere", "radius": 0.003 }|"shape": { "type": "mesh", "file": "shapes/leaf.obj", "scale": 0.01 }|; s|"dir": "out"|"dir": "."|' \
  small.json > meshscene/scene.json
grep -q leaf.obj meshscene/scene.json || fail "test bug: no mesh in the scene"
(cd meshscene && expect_fail 4 "shapes" "$lrigid" run scene.json --quiet)
cmp -s meshscene/shapes/leaf.obj "$src/tests/data/meshes/tetra.obj" || fail "the scene's mesh was changed"
echo "outputs_test: the output folder: PASS"

# ---- 2. a kill at every rename of the finish ----
"$lrigid" run small.json -o refA --quiet
sed 's/"seed": 1/"seed": 2/' small.json > seed2.json
"$lrigid" run seed2.json -o refB --quiet
same() {  # same A B: every file but summary.json identical, summary.json of the same seed
  local a=$1 b=$2 f
  # (the killed run's temporaries, the journal and the earlier results moved aside: never
  # final-looking, and a kill -9 cannot remove them; that the completion removes the journal
  # and the moved-aside results is checked on its own)
  [ "$(cd "$a" && find . \( -name '*.tmp*' -o -name '*.old[0-9]*' -o -name lrigid-finish.json \) -prune -o -print |
       sort)" = "$(cd "$b" && find . | sort)" ] ||
    return 1
  for f in $(cd "$b" && find . -type f ! -name summary.json ! -name lrigid-manifest.json); do
    cmp -s "$a/$f" "$b/$f" || return 1
  done
  [ "$(grep '"seed"' "$a/summary.json")" = "$(grep '"seed"' "$b/summary.json")" ]
}
command -v strace > /dev/null || fail "strace not found (scripts/install-deps installs it)"
cp -r refA probe
strace -f -o renames.txt -e trace=rename,renameat,renameat2 "$lrigid" run seed2.json -o probe --quiet
n=$(grep -c 'rename' renames.txt)
[ "$n" -ge 8 ] || fail "only $n renames seen in a finish"
for ((k = 1; k <= n; ++k)); do
  rm -rf kill; cp -r refA kill
  rc=0
  strace -f -o /dev/null -e trace=rename,renameat,renameat2 \
    -e inject=rename,renameat,renameat2:signal=KILL:when=$k \
    "$lrigid" run seed2.json -o kill --quiet 2> /dev/null > /dev/null || rc=$?
  # right after the kill: a complete result of either run, or none and the journal
  if [ -e kill/summary.json ]; then
    same kill refA || same kill refB || fail "kill at rename $k left a mixture with a summary.json"
  else
    [ -e kill/lrigid-finish.json ] || fail "kill at rename $k left no summary.json and no journal"
  fi
  # the next lrigid that opens the folder completes a decided finish
  "$lrigid" export-gltf kill -o probe.glb 2> err.txt || fail "export-gltf after a kill at rename $k"
  if same kill refB; then r=B; elif same kill refA; then r=A; else
    fail "after a kill at rename $k and its completion, kill/ is neither run's result"; fi
  [ ! -e kill/lrigid-finish.json ] || fail "the journal stayed after the completion"
  ls kill | grep -q '\.old' && fail "a moved-aside earlier result stayed"
  echo "outputs_test: killed at rename $k of $n (exit $rc): result $r"
done
echo "outputs_test: a kill at every rename of the finish: PASS"

# ---- 3. resume verifies ----
# an interrupted run with a checkpoint: stopped by a file-size limit (a full disk) at its
# trajectories, after some checkpoints (exit 4, the temporaries kept for --resume)
sed 's/"duration": 0.1/"duration": 0.6/; s/"count": 5/"count": 40/' small.json > long.json
"$lrigid" run long.json -o ref --quiet
# (KiB: 80 % of the trajectories, more than the largest .vtp frame)
limit=$(( $(stat -c %s ref/trajectories.csv) * 8 / 10240 ))
interrupted() {  # interrupted DIR: a run in DIR that stopped with a checkpoint
  rm -rf "$1"
  local rc=0
  ( ulimit -f "$limit"; exec "$lrigid" run long.json -o "$1" --quiet --checkpoint-every 1e-9 \
      2> err.txt ) || rc=$?
  [ "$rc" = 4 ] || fail "the file-size limit gave exit $rc"
  grep -q "resumable" err.txt || fail "the failed run does not say it is resumable"
  [ -f "$1/checkpoint/latest.json" ] || fail "no checkpoint in $1"
}
# each corruption: refused with exit 3 saying TEXT, nothing changed, twice; once the file is
# put back from GOOD, the resume works and gives the uninterrupted run's results
check_refused() {  # check_refused DIR TEXT FILE GOOD
  local dir=$1 text=$2 file=$3 good=$4 before
  before=$(snapshot "$dir")
  expect_fail 3 "$text" "$lrigid" run long.json --resume "$dir" --quiet
  [ "$(snapshot "$dir")" = "$before" ] || fail "a refused resume changed $dir"
  expect_fail 3 "$text" "$lrigid" run long.json --resume "$dir" --quiet
  [ "$(snapshot "$dir")" = "$before" ] || fail "a second refused resume changed $dir"
  cp "$good" "$file"
  "$lrigid" run long.json --resume "$dir" --quiet 2> err.txt || fail "resume after putting $file back"
  for f in trajectories.csv bodies.pvd shapes.pvd animation.glb landings.csv; do
    cmp -s "$dir/$f" "ref/$f" || fail "resumed $f differs from the uninterrupted run's"; done
  echo "outputs_test: $file: refused saying '$text', resumed once put back"
}
# the trajectories so far cut short: the resume must not exit 0 with NUL bytes in the result
interrupted r1
t=$(ls r1/trajectories.csv.tmp*); cp "$t" good; truncate -s $(( $(stat -c %s "$t") / 2 )) "$t"
check_refused r1 "where the checkpoint counts" "$t" good
# one changed byte in them
interrupted r2
t=$(ls r2/trajectories.csv.tmp*); cp "$t" good
printf 'X' | dd of="$t" bs=1 seek=200 conv=notrunc status=none
check_refused r2 "checksum" "$t" good
# a frame of the series changed
interrupted r3
f=$(ls r3/bodies.tmp*/bodies_000001.vtp); cp "$f" good
printf '\x01' | dd of="$f" bs=1 seek=$(( $(stat -c %s "$f") - 40 )) conv=notrunc status=none
check_refused r3 "bodies_000001.vtp" "$f" good
# one flipped bit in the checkpoint's body data: refused by its checksum, not resumed into
# other results
interrupted r4
c=$(ls r4/checkpoint/rank0.step*.bin); cp "$c" good
/usr/bin/python3 - "$c" <<'PY'
import sys
p = sys.argv[1]; b = bytearray(open(p, "rb").read())
b[len(b) // 2] ^= 0x10
open(p, "wb").write(b)
PY
check_refused r4 "checksum mismatch" "$c" good
# the checkpoint cut short: refused, and the output so far kept
interrupted r5
c=$(ls r5/checkpoint/rank0.step*.bin); cp "$c" good; truncate -s -9 "$c"
check_refused r5 "checkpoint" "$c" good
# latest.json naming a step whose file is missing: refused saying "missing"
interrupted r6
c=$(ls r6/checkpoint/rank0.step*.bin); cp "$c" good; rm "$c"
check_refused r6 "missing" "$c" good
echo "outputs_test: resume verifies: PASS"
echo "outputs_test: PASS"
