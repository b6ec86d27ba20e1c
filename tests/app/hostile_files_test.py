#!/usr/bin/python3
"""Hostile output files (issue 13): `info` and `render` on files whose declared
shapes, attributes or stages lie are exit 2 with one `error:` line, read only
what the file holds (run under a 1 GiB address-space limit: a file declaring
[1, 2^31, 1, 3] positions once made render allocate 3.5 GB), and create nothing."""
import os
import resource
import shutil
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


def limited():
    # ASan's shadow memory needs a far larger address space: no limit under it.
    if "ASAN_OPTIONS" not in os.environ:
        resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))


def flag_sim_run(args, cwd):
    return subprocess.run([flag_sim, *args], cwd=cwd, capture_output=True, text=True, timeout=120,
                          preexec_fn=limited)


def expect_refused(args, cwd, words, what):
    before = sorted(os.listdir(cwd))
    r = flag_sim_run(args, cwd)
    check(r.returncode == 2, f"{what}: exit {r.returncode}, expected 2\n{r.stderr}")
    check(r.stderr.startswith("error: ") and r.stderr.count("\n") == 1,
          f"{what}: not one error line\n{r.stderr}")
    check(words in r.stderr, f"{what}: '{words}' not in\n{r.stderr}")
    check(sorted(os.listdir(cwd)) == before, f"{what}: left {set(os.listdir(cwd)) - set(before)}")


def variant(tmp, name, edit):
    path = os.path.join(tmp, name)
    shutil.copy(os.path.join(tmp, "good.h5"), path)
    with h5py.File(path, "r+") as f:
        edit(f)
    return name


def replace(f, name, **kwargs):
    del f[name]
    f.create_dataset(name, **kwargs)


with tempfile.TemporaryDirectory() as tmp:
    r = subprocess.run([flag_sim, "run", "-o", "good.h5", "--quiet", "--frames", "3", "--set",
                        "flag.fine=[17,25]", "--set", "flag.coarse=[5,7]"],
                       cwd=tmp, capture_output=True, text=True)
    check(r.returncode == 0, f"the good run failed: {r.stderr}")
    cases = [
        (variant(tmp, "huge.h5", lambda f: replace(
            f, "/frames/positions", shape=(1, 2**31, 1, 3), dtype="f4", chunks=(1, 1024, 1, 3))),
         "declares 1 frames of 2147483648 x 1 nodes, more than a flag-sim scene can make"),
        (variant(tmp, "truncated.h5", lambda f: replace(
            f, "/frames/positions", shape=(3, 17, 25, 3), dtype="f4", chunks=(1, 17, 25, 3))),
         "declares 3 frames of 17 x 25 nodes (15300 bytes) but stores 0"),
        (variant(tmp, "rank.h5", lambda f: replace(
            f, "/frames/positions", shape=(3, 17, 25), dtype="f4")),
         "/frames/positions is not [T, J, K, 3]"),
        (variant(tmp, "stat.h5", lambda f: replace(
            f, "/stats/max_strain", shape=(2**40,), dtype="f4", chunks=(1024,))),
         "/stats/max_strain declares more than the 3 values"),
        (variant(tmp, "stages.h5", lambda f: f["/stats/stage_seconds"].attrs.__setitem__(
            "stages", np.array([b"a"] * 40, dtype=h5py.string_dtype()))),
         "columns but its attribute `stages` names 40"),
        (variant(tmp, "format.h5", lambda f: f.attrs.__setitem__("format", "other/1")),
         "not a flag-sim output"),
    ]
    with open(os.path.join(tmp, "text.h5"), "w") as f:
        f.write("not HDF5\n")
    cases.append(("text.h5", "not an HDF5 file"))
    for name, words in cases:
        expect_refused(["info", name], tmp, words, f"info {name}")
        if name not in ("stages.h5", "stat.h5"):  # render reads no /stats
            expect_refused(["render", name, "-o", "new/out.mp4", "--size", "64x64"], tmp, words,
                           f"render {name}")

    # A frame rate no video can have is bad input, not an ffmpeg failure (exit 4). A video's
    # rate comes from the frames' times; only where those say nothing (all equal) from the
    # `fps` attribute.
    def lying_rate(f, fps):
        f.attrs["fps"] = fps
        f["/frames/time"][...] = 0.0

    for fps in (0.0, float("nan"), -5.0, 1e9):
        name = variant(tmp, f"fps{fps}.h5", lambda f: lying_rate(f, fps))
        expect_refused(["render", name, "-o", "new/out.mp4", "--size", "64x64"], tmp,
                       "frames per second", f"render fps {fps}")
    # PNG frames need no frame rate: the same file renders.
    r = flag_sim_run(["render", "fps0.0.h5", "-o", "pngs", "--size", "64x64"], tmp)
    check(r.returncode == 0 and len(os.listdir(os.path.join(tmp, "pngs"))) == 3,
          f"PNG render of an fps 0 file: {r.returncode} {r.stderr}")

    # The good file still reads, under the same memory limit.
    r = flag_sim_run(["info", "good.h5"], tmp)
    check(r.returncode == 0, f"info good.h5: {r.returncode} {r.stderr}")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"ok: {len(cases)} hostile files x info/render, 4 frame rates")
