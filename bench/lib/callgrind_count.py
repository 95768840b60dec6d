"""The benchmarks' cost measure that other jobs on a shared machine do not move: `lrigid::simulate`'s
inclusive instructions under callgrind (one thread). Used by bench/contacts/run.py and
bench/accuracy/instructions_per_second.py."""
import os
import re
import subprocess
import sys


def inclusive_table(cg_file):
    """[(inclusive instructions, symbol)] of every function of a callgrind output"""
    out = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", cg_file],
                         capture_output=True, text=True, check=True).stdout
    rows = []
    for line in out.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\(.*?\)\s+(?:\*\s+)?\S*?:(.*)$", line)
        if m:
            rows.append((int(m.group(1).replace(",", "")), m.group(2)))
    return rows


def instructions_of(rows, pattern):
    """the summed inclusive instructions of the distinct functions whose symbol matches the regular
    expression `pattern` (template instances of one function are distinct functions)"""
    return sum(n for n, sym in rows if re.search(pattern, sym))


def simulate_instructions(cg_file):
    """`simulate` inclusive instructions of a callgrind output (the largest simulate entry)"""
    best = max([n for n, sym in inclusive_table(cg_file) if re.match(r"lrigid::simulate\(", sym)],
               default=0)
    if best == 0:
        sys.exit("callgrind_count: no lrigid::simulate in %s" % cg_file)
    return best


def callgrind(cmd, cg_file):
    """runs cmd (a list) under callgrind on one thread; simulate's inclusive instructions"""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + cg_file] + cmd,
                   env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return simulate_instructions(cg_file)
