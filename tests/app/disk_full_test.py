#!/usr/bin/python3
"""Disk full mid-run, as a file size limit (RLIMIT_FSIZE) makes it: the run
stops before HDF5 can run out of room half-way through a flush, exits 4 with
one error line, and every frame written is kept in a file h5py opens."""
import os
import resource
import signal
import subprocess
import sys
import tempfile

import h5py
import numpy as np

flag_sim = sys.argv[1]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def limited(size):
    def apply():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails, no signal
        resource.setrlimit(resource.RLIMIT_FSIZE, (size, size))
    return apply


with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "run.h5")
    run = subprocess.run([flag_sim, "run", "--mode", "mass-spring", "--set", "flag.fine=[17,25]",
                          "--frames", "300", "--set", "output.flush_every=5", "-o", out, "--quiet"],
                         preexec_fn=limited(1_400_000), capture_output=True, text=True)
    check(run.returncode == 4, f"exit {run.returncode}: {run.stderr}")
    check(run.stderr.startswith("error: ") and run.stderr.count("\n") == 1, f"stderr: {run.stderr!r}")
    check("no room for more frames" in run.stderr, f"message: {run.stderr}")
    check(os.path.exists(out), "the output file is kept under its name")
    if os.path.exists(out):
        with h5py.File(out, "r") as f:
            frames = f["frames/positions"].shape[0]
            check(0 < frames < 300, f"frames kept: {frames}")
            check(f.attrs["status"] == "interrupted", f"status {f.attrs['status']}")
            check("no room" in f.attrs["status_reason"], "status_reason")
            check(np.all(np.isfinite(f["frames/positions"][...])), "finite positions")
            check(f["stats/max_strain"].shape == (frames,), "stats as long as the frames")

for failure in failures:
    print("FAILED:", failure)
print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
sys.exit(1 if failures else 0)
