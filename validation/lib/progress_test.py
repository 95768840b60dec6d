#!/usr/bin/python3
"""Tests of validation/lib/progress.py (ctest progress_py_test): plain lines when stderr is a
pipe, nothing but the command's output with --quiet, the exit status passed on, durations."""
import os
import re
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import progress  # noqa: E402

CLI = os.path.join(HERE, "progress.py")


def run(k, n, *extra, cmd=("sh", "-c", "echo out; echo err >&2; exit 0"), history=None, ago=10):
    """Step k of n of a study that started `ago` seconds back."""
    env = {key: v for key, v in os.environ.items() if key not in ("LRIGID_PROGRESS", "CI")}
    args = ["/usr/bin/python3", CLI, "--label", "st", "--start", str(time.time() - ago),
            "--step", str(k), "--of", str(n), "--name", "s%d" % k] + list(extra)
    if history:
        args += ["--history", history]
    return subprocess.run(args + ["--"] + list(cmd), capture_output=True, text=True, env=env)


class ProgressTest(unittest.TestCase):
    def test_piped_gives_plain_lines(self):
        r = run(2, 4)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout, "out\nerr\n")  # the command's output, both streams
        lines = r.stderr.splitlines()
        # started 10 s (plus the interpreter's start) after the study: one step done, so
        # 3 steps left at the mean step time
        m = re.match(r"^st: 2/4 s2 started, elapsed (\d+) s, (\d+) s remaining$", lines[0])
        self.assertTrue(m, lines[0])
        self.assertAlmostEqual(int(m.group(2)), 3 * int(m.group(1)), delta=4)
        m = re.match(r"^st: 2/4 s2 done, elapsed (\d+) s, (\d+) s remaining$", lines[-1])
        self.assertTrue(m, lines[-1])
        self.assertAlmostEqual(int(m.group(2)), int(m.group(1)), delta=2)  # 2 done, 2 left
        self.assertNotIn("\r", r.stderr)
        self.assertNotIn("[#", r.stderr)

    def test_quiet_prints_only_the_command_output(self):
        r = run(1, 3, "--quiet")
        self.assertEqual(r.returncode, 0)
        self.assertEqual(r.stderr, "")
        self.assertEqual(r.stdout, "out\nerr\n")

    def test_failure_is_passed_on_and_not_remembered(self):
        with tempfile.TemporaryDirectory() as d:
            h = os.path.join(d, "h.json")
            r = run(3, 3, cmd=("sh", "-c", "exit 7"), history=h)
            self.assertEqual(r.returncode, 7)
            self.assertIn("st: 3/3 s3 failed (exit 7)", r.stderr)
            self.assertFalse(os.path.exists(h))
            # a complete run is remembered and gives the next run's estimate
            self.assertRegex(run(1, 3, history=h).stderr, r"started, elapsed \d+ s, \? remaining")
            self.assertEqual(run(3, 3, history=h, ago=60).returncode, 0)
            self.assertTrue(os.path.exists(h))
            r = run(1, 3, history=h)
            # the previous run took 60 s (and a little more): 50 s left after 10 s
            m = re.search(r"started, elapsed (\d+) s, (\d+) s remaining$", r.stderr.splitlines()[0])
            self.assertTrue(m, r.stderr)
            self.assertAlmostEqual(int(m.group(1)) + int(m.group(2)), 60, delta=5)

    def test_estimates(self):
        self.assertEqual(progress.format_duration(184), "3 min 04 s")
        self.assertEqual(progress.format_duration(7500), "2 h 05 min")
        self.assertEqual(progress.format_duration(None), "?")
        # 2 of 4 steps done in 20 s, 5 s into the third: 10 s per step, 15 s left
        self.assertAlmostEqual(progress.remaining(25, 2, 4, 5, None), 15)
        self.assertAlmostEqual(progress.remaining(25, 2, 4, 5, 100), 75)
        self.assertIsNone(progress.remaining(5, 0, 4, 5, None))


if __name__ == "__main__":
    unittest.main()
