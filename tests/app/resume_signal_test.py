#!/usr/bin/python3
"""run --resume after a signal (issue 30, item 4): a run stopped by SIGINT mid-way,
and one killed by SIGKILL (its .partial renamed), continue to frames equal, bit for
bit, to those of a run that was never stopped."""
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
# 33 x 49 from 9 x 13: about a millisecond a frame, so 1200 frames run for seconds.
SCENE = ["--set", "flag.fine=[33,49]", "--set", "scene.duration=40", "--set", "output.flush_every=7"]


def check(condition, what):
    if not condition:
        failures.append(what)


def contents(path):
    """Every dataset but the wall times and ParaView's views, by name."""
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and not name.startswith("xdmf") and name not in (
                    "stats/stage_seconds", "stats/wall_seconds"):
                out[name] = obj[()]
        f.visititems(visit)
        out["checkpoint frame"] = f["checkpoint"].attrs["frame"]
        out["scene"] = f.attrs["scene"]
    return out


def same(a, b):
    if a.keys() != b.keys():
        return f"datasets differ: {sorted(a.keys() ^ b.keys())}"
    for name in a:
        if not np.array_equal(a[name], b[name]):
            return f"{name} differs"
    return None


def wait_for_growth(path, size, timeout=60):
    deadline = time.time() + timeout
    while time.time() < deadline:
        if os.path.exists(path) and os.path.getsize(path) > size:
            return True
        time.sleep(0.05)
    return False


def stop(out, sig):
    proc = subprocess.Popen([flag_sim, "run", "-o", out, "--quiet", *SCENE],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    check(wait_for_growth(out + ".partial", 3_000_000), f"{sig.name}: the run never wrote frames")
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    return proc.returncode, err


def resume(path, cwd):
    return subprocess.run([flag_sim, "run", "--resume", path, "--quiet"], cwd=cwd,
                          capture_output=True, text=True, timeout=300)


with tempfile.TemporaryDirectory() as tmp:
    whole = os.path.join(tmp, "whole.h5")
    done = subprocess.run([flag_sim, "run", "-o", whole, "--quiet", *SCENE], capture_output=True,
                          text=True, timeout=300)
    check(done.returncode == 0, f"the uninterrupted run: {done.stderr}")
    reference = contents(whole)

    # SIGINT: the run ends the file as interrupted; resume continues it in place.
    stopped = os.path.join(tmp, "stopped.h5")
    code, err = stop(stopped, signal.SIGINT)
    check(code == 130, f"SIGINT: exit {code}: {err}")
    with h5py.File(stopped, "r") as f:
        frames = f["frames/time"].shape[0]
        check(f.attrs["status"] == "interrupted", "SIGINT: status")
        check(0 < frames < 1201, f"SIGINT: {frames} frames")
    result = resume(stopped, tmp)
    check(result.returncode == 0, f"SIGINT: resume exit {result.returncode}: {result.stderr}")
    check(result.stdout.startswith("complete: 1201 frames"), f"SIGINT: resume said {result.stdout}")
    why = same(reference, contents(stopped))
    check(why is None, f"SIGINT: the continued run: {why}")
    check(not os.path.exists(stopped + ".partial"), "SIGINT: resume left its .partial")

    # SIGKILL: the .partial holds the frames and checkpoint of the last flush.
    killed = os.path.join(tmp, "killed.h5")
    code, err = stop(killed, signal.SIGKILL)
    check(code == -signal.SIGKILL, f"SIGKILL: exit {code}")
    result = resume(killed + ".partial", tmp)
    check(result.returncode == 2 and "rename it to" in result.stderr,
          f"SIGKILL: resuming the .partial itself: exit {result.returncode}: {result.stderr}")
    os.rename(killed + ".partial", killed)
    with h5py.File(killed, "r") as f:
        check(f.attrs["status"] == "running", "SIGKILL: status")
        check(f["checkpoint"].attrs["written_frames"] <= f["frames/time"].shape[0],
              "SIGKILL: the checkpoint is past the frames")
    result = resume(killed, tmp)
    check(result.returncode == 0, f"SIGKILL: resume exit {result.returncode}: {result.stderr}")
    why = same(reference, contents(killed))
    check(why is None, f"SIGKILL: the continued run: {why}")

    # A checkpoint changed after it was written: run --resume refuses it (its
    # checksum), info still reads the file and says why it cannot be continued.
    changed = os.path.join(tmp, "changed.h5")
    os.rename(whole, changed)
    with h5py.File(changed, "r+") as f:
        f["checkpoint/physics_time"][0] += 1e-12
    result = resume(changed, tmp)
    check(result.returncode == 2 and result.stderr.startswith("error: ") and
          "/checkpoint/physics_time is damaged (its checksum)" in result.stderr,
          f"changed checkpoint: resume exit {result.returncode}: {result.stderr}")
    check(not os.path.exists(changed + ".partial"), "changed checkpoint: a .partial was left")
    info = subprocess.run([flag_sim, "info", changed], capture_output=True, text=True, timeout=60)
    check(info.returncode == 0 and "resume    not possible: " in info.stdout and
          "(its checksum)" in info.stdout, f"changed checkpoint: info said {info.stdout}{info.stderr}")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("ok")
