#!/bin/bash
# Every version of the batched step's loop functions that a CPU with AVX2 or AVX-512 runs is
# vectorized: in the AVX2 (x86-64-v3) and AVX-512 (x86-64-v4) clones of splitting_lanes,
# strang_lanes and its strang_force_lanes, euler_lanes, and rk4_lanes and its rk4_stage_lanes in
# the lrigid binary, at least
# MIN_PACKED of the floating-point arithmetic instructions are packed (vector) ones. A loop that
# stops vectorizing in one clone only (an operation that instruction set lacks, say a conversion
# between double and int64, which AVX2 does not have) leaves that clone scalar, at a third of
# the speed on the CPUs that run it, while the machine that runs the tests uses another clone;
# vectorization_guard_test, which times the clone this machine runs, cannot see it. This reads
# the machine code, so it checks both clones whatever the CPU.
# usage: clones_vectorized_test.sh LRIGID
set -euo pipefail
BIN=$1
MIN_PACKED=0.4
objdump -d --no-show-raw-insn -C "$BIN" | awk -v min="$MIN_PACKED" '
  function flush() {
    if (name != "") {
      share = tot > 0 ? pk / tot : 0
      printf "%s %.2f packed of %d  %s\n", (share >= min ? "ok  " : "LOW "), share, tot, name
      if (share < min) low++
      n[clone]++
    }
    name = ""; pk = 0; tot = 0
  }
  /^[0-9a-f]+ <.*::(splitting|strang|strang_force|euler|rk4|rk4_stage)_lanes<.*\[clone \.arch_x86_64_v[34]\]>:$/ {
    flush(); name = $0; sub(/^[0-9a-f]+ </, "", name); sub(/>:$/, "", name)
    clone = name; sub(/.*\[clone \./, "", clone); sub(/\]$/, "", clone)
    gsub(/lrigid::|\(anonymous namespace\)::/, "", name); sub(/\(.*\) \[clone/, " [clone", name)
    next
  }
  /^$/ { flush(); next }
  name != "" && /\tv?(add|sub|mul|div|fn?m(add|sub)[0-9]+|sqrt|min|max)[ps][sd] / {
    tot++
    if ($0 ~ /\tv?(add|sub|mul|div|fn?m(add|sub)[0-9]+|sqrt|min|max)p[sd] /) pk++
  }
  END {
    flush()
    printf "%d AVX2 and %d AVX-512 versions; %d below %s packed\n", n["arch_x86_64_v3"],
           n["arch_x86_64_v4"], low, min
    # the six files of the loops (one per precision and kind of M) give their 52 loop functions
    # both clones (per precision: splitting and strang for each M, and strang_force, euler, rk4
    # and rk4_stage for a sphere and for a non-flat and a flat body of the two other M)
    if (n["arch_x86_64_v3"] < 52 || n["arch_x86_64_v4"] < 52) { print "FAIL: clones missing"; exit 1 }
    if (low > 0) { print "FAIL: a clone of the loops is not vectorized"; exit 1 }
  }'
