#!/usr/bin/python3
"""ParaView opens flag-sim's XDMF sidecar with its default reader (issue 15):
every time step with all its points, the last step's points equal to the HDF5
file's, and the per-node fields `velocity` and `strain` as point arrays, from
another working directory, by relative and by absolute path; and a screenshot
from a headless pvpython on an Xvfb display, as README says to take one. Runs the real
pvpython (Debian's python3-paraview, installed by scripts/setup.sh
--test-deps); without it the test is skipped (exit 77), saying why.

Usage: paraview_test.py FLAG_SIM"""
import ctypes
import ctypes.util
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

flag_sim = sys.argv[1]
reader_script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "paraview_reader.py")
pvpython = shutil.which("pvpython")
if pvpython is None:
    print("SKIPPED: pvpython not found (install the test dependencies: scripts/setup.sh --test-deps)")
    sys.exit(77)
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def paraview_sees(xdmf, cwd, reader="default"):
    r = subprocess.run([pvpython, "--force-offscreen-rendering", reader_script, xdmf, reader],
                       cwd=cwd, capture_output=True, text=True, timeout=300)
    check(r.returncode == 0, f"pvpython on {xdmf} from {cwd}: exit {r.returncode}\n{r.stderr[-2000:]}")
    check("Skipping unrecognized" not in r.stderr, f"{xdmf}: the reader skipped arrays\n{r.stderr}")
    lines = r.stdout.strip().splitlines()
    return json.loads(lines[-1]) if r.returncode == 0 and lines else None


def x_display_answers(display, width, height):
    """Whether an X client can open `display` and finds a screen of width x
    height there (the size this test gave its own server, so that a server of
    someone else's on the same display number is not taken for it)."""
    x11 = ctypes.CDLL(ctypes.util.find_library("X11") or "libX11.so.6")
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XDisplayWidth.argtypes = x11.XDisplayHeight.argtypes = [ctypes.c_void_p, ctypes.c_int]
    x11.XDefaultScreen.argtypes = x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    dpy = x11.XOpenDisplay(display.encode())
    if not dpy:
        return False
    screen = x11.XDefaultScreen(dpy)
    size = (x11.XDisplayWidth(dpy, screen), x11.XDisplayHeight(dpy, screen))
    x11.XCloseDisplay(dpy)
    return size == (width, height)


def start_xvfb(tmp):
    """Starts an Xvfb of this test's own, without access control (-ac: no
    cookie to pass on) and listening on no TCP port, on a display number that
    depends on the process id, trying others when one is taken. Returns
    (process, display, None) once a client reaches it, or (None, None, what
    went wrong)."""
    xvfb = shutil.which("Xvfb")
    if xvfb is None:
        return None, None, "Xvfb not found (scripts/setup.sh --test-deps installs xvfb)"
    width, height = 1280, 1000 + os.getpid() % 24
    log_path = os.path.join(tmp, "xvfb.log")
    tried = []
    for attempt in range(8):
        number = 100 + (os.getpid() * 7 + attempt * 131) % 800
        display = f":{number}"
        with open(log_path, "w") as log:
            proc = subprocess.Popen([xvfb, display, "-screen", "0", f"{width}x{height}x24",
                                     "-nolisten", "tcp", "-ac", "-noreset"],
                                    stdout=log, stderr=subprocess.STDOUT)
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and proc.poll() is None:
            if x_display_answers(display, width, height):
                # A server that lost the display to another exits at once:
                # the one that answered must be this one, still running.
                time.sleep(1.0)
                if proc.poll() is None and x_display_answers(display, width, height):
                    return proc, display, None
            time.sleep(0.2)
        if proc.poll() is None:
            proc.terminate()
            proc.wait(timeout=30)
        with open(log_path) as log:
            said = log.read().strip().splitlines()
        tried.append(f"{display}: exit {proc.returncode}, {said[-1] if said else 'nothing said'}")
    return None, None, "Xvfb did not answer on any display tried: " + "; ".join(tried)


with tempfile.TemporaryDirectory() as tmp:
    results = os.path.join(tmp, "results")
    J, K = 17, 25
    run = subprocess.run([flag_sim, "run", "--quiet", "--frames", "6", "--set", f"flag.fine=[{J},{K}]",
                          "--set", "flag.coarse=[5,7]", "--set", "output.every=2",
                          "-o", os.path.join(results, "flag.h5")],
                         capture_output=True, text=True, timeout=300)
    check(run.returncode == 0, f"run failed: {run.stderr}")
    with h5py.File(os.path.join(results, "flag.h5"), "r") as f:
        times = f["frames/time"][...]
        last = {"positions": f["frames/positions"][-1].reshape(-1, 3),
                "velocity": f["frames/velocity"][-1].reshape(-1, 3),
                "strain": f["frames/strain"][-1].reshape(-1)}
    T = len(times)
    check(T == 3, f"{T} frames written, expected 3 (6 frames, every 2)")
    check(np.abs(last["velocity"]).max() > 0 and last["strain"].max() > 0,
          "the last frame moves and strains: the arrays below compare something")
    # From the directory above, relative; from /, absolute; and ParaView's legacy
    # reader (XDMFReader), which Open With... offers.
    for xdmf, cwd, reader in (("results/flag.xdmf", tmp, "default"),
                              (os.path.join(results, "flag.xdmf"), "/", "default"),
                              (os.path.join(results, "flag.xdmf"), "/", "XDMFReader")):
        seen = paraview_sees(xdmf, cwd, reader)
        if seen is None:
            continue
        what = f"{reader} reader on {xdmf} from {cwd}"
        if reader == "default":
            check(seen["reader"] == "Xdmf3ReaderS", f"{what}: default reader is {seen['reader']}")
        check(np.allclose(seen["steps"], times), f"{what}: time steps {seen['steps']} vs {list(times)}")
        check(seen["points_per_step"] == [J * K] * T, f"{what}: points per step {seen['points_per_step']}")
        check(np.array_equal(np.array(seen["last_points"], dtype=np.float32), last["positions"]),
              f"{what}: the last step's points differ from /frames/positions")
        # The legacy reader (xdmf2) selects outside a [J, K, 3] attribute's extent
        # (HDF5: "selection + offset not within extent"): its vectors are not read.
        for name in ("velocity", "strain") if reader == "default" else ("strain",):
            check(name in seen["arrays"], f"{what}: no point array {name}: {list(seen['arrays'])}")
            if name in seen["arrays"]:
                got = np.array(seen["arrays"][name], dtype=np.float32).reshape(last[name].shape)
                check(np.array_equal(got, last[name]), f"{what}: point array {name} differs")
    # A picture from a headless pvpython: Debian's ParaView draws through X, so
    # SaveScreenshot needs a display (without one it dies in XSync, also with
    # --force-offscreen-rendering); README says to run it under xvfb-run. The
    # test starts its own Xvfb instead (see start_xvfb) so that it can tell an
    # X server that did not come up from ParaView failing to draw.
    shot = os.path.join(tmp, "shot.png")
    script = os.path.join(tmp, "shot.py")
    with open(script, "w") as f:
        f.write("from paraview.simple import *\n"
                f"Show(OpenDataFile({os.path.join(results, 'flag.xdmf')!r}))\n"
                f"Render()\nSaveScreenshot({shot!r}, ImageResolution=[320, 180])\n")
    xvfb, display, why = start_xvfb(tmp)
    check(xvfb is not None, f"no X display for the screenshot: {why}")
    if xvfb is not None:
        env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "XAUTHORITY")}
        env["DISPLAY"] = display
        try:
            r = subprocess.run([pvpython, script], capture_output=True, text=True, timeout=300, env=env)
        finally:
            xvfb.terminate()
            xvfb.wait(timeout=30)
        said = [line for line in r.stderr.splitlines() if "ERR|" in line or "error" in line.lower()]
        check(r.returncode == 0 and os.path.exists(shot) and os.path.getsize(shot) > 1000,
              f"pvpython SaveScreenshot on {display}: exit {r.returncode}\n" + "\n".join(said[:10]))

for failure in failures:
    print("FAIL:", failure)
print(f"{'failed' if failures else 'passed'}: ParaView reads the sidecar")
sys.exit(1 if failures else 0)
