#!/usr/bin/env bash
# Issue 14's table: every full-lattice integrator on the default scene's cloth
# at 33x49, 65x97 and 129x193, at the fewest steps that keep the p99 link
# strain at or below 1%. The explicit spring-damper and Bullet run at the
# substeps their stability limit sets; implicit Euler from 1 step a frame and
# XPBD from 40 substeps double until p99 <= 1% (or 5120). Bullet runs at
# 33x49 only (about 8x the spring-damper's cost: minutes a frame above).
# Prints per run: lattice, integrator, substeps per frame (implicit Euler:
# asked, and taken on average once steps that jump a strain are halved), ms per output frame
# (all stages), max and p99 link strain over the run, and the flap frequency
# (zero crossings of the fly-end midpoint's z about its mean, after the first
# third of the run).
#
# Usage: bench/references.sh [FRAMES] [FRAMES_AT_129x193]   (defaults 61 and 31)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:-61}"
frames_finest="${2:-31}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

# run NAME FRAMES ARGS...: prints the row; exit status 0 when p99 <= 1% and complete.
run() {
  local name="$1" n="$2"
  shift 2
  "$root/build/flag-sim" run --frames "$n" -o "$out/$name.h5" --quiet "$@" >"$out/$name.txt" 2>&1 || true
  /usr/bin/python3 - "$out/$name.h5" "$name" "$root/bench" "$out/$name.txt" <<'PY'
import re
import sys
import h5py
import numpy as np

sys.path.insert(0, sys.argv[3])
from strain_summary import p99_strain

path, name = sys.argv[1], sys.argv[2]
with h5py.File(path, "r") as f:
    status = f.attrs["status"]
    status = status.decode() if isinstance(status, bytes) else str(status)
    seconds = f["stats/stage_seconds"][1:].sum(axis=1).mean()
    substeps = int(f.attrs["substeps_per_frame"])
    max_strain = float(f["stats/max_strain"][...].max())
    z = f["frames/positions"][:, :, -1, 2]
    t = f["frames/time"][...]
z = z[:, z.shape[1] // 2]
keep = t >= t[-1] / 3
w = z[keep] - z[keep].mean()
crossings = np.count_nonzero(np.signbit(w[1:]) != np.signbit(w[:-1]))
span = t[keep][-1] - t[keep][0]
flap = crossings / (2 * span) if span > 0 else 0.0
p99 = p99_strain(path)
# Implicit Euler's halved steps (its summary line: "N of M steps undone and halved").
halved = re.search(r"(\d+) of (\d+) steps undone", open(sys.argv[4]).read())
steps = f"{substeps}" if not halved else f"{substeps}:{int(halved[2]) / (len(t) - 1):.1f}"
print(f"{name:<28} {steps:>8} {1e3 * seconds:10.1f} {100 * max_strain:8.2f}% {100 * p99:7.2f}% "
      f"{flap:6.2f} Hz  {status}", flush=True)
sys.exit(0 if status == "complete" and p99 <= 0.01 else 1)
PY
}

ladder() {  # lattice frames mode first
  local lattice="$1" n="$2" mode="$3" s="$4"
  while ((s <= 5120)); do
    if run "$lattice $mode" "$n" --mode "$mode" --set "flag.fine=[${lattice/x/,}]" \
      --set "solver.substeps=$s"; then
      return
    fi
    s=$((s * 2))
  done
}

echo "lattice integrator           substeps   ms/frame   max       p99    flap    status"
echo "(implicit: 'S:T' = S steps a frame asked, T taken on average after halving)"
for lattice in 33x49 65x97 129x193; do
  n="$frames"
  [ "$lattice" = 129x193 ] && n="$frames_finest"
  run "$lattice mass-spring" "$n" --mode mass-spring --set "flag.fine=[${lattice/x/,}]" || true
  [ "$lattice" = 33x49 ] && { run "$lattice bullet" "$n" --mode bullet --set "flag.fine=[33,49]" || true; }
  ladder "$lattice" "$n" implicit 1
  ladder "$lattice" "$n" xpbd 40
done
