# flag-sim sweep --plot: what accuracy costs (embedded in the binary, run with
# /usr/bin/python3 - CSV PNG [TITLE]). Left: mean-shape error against ms per
# frame, log axes, the Pareto front of the hybrid points, the references.
# Right: the strain the paper infill's relaxation cap buys (max link strain
# against the cap, one line per coarse lattice and substep count), the smooth
# infill's points beside it. A sweep with --seeds N has N rows a point: each
# point is drawn at its seeds' mean, with the seed-to-seed sd as an error bar.
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.transforms  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

csv_path, png_path = sys.argv[1], sys.argv[2]
title = sys.argv[3] if len(sys.argv) > 3 else ""
rows = list(csv.DictReader(open(csv_path)))
error_key = "mean_shape_rms_m"


def value(row, key):
    try:
        return float(row[key])
    except (KeyError, ValueError):
        return None


def over_seeds(rows):
    """One row a point: the mean over its seeds' rows, the error's sample sd in error_sd."""
    by_point = {}
    for r in rows:
        by_point.setdefault(r["point"], []).append(r)
    merged = []
    for group in by_point.values():
        r = dict(group[0])
        r["seeds"] = len(group)
        r["error_sd"] = 0.0
        for key in ("ms_per_frame", error_key, "max_strain"):
            values = [value(g, key) for g in group if value(g, key) is not None]
            if values:
                mean = sum(values) / len(values)
                r[key] = repr(mean)
                if key == error_key and len(values) > 1:
                    r["error_sd"] = (sum((v - mean) ** 2 for v in values) / (len(values) - 1)) ** 0.5
        merged.append(r)
    return merged


seeds = max([sum(1 for q in rows if q["point"] == r["point"]) for r in rows] or [1])
rows = over_seeds(rows)


def short_label(r):
    """coarse lattice, s = substeps per frame, r = the paper infill's relaxation cap."""
    label = f"{r['coarse']} s{r['substeps']}"
    if r.get("infill_solver") == "smooth":
        return label + " smooth"
    return label + f" r{r['relax_iterations']}"


fig, (ax, ax_strain) = plt.subplots(1, 2, figsize=(13, 5.5), dpi=100,
                                    gridspec_kw={"width_ratios": [3, 2]})
hybrid = [r for r in rows if r["mode"] == "hybrid" and value(r, error_key)]
points = sorted(((value(r, "ms_per_frame"), value(r, error_key), r) for r in hybrid),
                key=lambda p: p[0])
ax.errorbar([p[0] for p in points], [1e3 * p[1] for p in points],
            yerr=[1e3 * p[2]["error_sd"] for p in points] if seeds > 1 else None, fmt="o",
            color="tab:blue", zorder=3, capsize=3,
            label="hybrid" if seeds == 1 else f"hybrid (mean +- sd over {seeds} seeds)")
ax.set_xscale("log")
ax.set_yscale("log")


def readable_log(axis):
    """Ticks at 1, 2 and 5 of every decade, in plain numbers: a sweep spans less than a decade
    of error, where the default locator leaves one or two ticks ("4x10^1") to read it by."""
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


readable_log(ax.xaxis)
readable_log(ax.yaxis)
front, best = [], float("inf")
for ms, err, _ in points:  # cheapest first: a point is on the front if nothing cheaper beats it
    if err < best:
        front.append((ms, err))
        best = err
if front:
    ax.plot([p[0] for p in front], [1e3 * p[1] for p in front], color="tab:blue", alpha=0.5,
            drawstyle="steps-post", label="Pareto front")
# The other full-lattice references (sweep --references), each its own marker.
others = {"bullet": ("s", "tab:red", "Bullet"), "implicit": ("D", "tab:purple", "implicit Euler"),
          "xpbd": ("^", "tab:brown", "XPBD")}
for r in rows:
    if r["mode"] in others and value(r, error_key):
        marker, colour, name = others[r["mode"]]
        ax.errorbar([value(r, "ms_per_frame")], [1e3 * value(r, error_key)],
                    yerr=[1e3 * r["error_sd"]] if seeds > 1 else None, fmt=marker, capsize=3,
                    color=colour, zorder=3, label=f"{name}, full lattice")
    if r["mode"] == "mass-spring":
        ax.axvline(value(r, "ms_per_frame"), color="k", linestyle="--",
                   label="mass-spring reference (error 0)")
ax.set_xlabel("ms per output frame (one core)")
ax.set_ylabel("mean-shape RMS error vs mass-spring, mm")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8, loc="upper right")
ax.text(0.01, 0.01, "labels: coarse lattice, s = physics substeps per frame,\n"
        "r = the paper infill's step-3.4 pass cap (smooth: the smooth infill)",
        transform=ax.transAxes, fontsize=7, color="0.3", va="bottom")

# The relaxation cap against the strain it leaves, per coarse lattice and substeps.
paper = [r for r in hybrid if r.get("infill_solver") != "smooth" and value(r, "relax_iterations")]
series = {}
for r in paper:
    series.setdefault((r["coarse"], r["substeps"]), []).append(
        (value(r, "relax_iterations"), 100 * value(r, "max_strain")))
smooth = [r for r in hybrid if r.get("infill_solver") == "smooth"]
# One colour per coarse lattice and substeps, shared by its paper line and smooth level.
keys = sorted(set(series) | {(r["coarse"], r["substeps"]) for r in smooth})
colour = {key: f"C{i % 10}" for i, key in enumerate(keys)}
for (coarse, substeps), xy in sorted(series.items()):
    xy.sort()
    ax_strain.plot([p[0] for p in xy], [p[1] for p in xy], marker="o",
                   color=colour[(coarse, substeps)], label=f"paper {coarse} s{substeps}")
if series:  # the smooth infill's points as levels beside the paper solver's lines
    for r in smooth:
        ax_strain.axhline(100 * value(r, "max_strain"), linestyle=":", linewidth=1.2,
                          color=colour[(r["coarse"], r["substeps"])],
                          label=f"smooth {r['coarse']} s{r['substeps']}")
    ax_strain.set_xscale("log")
    ax_strain.set_xlabel("relaxation cap (step 3.4 passes per frame)")
    ax_strain.set_title("The strain the relaxation cap buys", fontsize=10)
else:  # no cap swept: the strain each point leaves, against its cost
    for r in smooth:
        ax_strain.plot([value(r, "ms_per_frame")], [100 * value(r, "max_strain")], marker="o",
                       linestyle="", color=colour[(r["coarse"], r["substeps"])],
                       label=f"smooth {r['coarse']} s{r['substeps']}")
    ax_strain.set_xscale("log")
    readable_log(ax_strain.xaxis)
    ax_strain.set_xlabel("ms per output frame (one core)")
    ax_strain.set_title("The strain each point leaves (no relaxation cap swept: --relax)",
                        fontsize=10)
ax_strain.axhline(1.0, color="tab:red", linewidth=0.8, label="1% (fibers' bound)")
ax_strain.set_ylabel("max link strain over the run, %")
ax_strain.grid(True, which="both", alpha=0.3)
ax_strain.legend(fontsize=7)

fine = rows[0]["fine"] if rows else "?"
frames = rows[0]["frames"] if rows else "?"
fig.suptitle(title or f"What accuracy costs: {fine} dense lattice, {frames} frames", fontsize=11)
# Each label at the first of a few places around its point where it overlaps
# no label placed before it (nor any point), cheapest point first; placed
# after the layout is final, in display coordinates.
fig.tight_layout()
fig.canvas.draw()
renderer = fig.canvas.get_renderer()
placed = []
for ms, err, _ in points:
    x, y = ax.transData.transform((ms, 1e3 * err))
    placed.append(matplotlib.transforms.Bbox.from_bounds(x - 4, y - 4, 8, 8))
offsets = [(5, 3), (5, -10), (-5, 3), (-5, -10), (5, 13), (5, -20), (-5, 13), (-5, -20)]
for ms, err, r in points:
    for dx, dy in offsets:
        note = ax.annotate(short_label(r), (ms, 1e3 * err), textcoords="offset points",
                           xytext=(dx, dy), fontsize=7, ha="left" if dx > 0 else "right")
        box = note.get_window_extent(renderer)
        if not any(box.overlaps(other) for other in placed) or (dx, dy) == offsets[-1]:
            placed.append(box)
            break
        note.remove()
fig.savefig(png_path)
