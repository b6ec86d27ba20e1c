"""Per-stage medians of a flag-sim run, from its /stats: the cost scripts' one reading of a file.

stages(path) -> {stage name: median ms over frames 1.., ..., "whole": median ms of the frame}
show(label, row) prints one such row on a line.
"""
import h5py
import numpy as np


def stages(path):
    with h5py.File(path, "r") as f:
        s = f["/stats/stage_seconds"]
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in s.attrs["stages"]]
        row = {n: 1e3 * float(np.median(s[1:, i])) for i, n in enumerate(names)}
        row["whole"] = 1e3 * float(np.median(f["/stats/wall_seconds"][1:]))
    return row


def show(label, row):
    parts = "  ".join(f"{k} {v:.2f}" for k, v in row.items())
    print(f"{label:<14} {parts}")
