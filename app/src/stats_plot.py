# flag-sim plot: a run's statistics over time (embedded in the binary, run with
# /usr/bin/python3 - OUT.h5 PNG). Three panels sharing the time axis: link
# strain (max and mean, %), kinetic energy (J), and wall time per frame (ms)
# with its largest stages. Frames where the infill did not reach its
# tolerance are marked on the strain panel.
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

h5_path, png_path = sys.argv[1], sys.argv[2]
with h5py.File(h5_path, "r") as f:
    t = f["frames/time"][...]
    T, J, K = f["frames/positions"].shape[:3]
    stats = f["stats"]
    max_strain = stats["max_strain"][:T] * 100
    mean_strain = stats["mean_strain"][:T] * 100
    energy = stats["kinetic_energy"][:T] if "kinetic_energy" in stats else None
    wall_ms = stats["wall_seconds"][:T] * 1e3
    stage_ms = stats["stage_seconds"][:T] * 1e3 if "stage_seconds" in stats else None
    stages = list(stats["stage_seconds"].attrs.get("stages", [])) if stage_ms is not None else []
    converged = stats["infill_converged"][:T] if "infill_converged" in stats else None
    mode, status = str(f.attrs.get("mode", "?")), str(f.attrs.get("status", "?"))

fig, (ax_strain, ax_energy, ax_time) = plt.subplots(3, 1, figsize=(9, 8), dpi=100, sharex=True)
ax_strain.plot(t, max_strain, color="tab:red", label="max link strain")
ax_strain.plot(t, mean_strain, color="tab:orange", label="mean link strain")
if converged is not None and np.any(converged == 0):
    bad = converged == 0
    ax_strain.scatter(t[bad], max_strain[bad], color="black", marker="x", zorder=3,
                      label=f"infill not converged ({int(bad.sum())} frames)")
ax_strain.set_ylabel("strain (%)")
ax_strain.legend(loc="upper right", fontsize=8)
ax_strain.grid(alpha=0.3)

if energy is not None:
    ax_energy.plot(t, energy, color="tab:green")
ax_energy.set_ylabel("kinetic energy (J)")
ax_energy.grid(alpha=0.3)

ax_time.plot(t, wall_ms, color="black", label="whole frame")
if stage_ms is not None and stage_ms.shape[1] == len(stages):
    # The stages that take the most time over the run, at most five.
    order = np.argsort(stage_ms.sum(axis=0))[::-1][:5]
    for i in order:
        if stage_ms[:, i].sum() > 0:
            ax_time.plot(t, stage_ms[:, i], linewidth=0.8, label=stages[i])
ax_time.set_ylabel("wall time per frame (ms)")
ax_time.set_xlabel("simulated time (s)")
ax_time.legend(loc="upper right", fontsize=8, ncol=2)
ax_time.grid(alpha=0.3)

fig.suptitle(f"{os.path.basename(h5_path)}: {mode}, {J} x {K} nodes, {T} frames "
             f"(t = {t[0]:.3g} .. {t[-1]:.3g} s), {status}", fontsize=10)
fig.tight_layout()
fig.savefig(png_path)
