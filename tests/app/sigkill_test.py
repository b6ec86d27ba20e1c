#!/usr/bin/python3
"""Faults: SIGKILL leaves a .partial file that h5py opens with every frame up to
the last flush; SIGINT and SIGTERM finish the frame, exit 130, status interrupted."""
import os
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

flag_sim = sys.argv[1]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def start(out, flush_every):
    # A long run on a small lattice: frames come quickly, the run would last minutes.
    return subprocess.Popen(
        [flag_sim, "run", "-o", out, "--quiet", "--set", "flag.fine=[9,13]", "--set", "scene.duration=1000",
         "--set", f"output.flush_every={flush_every}"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def interrupt(proc):
    """SIGINT to a running flag-sim; its stderr and the seconds it took to exit."""
    sent = time.time()
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    return err, time.time() - sent


def wait_for_growth(path, size, timeout=60):
    deadline = time.time() + timeout
    while time.time() < deadline:
        if os.path.exists(path) and os.path.getsize(path) > size:
            return True
        time.sleep(0.05)
    return False


with tempfile.TemporaryDirectory() as tmp:
    # SIGKILL: no chance to clean up; the flushed frames must survive.
    out = os.path.join(tmp, "killed.h5")
    proc = start(out, 1)
    check(wait_for_growth(out + ".partial", 60_000), "the run never wrote frames")
    time.sleep(0.5)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    check(not os.path.exists(out), "a killed run must not look finished")
    with h5py.File(out + ".partial", "r") as f:
        frames = f["frames/positions"].shape[0]
        check(frames >= 2, f"only {frames} frames survived")
        check(f.attrs["status"] == "running", "status of a killed run")
        check(f["frames/time"].shape[0] >= frames - 1, "time series as long as the frames")
        check(np.all(np.isfinite(f["frames/positions"][: frames - 1])), "flushed frames readable")
        print(f"SIGKILL: {frames} frames readable")

    for sig in (signal.SIGINT, signal.SIGTERM):
        out = os.path.join(tmp, f"{sig.name}.h5")
        proc = start(out, 5)
        check(wait_for_growth(out + ".partial", 60_000), f"{sig.name}: no frames")
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=60)
        check(proc.returncode == 130, f"{sig.name}: exit {proc.returncode} {err}")
        check(os.path.exists(out) and not os.path.exists(out + ".partial"), f"{sig.name}: file renamed")
        with h5py.File(out, "r") as f:
            check(f.attrs["status"] == "interrupted", f"{sig.name}: status {f.attrs['status']}")
            n = f["frames/positions"].shape[0]
            check(n >= 1 and f["frames/time"].shape[0] == n, f"{sig.name}: frames {n}")
            check(np.all(np.isfinite(f["frames/positions"][...])), f"{sig.name}: finite frames")

    # A signal inside a long frame (mass-spring on 129 x 193: seconds a frame)
    # takes effect at the next substep: the run stops in well under a second,
    # keeps the frames before, and does not write the one it was making.
    out = os.path.join(tmp, "long.h5")
    proc = subprocess.Popen(
        [flag_sim, "run", "-o", out, "--quiet", "--mode", "mass-spring", "--frames", "50",
         "--set", "output.flush_every=1"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    check(wait_for_growth(out + ".partial", 500_000), "long frames: frame 0 never written")
    time.sleep(1.0)  # inside frame 1
    err, took = interrupt(proc)
    check(proc.returncode == 130, f"long frame: exit {proc.returncode} {err}")
    check(took < 2.0, f"long frame: the signal took {took:.2f} s to stop the run")
    with h5py.File(out, "r") as f:
        check(f.attrs["status"] == "interrupted", f"long frame: status {f.attrs['status']}")
        check("not written" in f.attrs["status_reason"], f"long frame: {f.attrs['status_reason']}")
        n = f["frames/positions"].shape[0]
        check(n >= 1, f"long frame: {n} frames kept")
        check(np.all(np.isfinite(f["frames/positions"][...])), "long frame: finite frames")
    print(f"SIGINT inside a frame: stopped in {took:.2f} s")

    # A signal while `run --render` draws: the render stops, the run's file is kept, exit 130.
    out = os.path.join(tmp, "drawn.h5")
    frames_dir = os.path.join(tmp, "drawn_frames")
    proc = subprocess.Popen(
        [flag_sim, "run", "-o", out, "--quiet", "--set", "flag.fine=[17,25]", "--frames", "600",
         "--render", frames_dir, "--size", "1280x720"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 60
    while time.time() < deadline and (not os.path.isdir(frames_dir) or len(os.listdir(frames_dir)) < 3):
        time.sleep(0.05)
    err, took = interrupt(proc)
    check(proc.returncode == 130, f"render: exit {proc.returncode} {err}")
    check(took < 2.0, f"render: the signal took {took:.2f} s")
    check(len(os.listdir(frames_dir)) < 600, "render: every frame was drawn anyway")
    check(err.startswith("interrupted: rendering"), f"render: {err}")
    with h5py.File(out, "r") as f:
        check(f.attrs["status"] == "complete", "render: the run's file is kept whole")
        check(f["frames/positions"].shape[0] == 600, "render: the run's frames")
    print(f"SIGINT during run --render: stopped in {took:.2f} s")

for failure in failures:
    print("FAILED:", failure)
print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
sys.exit(1 if failures else 0)
