# flag-sim sweep --plot: error against cost, log axes (embedded in the binary,
# run with /usr/bin/python3 - CSV PNG).
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

csv_path, png_path = sys.argv[1], sys.argv[2]
rows = list(csv.DictReader(open(csv_path)))
error_key = "mean_shape_rms_m"


def value(row, key):
    try:
        return float(row[key])
    except (KeyError, ValueError):
        return None


fig, ax = plt.subplots(figsize=(8, 5.5), dpi=100)
hybrid = [r for r in rows if r["mode"] == "hybrid" and value(r, error_key)]
points = sorted(((value(r, "ms_per_frame"), value(r, error_key), r) for r in hybrid),
                key=lambda p: p[0])
ax.scatter([p[0] for p in points], [1e3 * p[1] for p in points], color="tab:blue", zorder=3,
           label="hybrid")
for ms, err, r in points:
    label = f"{r['coarse']} s{r['substeps']} r{r['relax_iterations']}"
    ax.annotate(label, (ms, 1e3 * err), textcoords="offset points", xytext=(4, 4), fontsize=7)
front, best = [], float("inf")
for ms, err, _ in points:  # cheapest first: a point is on the front if nothing cheaper beats it
    if err < best:
        front.append((ms, err))
        best = err
if front:
    ax.plot([p[0] for p in front], [1e3 * p[1] for p in front], color="tab:blue", alpha=0.5,
            drawstyle="steps-post", label="Pareto front")
for r in rows:
    if r["mode"] == "bullet" and value(r, error_key):
        ax.scatter([value(r, "ms_per_frame")], [1e3 * value(r, error_key)], marker="s",
                   color="tab:red", zorder=3, label="Bullet, full lattice")
    if r["mode"] == "mass-spring":
        ax.axvline(value(r, "ms_per_frame"), color="k", linestyle="--",
                   label="mass-spring reference (error 0)")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("ms per output frame (one core)")
ax.set_ylabel("mean-shape RMS error vs mass-spring, mm")
fine = rows[0]["fine"] if rows else "?"
ax.set_title(f"What accuracy costs: {fine} dense lattice")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(png_path)
