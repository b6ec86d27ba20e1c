#!/usr/bin/python3
"""sweep --jobs 2 stopped by SIGINT or SIGTERM to the parent, at either of its
two phases: while it runs the shared reference itself (no worker yet), and
while workers run their points (they are stopped too, none left running).
Either way the parent exits 130 and writes no CSV, and leaves no points
directory."""
import os
import signal
import subprocess
import sys
import tempfile
import time

flag_sim = os.path.abspath(sys.argv[1])
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


def stop(proc, sig, out, what, workers):
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    check(proc.returncode == 130, f"{what}: exit {proc.returncode} {err}")
    # (a worker stopped in mid-frame says so itself, before the parent's last line)
    last = err.strip().splitlines()[-1] if err.strip() else ""
    check(last.startswith("interrupted: sweep: stopped by a signal"), f"{what}: {err}")
    time.sleep(0.2)
    check(not any(alive(w) for w in workers), f"{what}: a worker is still running")
    check(not os.path.exists(out), f"{what}: a CSV was written")
    check(not os.path.exists(out + ".points"), f"{what}: the points directory is left")


with tempfile.TemporaryDirectory() as tmp:
    # The default scene's mass-spring reference on 129 x 193 takes seconds a
    # frame: a signal 1 s in finds the parent running it, no worker started.
    for sig in (signal.SIGINT, signal.SIGTERM):
        out = os.path.join(tmp, f"reference_{sig.name}.csv")
        proc = subprocess.Popen(
            [flag_sim, "sweep", "--coarse", "9x13", "--jobs", "2", "-o", out, "--quiet"],
            cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(1.0)
        check(children_of(proc.pid) == [], f"reference {sig.name}: workers before the reference")
        stop(proc, sig, out, f"reference {sig.name}", [])
    # With the reference saved (2 frames), the workers start at once; Bullet on
    # 129 x 193 (point 1, asked for by --references) takes about a minute a frame.
    ref = os.path.join(tmp, "ref.rec")
    r = subprocess.run([flag_sim, "sweep", "--coarse", "9x13", "--frames", "2", "--point", "0",
                        "--reference-file", ref, "-o", os.path.join(tmp, "p0.csv"), "--quiet"],
                       cwd=tmp, capture_output=True, text=True, timeout=300)
    check(r.returncode == 0 and os.path.exists(ref), f"the reference: {r.stderr}")
    for sig in (signal.SIGINT, signal.SIGTERM):
        out = os.path.join(tmp, f"workers_{sig.name}.csv")
        proc = subprocess.Popen(
            [flag_sim, "sweep", "--coarse", "9x13", "--frames", "2", "--jobs", "2",
             "--references", "mass-spring,bullet", "--reference-file", ref, "-o", out, "--quiet"],
            cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline, seen = time.time() + 30, set()
        while time.time() < deadline and not any(alive(w) for w in seen):
            seen.update(children_of(proc.pid))
            time.sleep(0.02)
        time.sleep(0.5)
        workers = [w for w in seen | set(children_of(proc.pid))]
        check(any(alive(w) for w in workers), f"workers {sig.name}: no worker running")
        stop(proc, sig, out, f"workers {sig.name}", workers)
    check(os.path.exists(ref), "the user's reference file is kept")

for failure in failures:
    print("FAILED:", failure)
print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
sys.exit(1 if failures else 0)
