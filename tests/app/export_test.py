#!/usr/bin/python3
"""`flag-sim export` (issue 15): the PC2 point cache read back byte by byte by
an independent reader written from the format's description (Blender's
Mesh Cache reads the same layout), the OBJ read by meshio (Debian's
python3-meshio, installed by scripts/setup.sh --test-deps), an OBJ per frame,
and bad requests refused with nothing left behind.

Usage: export_test.py FLAG_SIM"""
import os
import struct
import subprocess
import sys
import tempfile

import h5py
import numpy as np

try:
    import meshio
except ImportError:
    print("SKIPPED: meshio not found (install the test dependencies: scripts/setup.sh --test-deps)")
    sys.exit(77)

flag_sim = os.path.abspath(sys.argv[1])
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def flag_sim_run(args, cwd):
    return subprocess.run([flag_sim, *args], cwd=cwd, capture_output=True, text=True, timeout=300)


def read_pc2(path):
    """PC2: char[12] 'POINTCACHE2\\0', int32 version, int32 points, float32 start
    frame, float32 sample rate, int32 samples, then float32 xyz, little-endian."""
    with open(path, "rb") as f:
        data = f.read()
    signature, version, points, start, rate, samples = struct.unpack("<12siiffi", data[:32])
    body = np.frombuffer(data[32:], dtype="<f4")
    return signature, version, points, start, rate, samples, body


with tempfile.TemporaryDirectory() as tmp:
    J, K = 17, 25
    r = flag_sim_run(["run", "--quiet", "--frames", "5", "--set", f"flag.fine=[{J},{K}]",
                      "-o", "run.h5"], tmp)
    check(r.returncode == 0, f"run: {r.stderr}")
    with h5py.File(os.path.join(tmp, "run.h5"), "r") as f:
        x = f["frames/positions"][...]
    T = len(x)

    # A point cache of every frame, and its OBJ.
    r = flag_sim_run(["export", "run.h5", "-o", "blender/flag.pc2"], tmp)
    check(r.returncode == 0, f"export pc2: exit {r.returncode} {r.stderr}")
    check(sorted(os.listdir(os.path.join(tmp, "blender"))) == ["flag.obj", "flag.pc2"],
          f"export pc2 wrote {os.listdir(os.path.join(tmp, 'blender'))}")
    signature, version, points, start, rate, samples, body = read_pc2(
        os.path.join(tmp, "blender", "flag.pc2"))
    check(signature == b"POINTCACHE2\0", f"signature {signature}")
    check((version, points, start, rate, samples) == (1, J * K, 0.0, 1.0, T),
          f"header {(version, points, start, rate, samples)}")
    check(body.size == T * J * K * 3, f"{body.size} floats after the header")
    if body.size == T * J * K * 3:
        check(np.array_equal(body.reshape(T, J, K, 3), x), "the samples are the file's frames")

    mesh = meshio.read(os.path.join(tmp, "blender", "flag.obj"))
    check(np.array_equal(mesh.points.astype(np.float32), x[0].reshape(-1, 3)),
          "the OBJ's vertices are frame 0")
    quads = [c.data for c in mesh.cells if c.type == "quad"]
    check(len(quads) == 1 and quads[0].shape == ((J - 1) * (K - 1), 4), "one quad per cell")
    if quads:
        q = quads[0]
        check(q[0].tolist() == [0, K, K + 1, 1], f"first quad {q[0].tolist()}")
        # Counter-clockwise about the vertex normals: each quad's area vector along them.
        p = mesh.points
        area = np.cross(p[q[:, 2]] - p[q[:, 0]], p[q[:, 3]] - p[q[:, 1]])
        normals = mesh.point_data["obj:vn"]
        check(np.all((area * normals[q[:, 0]]).sum(axis=1) > 0), "quads wind about the normals")
        check(np.allclose(np.linalg.norm(normals, axis=1), 1, atol=1e-5), "unit normals")
    uv = mesh.point_data["obj:vt"].reshape(J, K, -1)
    check(np.allclose(uv[0, 0, :2], [0, 1]) and np.allclose(uv[-1, -1, :2], [1, 0]),
          "UVs: (0, 1) at the pole's top, (1, 0) at the bottom fly corner")

    # One OBJ per frame of a range, numbered as in the file.
    r = flag_sim_run(["export", "run.h5", "-o", "objs/", "--frames", "2:4"], tmp)
    check(r.returncode == 0, f"export dir: {r.stderr}")
    names = sorted(os.listdir(os.path.join(tmp, "objs")))
    check(names == ["frame_00002.obj", "frame_00003.obj"], f"per-frame OBJs {names}")
    if names:
        frame3 = meshio.read(os.path.join(tmp, "objs", "frame_00003.obj"))
        check(np.array_equal(frame3.points.astype(np.float32), x[3].reshape(-1, 3)),
              "frame_00003.obj holds frame 3")

    # Refused, exit 2, one error line, nothing created.
    for args, words in ((["-o", "out.abc"], "expected NAME.pc2"),
                        (["-o", "run.pc2", "--frames", "9:"], "has frames 0 to 4"),
                        (["-o", "new/dir/run.pc2", "--frames", "3:2"], "the range is empty"),
                        (["-o", "run.xdmf"], "expected NAME.pc2"),
                        (["-o", "copy.pc2", "--frames", "x"], "expected N (one frame; -1 the last) or A:B")):
        before = sorted(os.listdir(tmp))
        r = flag_sim_run(["export", "run.h5", *args], tmp)
        check(r.returncode == 2, f"export {args}: exit {r.returncode}")
        check(r.stderr.startswith("error: ") and r.stderr.count("\n") == 1 and words in r.stderr,
              f"export {args}: {r.stderr!r}")
        check(sorted(os.listdir(tmp)) == before, f"export {args} left {set(os.listdir(tmp)) - set(before)}")
    # The input is never an output, however spelt: an OBJ named as the run's own file.
    os.symlink("run.h5", os.path.join(tmp, "alias.obj"))
    r = flag_sim_run(["export", "run.h5", "-o", "alias.obj"], tmp)
    check(r.returncode == 2 and "would overwrite the input" in r.stderr, f"export onto its input: {r.stderr}")
    with h5py.File(os.path.join(tmp, "run.h5"), "r") as f:
        check(np.array_equal(f["frames/positions"][...], x), "the input is untouched")

for failure in failures:
    print("FAIL:", failure)
print(f"{'failed' if failures else 'passed'}: export")
sys.exit(1 if failures else 0)
