"""The benchmarks' cost measure that other jobs on a shared machine do not move: `lrigid::simulate`'s
inclusive instructions under callgrind (one thread). Used by bench/contacts/run.py and
bench/accuracy/instructions_per_second.py."""
import os
import re
import subprocess
import sys


def simulate_instructions(cg_file):
    """`simulate` inclusive instructions of a callgrind output (the largest simulate entry)"""
    out = subprocess.run(["callgrind_annotate", "--inclusive=yes", cg_file], capture_output=True,
                         text=True, check=True).stdout
    best = 0
    for line in out.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\(.*\)\s+\S*lrigid::simulate\(", line)
        if m:
            best = max(best, int(m.group(1).replace(",", "")))
    if best == 0:
        sys.exit("callgrind_count: no lrigid::simulate in %s" % cg_file)
    return best


def callgrind(cmd, cg_file):
    """runs cmd (a list) under callgrind on one thread; simulate's inclusive instructions"""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + cg_file] + cmd,
                   env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return simulate_instructions(cg_file)
