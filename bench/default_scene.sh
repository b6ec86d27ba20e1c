#!/usr/bin/env bash
# The issue's baseline table: `flag-sim run --mode mass-spring` on the default
# scene at 33x49, 65x97 and 129x193, for SECONDS of simulated time each (default
# 2 s; the 129x193 run takes minutes). Prints, per lattice: substeps per frame
# the stability limit required, ms per output frame (simulation + output), max
# and 99th-percentile link strain over all frames.
#
# Usage: bench/default_scene.sh [SECONDS] [LATTICES...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-2}"
shift || true
lattices=("$@")
if ((${#lattices[@]} == 0)); then lattices=("33,49" "65,97" "129,193"); fi
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

printf "%-9s %9s %12s %11s %11s\n" lattice substeps ms/frame max_strain p99_strain
for lattice in "${lattices[@]}"; do
  file="$out/run_${lattice/,/x}.h5"
  "$root/build/flag-sim" run --mode mass-spring --set "flag.fine=[$lattice]" \
    --set "scene.duration=$seconds" -o "$file" --quiet >/dev/null
  /usr/bin/python3 - "$file" "$lattice" "$root/bench" <<'PY'
import sys
import h5py

sys.path.insert(0, sys.argv[3])
from strain_summary import p99_strain

path, lattice = sys.argv[1], sys.argv[2].replace(",", "x")
with h5py.File(path, "r") as f:
    wall = f["stats/wall_seconds"][1:]
    substeps = f.attrs["substeps_per_frame"]
    max_strain = float(f["stats/max_strain"][...].max())
p99 = p99_strain(path)
print(f"{lattice:<9} {substeps:9.0f} {1e3 * wall.mean():12.1f} {100 * max_strain:10.2f}% {100 * p99:10.2f}%")
PY
done
