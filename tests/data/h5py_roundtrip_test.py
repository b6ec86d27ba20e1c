#!/usr/bin/python3
"""The output file as h5py (Debian's /usr/bin/python3) sees it: every contract
path with its dtype and shape, the attributes, and a foreign HDF5 file refused."""
import os
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


with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "run.h5")
    run = subprocess.run([flag_sim, "run", "--frames", "5", "--set", "flag.fine=[17,25]", "-o", out,
                          "--quiet"], capture_output=True, text=True)
    check(run.returncode == 0, f"run failed: {run.stderr}")
    with h5py.File(out, "r") as f:
        attrs = f.attrs
        check(attrs["format"] == "flag-sim/1", "format")
        check(attrs["status"] == "complete", "status")
        check(attrs["mode"] == "hybrid", "mode")
        check(attrs["effects"] == "stretch,gravity,wind,damping,infill", f"effects {attrs['effects']}")
        check("[flag]" in attrs["scene"] and "fine = [ 17, 25 ]" in attrs["scene"], "scene text")
        check(int(attrs["seed"]) == 1, "seed")
        check(isinstance(attrs["version"], str), "version")
        check(attrs["status_reason"].startswith("all 5 frames simulated"),
              f"a complete file says why it ended: {attrs.get('status_reason')}")
        check(isinstance(attrs["substeps_per_frame"], np.integer),
              f"substeps_per_frame is a count: {type(attrs['substeps_per_frame'])}")
        for name, unit in (("substep_seconds", "s"), ("substeps_per_frame", "1"),
                           ("stable_substep_seconds", "s"), ("fps", "1/s"), ("seed", "1")):
            check(attrs.get(name + ".units") == unit, f"{name}.units = {attrs.get(name + '.units')}")
        numeric = [n for n, v in attrs.items() if isinstance(v, (np.number, int, float))]
        check(all(n + ".units" in attrs for n in numeric),
              f"numeric attributes without units: {[n for n in numeric if n + '.units' not in attrs]}")
        T, J, K = 5, 17, 25
        expect = {
            "coarse/positions": (np.float32, (T, 9, 13, 3)),
            "coarse/rows": (np.int32, (9,)),
            "coarse/cols": (np.int32, (13,)),
            "frames/time": (np.float64, (T,)),
            "frames/positions": (np.float32, (T, J, K, 3)),
            "frames/velocity": (np.float32, (T, J, K, 3)),
            "frames/strain": (np.float32, (T, J, K)),
            "lattice/rest_positions": (np.float32, (J, K, 3)),
            "stats/max_strain": (np.float32, (T,)),
            "stats/mean_strain": (np.float32, (T,)),
            "stats/wall_seconds": (np.float64, (T,)),
            "stats/infill_converged": (np.float64, (T,)),
            "stats/infill_residual": (np.float64, (T,)),
            "stats/infill_iterations": (np.float64, (T,)),
            "stats/coarse_offset": (np.float64, (T,)),
        }
        for path, (dtype, shape) in expect.items():
            check(path in f, f"missing {path}")
            if path in f:
                check(f[path].dtype == dtype, f"{path} dtype {f[path].dtype}")
                check(f[path].shape == shape, f"{path} shape {f[path].shape}")
        stages = list(f["stats/stage_seconds"].attrs["stages"])
        check(stages == ["stretch", "gravity", "wind", "integrate", "infill_3.1", "infill_3.3",
                         "infill_3.4", "checks", "output"], f"stages {stages}")
        check(f["stats/coarse_offset"].attrs["units"] == "m", "coarse_offset units")
        # Every dataset says its unit (contract: attr units on every dataset).
        units = {"frames/time": "s", "frames/positions": "m", "frames/velocity": "m/s",
                 "frames/strain": "1", "stats/max_strain": "1", "stats/stage_seconds": "s",
                 "stats/kinetic_energy": "J", "lattice/rest_positions": "m",
                 "coarse/positions": "m", "coarse/rows": "1"}
        for path, unit in units.items():
            check(f[path].attrs.get("units") == unit, f"{path} units {f[path].attrs.get('units')}")
        datasets = []
        f.visititems(lambda name, obj: datasets.append(name)
                     if isinstance(obj, h5py.Dataset) and not name.startswith("xdmf/") else None)
        check(all("units" in f[name].attrs for name in datasets),
              f"without units: {[n for n in datasets if 'units' not in f[n].attrs]}")
        # Per-node strain: each node's largest link |d - S| / S, from the positions themselves.
        x = f["frames/positions"][...].astype(np.float64)
        sx, sy = 1.5 / (K - 1), 1.0 / (J - 1)
        row = np.abs(np.linalg.norm(np.diff(x, axis=2), axis=-1) - sx) / sx  # [T, J, K-1]
        col = np.abs(np.linalg.norm(np.diff(x, axis=1), axis=-1) - sy) / sy  # [T, J-1, K]
        node = np.zeros((T, J, K))
        for a, b in ((row, (slice(None), slice(None), slice(0, -1))),
                     (row, (slice(None), slice(None), slice(1, None))),
                     (col, (slice(None), slice(0, -1), slice(None))),
                     (col, (slice(None), slice(1, None), slice(None)))):
            node[b] = np.maximum(node[b], a)
        # float32 positions: strains agree to about 1e-7 m / 6 cm
        check(np.allclose(f["frames/strain"][...], node, atol=2e-5),
              f"node strain off by {np.abs(f['frames/strain'][...] - node).max()}")
        check(np.isclose(f["frames/strain"][...].max(axis=(1, 2)), f["stats/max_strain"][...],
                         atol=1e-6).all(), "the largest node strain is /stats/max_strain")
        # Velocities: hybrid mode's dense nodes move by the frame differences.
        v = f["frames/velocity"][...]
        check(np.all(v[0] == 0), "frame 0 at rest")
        check(np.allclose(v[1:], np.diff(x, axis=0) * 30.0, atol=1e-4),
              f"velocity is the frame difference x fps: {np.abs(v[1:] - np.diff(x, axis=0) * 30).max()}")
        # The kinetic energy is the dense lattice's, from those velocities (one meaning in every
        # mode): lumped masses, areal density x cell area, halved on edges, quartered at corners.
        share = np.ones((J, K))
        share[[0, -1], :] *= 0.5
        share[:, [0, -1]] *= 0.5
        mass = 0.2 * sx * sy * share
        energy = 0.5 * (mass[None] * (v.astype(np.float64) ** 2).sum(axis=-1)).sum(axis=(1, 2))
        check(np.allclose(f["stats/kinetic_energy"][...], energy, rtol=1e-5, atol=1e-12),
              f"kinetic energy: {f['stats/kinetic_energy'][...]} vs {energy}")
        # One view of every frame of every field, for the XDMF sidecar, that reads as its frame.
        for field in ("positions", "velocity", "strain"):
            check(len(f["xdmf/" + field]) == T, f"xdmf views of {field}")
            for t in range(T):
                check(np.array_equal(f[f"xdmf/{field}/{t}"][...], f["frames/" + field][t]),
                      f"xdmf view of {field} in frame {t}")
        check(np.all(f["stats/infill_converged"][...] == 1), "the infill converged on every frame")
        # The dense counterpart of each coarse node is as far from it as the file says.
        dense = f["frames/positions"][...].astype(np.float64)[:, ::2, ::2]
        offset = np.linalg.norm(dense - f["coarse/positions"][...], axis=-1).max(axis=(1, 2))
        check(np.allclose(offset, f["stats/coarse_offset"][...], atol=1e-6), "coarse_offset")
        check(list(f["coarse/rows"][...]) == list(range(0, 17, 2)), "coarse rows")
        check(f["stats/stage_seconds"].shape == (T, len(stages)), "stage_seconds shape")
        rest = f["lattice/rest_positions"][...]
        check(np.allclose(rest[0, 0], [0, 2, 0]) and np.allclose(rest[J - 1, K - 1], [1.5, 1.0, 0]),
              "rest positions follow the contract")
        check(np.allclose(np.diff(f["frames/time"][...]), 1 / 30), "frame times")
        check(np.all(np.isfinite(f["frames/positions"][...])), "finite positions")
        check(np.allclose(f["frames/positions"][:, :, 0], rest[None, :, 0], atol=1e-6),
              "pole edge pinned at rest")
    check(os.path.exists(os.path.join(tmp, "run.xdmf")), "xdmf sidecar")

    # A file whose stage names outnumber its stage columns: one error line, exit 2.
    lying = os.path.join(tmp, "lying.h5")
    shutil.copy(os.path.join(tmp, "run.h5"), lying)
    with h5py.File(lying, "r+") as f:
        names = list(f["stats/stage_seconds"].attrs["stages"]) + ["extra_1", "extra_2"]
        f["stats/stage_seconds"].attrs["stages"] = names
    info = subprocess.run([flag_sim, "info", lying], capture_output=True, text=True)
    check(info.returncode == 2, f"lying stages exit {info.returncode}")
    check(info.stderr.startswith("error: ") and info.stderr.count("\n") == 1
          and "names 11" in info.stderr, f"lying stages message: {info.stderr}")

    foreign = os.path.join(tmp, "foreign.h5")
    with h5py.File(foreign, "w") as f:
        f["data"] = np.zeros(3)
    info = subprocess.run([flag_sim, "info", foreign], capture_output=True, text=True)
    check(info.returncode == 2, f"foreign file exit {info.returncode}")
    check(info.stderr.startswith("error: ") and "not a flag-sim output" in info.stderr,
          f"foreign message: {info.stderr}")

for failure in failures:
    print("FAILED:", failure)
print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
sys.exit(1 if failures else 0)
