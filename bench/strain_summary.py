"""Shared by the bench scripts: the 99th-percentile link strain of a flag-sim
output file, over every row and column link of every frame."""
import h5py
import numpy as np


def p99_strain(path):
    with h5py.File(path, "r") as f:
        p = f["frames/positions"][...].astype(np.float64)
        rest = f["lattice/rest_positions"][...].astype(np.float64)
    sx = np.linalg.norm(rest[0, 1] - rest[0, 0])
    sy = np.linalg.norm(rest[1, 0] - rest[0, 0])
    row = np.abs(np.linalg.norm(np.diff(p, axis=2), axis=-1) - sx) / sx
    col = np.abs(np.linalg.norm(np.diff(p, axis=1), axis=-1) - sy) / sy
    return float(np.percentile(np.concatenate([row.ravel(), col.ravel()]), 99))
