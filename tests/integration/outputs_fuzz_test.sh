#!/bin/bash
# The output folder's invariants (docs/outputs.md) under a kill at any write of a run and under
# a corrupted checkpoint:
#  1. a run with checkpoints, over an earlier complete result and files of the user's, is killed
#     (strace -e inject=SYSCALL:signal=KILL:when=K) at the write sites of its own: a site is a
#     write-class syscall (open for writing, write, writev, fsync, rename, unlink, mkdir, rmdir)
#     on a kind of path in the folder, killed at its first call; every site that changes a
#     name or makes a folder or the journal durable, every other one of the rest. After
#     each kill the folder holds the earlier result byte for byte, the new one, or no
#     summary.json and the journal; the next lrigid completes a decided finish into the new
#     result; a run with a checkpoint resumes to the uninterrupted run's result byte for byte
#     (or refuses with exit 3 changing nothing, and a fresh run then works); the user's files
#     are never touched.
#  2. the checkpoint of a run killed in its finish (before the journal) is corrupted field by
#     field: a field of each class (magic, format version, the header's values, the bodies'
#     data, the run's counts, the writer's part, the trailing checksum) with its checksum
#     kept; the header's values, the output's counts and every length and count with a
#     checksum made to match; cuts at several offsets, an extra byte, the file removed; and
#     latest.json, each field changed or missing. --resume refuses each with exit 3 naming the
#     file and changes nothing (the finish's leftovers included); with the good files back it
#     resumes to the uninterrupted run's result.
# usage: outputs_fuzz_test.sh SOURCE_DIR LRIGID [kill|corrupt]  (both without the third: ctest
# runs them as two tests, which a parallel ctest runs side by side)
set -euo pipefail
src=$1 lrigid=$2 part=${3:-all}
# in memory where there is /dev/shm: a run makes some hundred fsyncs, which cost nothing there;
# a kill loses nothing that the page cache holds, so the outcomes are the same
work=$(mktemp -d -p /dev/shm 2> /dev/null || mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; [ -f err.txt ] && cat err.txt; exit 1; }
command -v strace > /dev/null || fail "strace not found (scripts/install-deps installs it)"
py=/usr/bin/python3
start=$(date +%s)

# a listing of DIR with each name's inode, size and change time, which any write, rename or
# re-creation changes: what "changes nothing" compares
snapshot() { (cd "$1" && find . -printf '%y %p %i %s %C@\n' | sort); }
# one thread and a fixed seed: the results are byte for byte the same at every run (timing
# aside), so a kill, a resume and a completion can be compared with an uninterrupted run
run() { "$lrigid" run "$@" --quiet --threads 1; }

cat > a.json <<'JSON'
{
  "fluid": { "density": 1.2, "kinematic_viscosity": 1.5e-5,
             "uniform": { "U": [1, 0, 0], "k": 0.1, "epsilon": 0.05 } },
  "gravity": [0, 0, -9.81],
  "effects": "auto",
  "integrator": { "scheme": "splitting", "dt": 0.001 },
  "duration": 0.05, "seed": 1,
  "ground": { "z": 0.9 },
  "bodies": [ { "name": "bead", "shape": { "type": "sphere", "radius": 0.003 }, "density": 30,
                "count": 5, "spawn_box": [[0, 0, 1], [0.1, 0.1, 1.1]] } ],
  "output": { "dir": "out", "every": 0.01, "formats": ["csv", "pvd", "glb"],
              "checkpoint_every": 0 }
}
JSON
sed 's/"seed": 1/"seed": 2/' a.json > b.json
# a result's content: every final name in DIR (not the run's temporaries *.tmp<pid>, the
# earlier results moved aside *.old<pid>, the journal, checkpoint/, the user's files) and each
# file's checksum, summary.json's without its timing
left='.*\.\(tmp\|old\)[0-9]+.*'
result_of() {  # result_of DIR
  (cd "$1" && { find . \( -regex "$left" -o -name lrigid-finish.json -o -name checkpoint \
                        -o -name notes.txt -o -name mine \) -prune -o ! -name summary.json -print0 |
                  xargs -0 md5sum 2>&1 | sort -k2
                grep -v '"wall_seconds"\|"body_steps_per_second"' summary.json 2>&1; })
}
run a.json -o refA
# the new run writes a checkpoint at every output (6 of them)
run b.json -o refB --checkpoint-every 1e-9
resultA=$(result_of refA) resultB=$(result_of refB)
is_result() {  # is_result DIR A|B: DIR holds exactly the result of run A or B
  local want=result$2
  [ "$(result_of "$1")" = "${!want}" ]
}
# ...and nothing else of lrigid's is left: no journal, checkpoint, temporary or moved-aside file
is_clean_result() {  # is_clean_result DIR A|B
  is_result "$1" "$2" || return 1
  [ -z "$(cd "$1" && find . -regex "$left" -o -name lrigid-finish.json -o -name checkpoint)" ]
}
user_files() {  # the user's notes and a folder of theirs in the output folder
  echo notes > "$1/notes.txt"; mkdir -p "$1/mine"; echo keep > "$1/mine/keep.txt"
}
user_files_kept() {
  [ "$(cat "$1/notes.txt" 2> /dev/null)" = notes ] && [ "$(ls "$1/mine")" = keep.txt ] &&
    [ "$(cat "$1/mine/keep.txt")" = keep ]
}

# ---- 1. a kill at every write site of a run ----
# the write-class syscalls (open for writing counts among the opens), traced with the paths
# of their descriptors
calls=openat,write,writev,pwrite64,fsync,fdatasync,ftruncate,rename,renameat,renameat2,unlink,unlinkat,mkdir,mkdirat,rmdir
rm -rf probe; cp -a refA probe; user_files probe
strace -f -y -o trace.txt -e trace=$calls "$lrigid" run b.json -o "$work/probe" --quiet \
  --threads 1 --checkpoint-every 1e-9 || fail "the traced run failed"
is_clean_result probe B || fail "the traced run's result differs from the untraced one's"
# the kill points: for each call of the main thread into the output folder, its number among
# that thread's calls of the same syscall (what when= counts); a site is the syscall and the
# path with its numbers made N; the first call at each site
"$py" - trace.txt "$work/probe" > points.txt <<'PY'
import collections, re, sys
lines = open(sys.argv[1]).read().splitlines()
root = sys.argv[2]
main = lines[0].split()[0]
count = collections.Counter()
first = {}
for ln in lines:
    pid, rest = ln.split(None, 1)
    m = re.match(r'(\w+)\((.*)', rest)
    if not m:
        continue  # "<... resumed>", exits, signals
    call, args = m.groups()
    count[pid, call] += 1
    if pid != main or root not in args:
        continue
    if call == 'openat' and not re.search(r'O_WRONLY|O_RDWR|O_CREAT', args):
        continue
    paths = re.findall(re.escape(root) + r'[^">,]*', args)
    site = call + ' ' + ' '.join(re.sub(r'\d+', 'N', p[len(root):]) or '/' for p in paths)
    first.setdefault(site, count[pid, call])
# every site where a name changes (rename, unlink, mkdir, rmdir) or a folder or the journal is
# made durable (fsync): their order is what the invariants rest on; of the other sites (a
# file opened, written or made durable) every other one, by syscall in the order of the run
rare = re.compile(r'^(rename|renameat2?|unlink|unlinkat|mkdir|mkdirat|rmdir) |'
                  r'^fsync (/|/[a-z]+(\.tmpN)?|/checkpoint|/lrigid-finish\.json\.tmpN)$')
sites = sorted(first.items(), key=lambda p: (p[0].split()[0], p[1]))
other = [p for p in sites if not rare.match(p[0])]
for site, k in sites:
    if rare.match(site) or other.index((site, k)) % 2 == 0:
        print(site.split()[0], k, site)
PY
npoints=$(wc -l < points.txt)
[ "$npoints" -ge 60 ] || fail "only $npoints kill points found in the traced run"
echo "outputs_fuzz_test: $npoints kill points ($(cut -d' ' -f1 points.txt | sort | uniq -c |
  awk '{printf "%s%s %s", sep, $1, $2; sep=", "}'))"

[ "$part" != corrupt ] || npoints=0  # (the corruptions below take a kill point of them)
i=0 resumed=0 refused=0 completed=0 earlier=0 finished=0 elsewhere=0
while read -r call k site; do
  i=$((i + 1))
  what="kill $i/$npoints at $call #$k ($site)"
  rm -rf k; cp -a refA k; user_files k
  rc=0
  strace -f -y -o kill.txt -e trace="$call" -e inject="$call:signal=KILL:when=$k" \
    "$lrigid" run b.json -o "$work/k" --quiet --threads 1 --checkpoint-every 1e-9 \
    > /dev/null 2> err.txt || rc=$?
  if [ "$rc" = 0 ]; then
    # fewer calls than traced (the traced run rewrote its partial series on the clock more
    # often): it finished before the K-th, with the new result
    is_clean_result k B && user_files_kept k ||
      fail "$what: not reached, and the run's result differs"
    finished=$((finished + 1))
    echo "outputs_fuzz_test: $what: not reached, the run finished"
    continue
  fi
  [ "$rc" = 137 ] || fail "$what: the run exited $rc, not killed"
  # the call killed: the site's (the run does the same as traced), or, where another thread
  # reached its own K-th call first or a partial series was rewritten on the clock, another
  path=${site#* }; path=${path%% *}
  [ "$path" != / ] || path='<>'  # the folder itself, by its descriptor
  hit=$(grep -m1 ' = ?$' kill.txt | sed "s|$work/k||g; s/[0-9]\+/N/g; s/  */ /g") || true
  case $hit in
    *"$path"*) at= ;;
    *) elsewhere=$((elsewhere + 1)) at=" (landed at: ${hit:-a call of another thread})" ;;
  esac
  user_files_kept k || fail "$what: the user's files were touched"
  # right after the kill: a complete result of either run, or none and the journal
  if [ -e k/summary.json ]; then
    is_result k A || is_result k B || fail "$what: a mixture with a summary.json"
  else
    [ -e k/lrigid-finish.json ] || fail "$what: no summary.json and no journal"
  fi
  if [ -e k/lrigid-finish.json ]; then
    # a decided finish: the next lrigid to open the folder completes it (--resume then finds
    # the run finished; export-gltf goes on with its own work)
    if [ -e k/checkpoint/latest.json ] && ((i % 2)); then
      rc=0; run b.json --resume k 2> err.txt || rc=$?
      [ "$rc" = 3 ] && grep -q "has finished" err.txt ||
        fail "$what: --resume over a decided finish exited $rc"
    else
      "$lrigid" export-gltf k -o k.glb 2> err.txt || fail "$what: export-gltf after the kill"
    fi
    grep -q "complet" err.txt || fail "$what: the completion is not said on stderr"
    is_clean_result k B || fail "$what: the completed finish is not the new run's result"
    completed=$((completed + 1)) outcome="decided finish completed"
  elif [ -e k/checkpoint/latest.json ]; then
    before=$(snapshot k)
    rc=0; run b.json --resume k 2> err.txt || rc=$?
    if [ "$rc" = 0 ]; then
      is_clean_result k B || fail "$what: the resumed result differs from the uninterrupted one"
      resumed=$((resumed + 1)) outcome="resumed"
    else
      [ "$rc" = 3 ] || fail "$what: --resume exited $rc"
      [ "$(snapshot k)" = "$before" ] || fail "$what: a refused --resume changed the folder"
      echo "outputs_fuzz_test: $what: --resume refused: $(head -1 err.txt)"
      rm -rf k/checkpoint
      run b.json -o k 2> err.txt || fail "$what: a fresh run after the refused resume"
      is_result k B || fail "$what: the fresh run's result differs"
      refused=$((refused + 1)) outcome="resume refused, fresh run"
    fi
  elif is_result k A; then
    # killed before its first checkpoint: the earlier result is intact, and a new run works
    run b.json -o k 2> err.txt || fail "$what: a new run over the earlier result"
    is_result k B || fail "$what: the new run's result differs"
    earlier=$((earlier + 1)) outcome="earlier result kept, new run"
  else
    is_clean_result k B || fail "$what: neither run's clean result"
    finished=$((finished + 1)) outcome="finished"
  fi
  user_files_kept k || fail "$what: the user's files were touched"
  echo "outputs_fuzz_test: $what: $outcome$at"
done < <(head -n "$npoints" points.txt)
if [ "$part" != corrupt ]; then
  echo "outputs_fuzz_test: $npoints kills ($elsewhere not at their site): $resumed resumed," \
       "$refused resume refused, $completed decided finishes completed, $earlier before any" \
       "checkpoint, $finished finished (killed after the finish or not reached)"
  echo "outputs_fuzz_test: a kill at every write site: PASS ($(( $(date +%s) - start )) s)"
fi
[ "$part" != kill ] || { echo "outputs_fuzz_test: PASS"; exit 0; }

# ---- 2. a corrupted checkpoint ----
cat > ckp.py <<'PY'
# a checkpoint's fields (io/checkpoint.cpp, the writer's part io/result_writer.cpp), and
# corruptions of them
import struct, sys

def fnv(b):  # FNV-1a 64 (io/durable.h)
    h = 14695981039346656037
    for c in b:
        h = ((h ^ c) * 0x100000001b3) & 0xffffffffffffffff
    return h

def layout(b):
    """[(name, offset, size)]: every field; a vector as NAME.count and NAME.data"""
    f, at = [], 0
    def raw(name, n):
        nonlocal at
        f.append((name, at, n)); at += n
    def u64():
        return struct.unpack_from('<Q', b, at)[0]
    def vec(name, item):
        n = u64(); raw(name + '.count', 8)
        if n: raw(name + '.data', n * item)
    def s(name):
        n = u64(); raw(name + '.length', 8)
        if n: raw(name + '.text', n)
    raw('magic', 7); raw('version', 1)
    s('build'); s('scene'); raw('ranks', 4); raw('rank', 4); raw('t', 8); raw('step', 8)
    for name, item in (('x', 24), ('q', 32), ('v', 24), ('w', 24), ('u_seen', 24), ('type', 2),
                       ('status', 1), ('t_stop', 8)):
        vec(name, item)
    n = u64(); raw('reasons.count', 8)
    for k in range(n):
        s('reason%d' % k)
    for name, item in (('history', 8), ('history_offset', 8), ('contact', 1), ('rest_steps', 4),
                       ('impacts', 4), ('t_touch', 8), ('x_touch', 24), ('hidden', 1),
                       ('watch', 72), ('pair_impulses', 64)):
        vec(name, item)
    raw('stats', 96)
    s('writer.tag'); raw('writer.csv_bytes', 8); raw('writer.csv_sum', 8)
    n = u64(); raw('writer.frames.count', 8)
    for k in range(n):
        raw('writer.frame%d.t' % k, 8); s('writer.frame%d.name' % k)
    vec('writer.frame_sums', 32)
    for name, item in (('gltf.body_type', 4), ('gltf.times', 8), ('gltf.x', 24), ('gltf.q', 32),
                       ('gltf.hidden', 1), ('gltf.state', 1), ('gltf.v', 24), ('gltf.w', 24)):
        vec(name, item)
    raw('checksum', 8)
    if at != len(b):
        sys.exit('test bug: the checkpoint layout ends at %d of %d bytes' % (at, len(b)))
    if fnv(b[:-8]) != struct.unpack_from('<Q', b, len(b) - 8)[0]:
        sys.exit('test bug: the checksum is not io/durable.h\'s FNV-1a 64 of the bytes before it')
    return f

cmd, path = sys.argv[1], sys.argv[2]
b = bytearray(open(path, 'rb').read())
if cmd == 'fields':
    for name, at, n in layout(b):
        print(name, at, n)
    sys.exit()
# corrupt PATH FIELD HOW SUM: HOW flip (a bit of its middle byte), plus1, huge (a length
# of 2^36), set:VALUE (an integer field), zero; SUM "sum": a checksum made to match, "raw": kept
field, how, sum_ = sys.argv[3:6]
if field == 'cut':  # cut at byte HOW
    b = b[:int(how)]
elif field == 'append':
    b += b'\0'
else:
    name, at, n = next(x for x in layout(b) if x[0] == field)
    if how == 'flip':
        b[at + n // 2] ^= 0x10
    elif how == 'zero':
        b[at:at + n] = bytes(n)
    else:
        v = int.from_bytes(b[at:at + n], 'little', signed=True)
        v = v + 1 if how == 'plus1' else 1 << 36 if how == 'huge' else int(how[4:])
        b[at:at + n] = v.to_bytes(n, 'little', signed=True)
if sum_ == 'sum' and len(b) >= 16:
    b[-8:] = struct.pack('<Q', fnv(b[:-8]))
open(path, 'wb').write(b)
PY
# an interrupted run, killed in its finish before the journal (after its last checkpoint): the
# folder also holds the finish's leftovers, which a refused resume keeps like everything else
k=$(grep -m1 ' rename /summary.json.tmpN.tmpN ' points.txt | cut -d' ' -f2)
[ -n "$k" ] || fail "test bug: no rename of summary.json's temporary among the kill points"
# (a run that rewrites its partial series on the clock more or less often than the traced one
# makes two renames more or fewer each time: the kill point moves until it lands there)
latest=r/checkpoint/latest.json
for try in 1 2 3 4 5; do
  rm -rf r; cp -a refA r; user_files r
  rc=0
  strace -f -o /dev/null -e trace=rename -e inject="rename:signal=KILL:when=$k" \
    "$lrigid" run b.json -o "$work/r" --quiet --threads 1 --checkpoint-every 1e-9 \
    > /dev/null 2>&1 || rc=$?
  if [ "$rc" = 0 ] || [ -e r/lrigid-finish.json ]; then k=$((k - 2))  # too late
  elif ! ls r/summary.json.tmp* > /dev/null 2>&1; then k=$((k + 2))  # too early
  else break; fi
done
[ -f $latest ] && ls r/summary.json.tmp* > /dev/null ||
  fail "test bug: the run killed in its finish left no checkpoint or no finish leftovers"
step=$("$py" -c 'import json, sys; print(json.load(open(sys.argv[1]))["step"])' $latest)
c=r/checkpoint/rank0.step$step.bin
cp $c good.bin; cp $latest good.json
"$py" ckp.py fields $c > fields.txt || fail "$(cat fields.txt)"
n=0
refused() {  # refused WHAT FILE [TEXT]: --resume exits 3 naming FILE (saying TEXT), changes nothing
  local before rc=0
  before=$(snapshot r)
  run b.json --resume r 2> err.txt || rc=$?
  [ "$rc" = 3 ] || fail "$1: --resume exited $rc, not 3"
  grep -qF "$2" err.txt || fail "$1: the message does not name $2"
  [ -z "${3:-}" ] || grep -qF "$3" err.txt || fail "$1: the message does not say '$3'"
  [ "$(snapshot r)" = "$before" ] || fail "$1: a refused --resume changed the folder"
  user_files_kept r || fail "$1: the user's files were touched"
  cp good.bin $c; cp good.json $latest
  n=$((n + 1))
}
ckp() { "$py" ckp.py corrupt $c "$@" || fail "test bug: ckp.py $*"; }
name=checkpoint/rank0.step$step.bin
# a field of each class, its checksum kept: refused by the checksum (the magic and the version
# before it): the header's, the bodies' state, the run's counts, the writer's part, the checksum
for field in magic version build.length scene.text ranks step x.count x.data status.data \
             stats writer.csv_sum writer.frame_sums.data gltf.q.data checksum; do
  grep -q "^$field " fields.txt || fail "test bug: the checkpoint has no field $field"
  ckp "$field" flip raw
  case $field in
    magic | version) refused "$field changed" $name "not an lrigid checkpoint" ;;
    *) refused "$field changed" $name "checksum mismatch" ;;
  esac
done
# a checksum made to match: what the structure says is checked on its own
ckp magic flip sum; refused "magic changed" $name "not an lrigid checkpoint"
ckp version set:50 sum; refused "version 2" $name "format 2"
ckp version set:52 sum; refused "version 4" $name "another format version"
ckp build.text flip sum; refused "build changed" $name "another build"
ckp scene.text flip sum; refused "scene changed" $name "another scene"
ckp ranks plus1 sum; refused "ranks + 1" $name "MPI rank"
ckp rank plus1 sum; refused "rank + 1" $name "holds rank"
ckp step plus1 sum; refused "step + 1" $name "another step"
ckp writer.tag.text flip sum; refused "the temporaries' tag" $name "not of one run"
ckp writer.csv_bytes plus1 sum; refused "the trajectories' length + 1" trajectories.csv.tmp
ckp writer.csv_sum flip sum; refused "the trajectories' checksum" trajectories.csv.tmp
ckp writer.frame_sums.data flip sum; refused "a frame's checksum" .vtp
ckp writer.frames.count plus1 sum; refused "frames + 1" $name
# every length and count (of the per-body strings and per-frame names the first): one more,
# and far more than the file holds
for field in $(awk '$1 ~ /\.(count|length)$/ && $1 !~ /^reason[1-9]|^writer\.frame[1-9]/ {print $1}' \
                 fields.txt); do
  ckp "$field" plus1 sum; refused "$field + 1" $name
  ckp "$field" huge sum; refused "$field = 2^36" $name
done
# cut at several offsets, with and without a checksum at the new end; a byte appended
size=$(stat -c %s good.bin)
for at in 0 8 16 $((size / 2)) $((size - 8)) $((size - 1)); do
  ckp cut $at raw; refused "cut at byte $at" $name
  ckp cut $at sum; refused "cut at byte $at, checksum made to match" $name
done
ckp append 0 raw; refused "a byte appended" $name
ckp append 0 sum; refused "a byte appended, checksum made to match" $name "bytes left"
rm $c; refused "the checkpoint removed" $name "missing"
# latest.json: not JSON, each field changed or missing
edit() {  # edit PYTHON: changes j, latest.json's content
  "$py" -c 'import json, sys
j = json.load(open(sys.argv[1]))
'"$1"'
open(sys.argv[1], "w").write(json.dumps(j))' $latest || fail "test bug: edit $1"
}
: > $latest; refused "latest.json empty" latest.json "not valid JSON"
head -c 40 good.json > $latest; refused "latest.json cut short" latest.json "not valid JSON"
edit 'j["step"] += 10'; refused "step + 10" latest.json "missing"
edit 'j["step"] = "x"'; refused "step not a number" latest.json "malformed"
edit 'j["build"] = "gnu-build-id:0"'; refused "build changed" latest.json "another build"
edit 'j["scene"] = "0"'; refused "scene changed" latest.json "another scene"
edit 'j["ranks"] = 2'; refused "ranks 2" latest.json "MPI rank"
for tag in '""' '"s"' '".json"' '".tmp"' '".tmp1/../x"' '"/tmp"'; do
  edit "j['tag'] = $tag"; refused "tag $tag" latest.json "tag"
done
edit 'j["tag"] = 1'; refused "tag a number" latest.json "malformed"
edit 'j["tag"] = ".tmp999999999"'; refused "another run's tag" trajectories.csv.tmp999999999 "missing"
for key in step build scene ranks tag; do
  edit "del j['$key']"; refused "no $key" latest.json "malformed"
done
echo "outputs_fuzz_test: $n corruptions refused, the folder unchanged"
# with the good files back the resume goes on, removes the finish's leftovers and gives the
# uninterrupted run's result
run b.json --resume r 2> err.txt || fail "the resume with the good checkpoint back"
is_clean_result r B || fail "the resumed result differs from the uninterrupted one"
user_files_kept r || fail "the user's files were touched"
echo "outputs_fuzz_test: a corrupted checkpoint: PASS ($(( $(date +%s) - start )) s)"
echo "outputs_fuzz_test: PASS"
