#!/usr/bin/python3
"""Progress lines (issue 15): on a terminal, run, render, compare and sweep show
a line with the frame, the rate and an ETA, labelled by what is running; with
stderr not a terminal (or --quiet) they print none. The terminal is a real
pseudo-terminal (os.openpty) given to flag-sim as its stderr.

Usage: progress_test.py FLAG_SIM"""
import os
import subprocess
import sys
import tempfile

flag_sim = os.path.abspath(sys.argv[1])
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def on_terminal(args, cwd):
    """Runs flag-sim with stderr on a pseudo-terminal; returns (exit, stdout, what the terminal got)."""
    primary, secondary = os.openpty()
    process = subprocess.Popen([flag_sim, *args], cwd=cwd, stdout=subprocess.PIPE,
                               stderr=secondary, text=True)
    os.close(secondary)
    seen = b""
    while True:
        try:
            chunk = os.read(primary, 65536)
        except OSError:  # the terminal closes when the last writer exits (EIO)
            break
        if not chunk:
            break
        seen += chunk
    out = process.stdout.read()
    process.wait(timeout=300)
    os.close(primary)
    return process.returncode, out, seen.decode(errors="replace")


# Slow enough per frame that the 5-per-second redraw shows at least one line.
small = ["--set", "flag.fine=[33,49]", "--set", "flag.coarse=[5,7]", "--frames", "20"]
with tempfile.TemporaryDirectory() as tmp:
    code, out, terminal = on_terminal(["run", *small, "-o", "r.h5"], tmp)
    check(code == 0, f"run: exit {code}")
    check("frame " in terminal and "ETA" in terminal, f"run shows no progress: {terminal!r}")
    code, out, terminal = on_terminal(["render", "r.h5", "-o", "frames/", "--size", "320x180"], tmp)
    check(code == 0, f"render: exit {code}")
    check("render: frame " in terminal and "ETA" in terminal, f"render: {terminal!r}")
    code, out, terminal = on_terminal(["compare", *small, "--set", "flag.fine=[17,25]"], tmp)
    check(code == 0, f"compare: exit {code} {terminal[-500:]!r}")
    for label in ("reference (mass-spring): frame", "hybrid: frame", "tracking: frame"):
        check(label in terminal, f"compare shows no '{label}': {terminal[-800:]!r}")
    code, out, terminal = on_terminal(["sweep", *small, "--set", "flag.fine=[17,25]", "--coarse",
                                       "5x7", "-o", "s.csv"], tmp)
    check(code == 0, f"sweep: exit {code} {terminal[-500:]!r}")
    check("reference (point 0): frame" in terminal, f"sweep: {terminal[-800:]!r}")
    # Not a terminal: no progress line, only the summary.
    r = subprocess.run([flag_sim, "run", *small, "-o", "q.h5"], cwd=tmp, capture_output=True,
                       text=True, timeout=300)
    check(r.returncode == 0 and "\r" not in r.stderr and "ETA" not in r.stderr,
          f"run with stderr to a pipe: {r.stderr!r}")
    code, out, terminal = on_terminal(["run", *small, "-o", "q2.h5", "--quiet"], tmp)
    check(code == 0 and "ETA" not in terminal, f"run --quiet on a terminal: {terminal!r}")

for failure in failures:
    print("FAIL:", failure)
print(f"{'failed' if failures else 'passed'}: progress lines")
sys.exit(1 if failures else 0)
