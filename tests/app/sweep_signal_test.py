#!/usr/bin/python3
"""sweep --jobs 2 stopped by SIGINT or SIGTERM to the parent: the workers are
stopped too (none left running), the parent exits 130, no CSV is written."""
import os
import signal
import subprocess
import sys
import tempfile
import time

flag_sim = sys.argv[1]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def children_of(pid):
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            return [int(c) for c in f.read().split()]
    except OSError:
        return []


def alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().split()[2] != "Z"
    except OSError:
        return False


with tempfile.TemporaryDirectory() as tmp:
    for sig in (signal.SIGINT, signal.SIGTERM):
        out = os.path.join(tmp, f"{sig.name}.csv")
        # Points that take minutes (mass-spring and Bullet on 129 x 193).
        proc = subprocess.Popen(
            [flag_sim, "sweep", "--coarse", "9x13", "--jobs", "2", "-o", out, "--quiet"],
            cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline = time.time() + 30
        workers = []
        while time.time() < deadline and len(workers) < 2:
            workers = children_of(proc.pid)
            time.sleep(0.05)
        check(len(workers) == 2, f"{sig.name}: {len(workers)} workers started")
        time.sleep(0.5)
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=60)
        check(proc.returncode == 130, f"{sig.name}: exit {proc.returncode} {err}")
        check(err.startswith("interrupted: sweep: stopped by a signal"), f"{sig.name}: {err}")
        time.sleep(0.2)
        check(not any(alive(w) for w in workers), f"{sig.name}: a worker is still running")
        check(not os.path.exists(out), f"{sig.name}: a CSV was written")
        check(not os.path.exists(out + ".points"), f"{sig.name}: the points directory is left")

for failure in failures:
    print("FAILED:", failure)
print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
sys.exit(1 if failures else 0)
