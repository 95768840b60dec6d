#!/usr/bin/python3
"""Progress of a long study made of steps (validation/run_all, bench/accuracy/run_study.sh).

The same display as the runtime's (runtime/src/io/progress.*), on stderr:
  - on a terminal (stderr a tty, TERM not "dumb", CI unset): a bar kept on the last line and
    redrawn every second, "run_all [#####.....] 3/8 langevin, elapsed 2 min 10 s, ETA 5 min";
    the step's own output scrolls above it;
  - otherwise (piped, a log file, CI): a plain line when a step starts and ends, and every
    --interval seconds (default 60) while it runs;
  - quiet: nothing (the steps' own output is still shown).
LRIGID_PROGRESS=bar|lines|quiet overrides the choice.

Time remaining: the previous complete run of the same steps (a JSON history file) minus the
time elapsed; without one, the mean time of the steps done so far times the steps left.

In Python:   steps = Steps("run_all", n, history=FILE); rc = steps.run(k, name, cmd)
From a shell script, one step per call (exit status: the command's):
    progress.py --label L --start EPOCH --step K --of N --name NAME [--history FILE]
                [--log FILE] [--interval S] [--quiet] -- COMMAND ARGS...
"""
import argparse
import json
import os
import subprocess
import sys
import threading
import time

WIDTH = 24  # bar characters, as the runtime's


def auto_mode(stream=sys.stderr):
    forced = os.environ.get("LRIGID_PROGRESS", "")
    if forced in ("bar", "lines", "quiet"):
        return forced
    ci = os.environ.get("CI", "")
    if ci and ci not in ("false", "0"):
        return "lines"
    if os.environ.get("TERM") == "dumb" or not stream.isatty():
        return "lines"
    return "bar"


def format_duration(s):
    """'12 s', '3 min 04 s' or '2 h 05 min' (as Progress::format_duration)."""
    if s is None or s < 0 or s != s:
        return "?"
    if s < 60:
        return "%.0f s" % s
    if s < 3600:
        return "%d min %02d s" % (s // 60, int(s) % 60)
    return "%d h %02d min" % (s // 3600, int(s // 60) % 60)


def remaining(elapsed, done, total, current, previous_total):
    """Seconds left: from the previous run's total, else the mean of the `done` steps so far
    (their time is elapsed - current) times the steps left, less the current step's time."""
    if previous_total and previous_total > elapsed:
        return previous_total - elapsed
    if done > 0:
        return max(0.0, (elapsed - current) / done * (total - done) - current)
    return None


class Steps:
    """Steps 1..total of a study; `start` (epoch s) defaults to now."""

    def __init__(self, label, total, history=None, mode=None, start=None, interval=60.0,
                 key=None):
        self.label, self.total, self.history, self.interval = label, total, history, interval
        self.mode = mode or auto_mode()
        self.start = start if start is not None else time.time()
        self.key = key or "%s/%d" % (label, total)
        self.previous = self._load().get(self.key)
        self.lock = threading.Lock()
        self.bar = ""

    def _load(self):
        try:
            with open(self.history) as f:
                return json.load(f)
        except (OSError, ValueError, TypeError):
            return {}

    def _save_total(self, seconds):
        if not self.history:
            return
        h = self._load()
        h[self.key] = seconds
        tmp = "%s.tmp%d" % (self.history, os.getpid())
        with open(tmp, "w") as f:
            json.dump(h, f, indent=1)
        os.replace(tmp, self.history)

    def status(self, k, name, step_start, state):
        """The text after the label: 'study k/N name, elapsed ..., ... remaining'."""
        now = time.time()
        elapsed, current = now - self.start, now - step_start
        done = k - 1 if state != "done" else k
        left = remaining(elapsed, done, self.total, 0.0 if state == "done" else current,
                         self.previous)
        return (done, elapsed, left, "%d/%d %s%s, elapsed %s" % (
            k, self.total, name, "" if state == "running" else " " + state,
            format_duration(elapsed)))

    def _draw(self, k, name, step_start, state):
        done, elapsed, left, text = self.status(k, name, step_start, state)
        if self.mode == "lines":
            sys.stderr.write("%s: %s, %s remaining\n" % (self.label, text, format_duration(left)))
        elif self.mode == "bar":
            f = elapsed / (elapsed + left) if left is not None and elapsed + left > 0 else \
                done / self.total
            n = int(round(min(1.0, f) * WIDTH))
            self.bar = "%s [%s%s] %s, ETA %s" % (self.label, "#" * n, "." * (WIDTH - n), text,
                                                 format_duration(left))
            sys.stderr.write("\r%s\033[K" % self.bar)
        sys.stderr.flush()

    def run(self, k, name, cmd, log=None, env=None):
        """Runs step k (1-based) `cmd`, its output (stdout and stderr) echoed to stdout and
        appended to `log`; returns its exit status."""
        step_start = time.time()
        with self.lock:
            self._draw(k, name, step_start, "started" if self.mode == "lines" else "running")
        env = dict(env or os.environ, PYTHONUNBUFFERED="1")
        p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env)
        stop = threading.Event()

        def tick():  # bar: every second; lines: every interval
            while not stop.wait(1.0 if self.mode == "bar" else self.interval):
                with self.lock:
                    self._draw(k, name, step_start, "running")

        ticker = threading.Thread(target=tick, daemon=True)
        if self.mode != "quiet":
            ticker.start()
        logf = open(log, "ab") if log else None
        try:
            for line in iter(p.stdout.readline, b""):
                with self.lock:
                    if self.mode == "bar":
                        sys.stderr.write("\r\033[K")
                        sys.stderr.flush()
                    sys.stdout.buffer.write(line)
                    sys.stdout.flush()
                    if self.mode == "bar":
                        sys.stderr.write(self.bar)
                        sys.stderr.flush()
                if logf:
                    logf.write(line)
            rc = p.wait()
        finally:
            stop.set()
            if logf:
                logf.close()
        with self.lock:
            self._draw(k, name, step_start, "done" if rc == 0 else "failed (exit %d)" % rc)
            if self.mode == "bar":
                sys.stderr.write("\n")
                sys.stderr.flush()
        if k == self.total and rc == 0:
            self._save_total(time.time() - self.start)
        return rc


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--label", required=True)
    p.add_argument("--start", type=float, required=True, help="the study's start, epoch s")
    p.add_argument("--step", type=int, required=True, help="this step, 1..N")
    p.add_argument("--of", type=int, required=True, help="N, the number of steps")
    p.add_argument("--name", required=True)
    p.add_argument("--history", default=None, help="JSON file of the previous runs' totals")
    p.add_argument("--log", default=None, help="append the command's output to this file")
    p.add_argument("--interval", type=float, default=60.0, help="s between plain lines")
    p.add_argument("--quiet", action="store_true")
    p.add_argument("command", nargs=argparse.REMAINDER)
    a = p.parse_args()
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    if not cmd or not 1 <= a.step <= a.of:
        p.error("need --step K --of N with 1 <= K <= N, and -- COMMAND")
    steps = Steps(a.label, a.of, history=a.history, mode="quiet" if a.quiet else None,
                  start=a.start, interval=a.interval)
    sys.exit(steps.run(a.step, a.name, cmd, log=a.log))


if __name__ == "__main__":
    main()
