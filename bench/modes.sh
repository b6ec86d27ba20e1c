#!/usr/bin/env bash
# Issue 5's table: the default scene (129x193 dense, 9x13 coarse) in every mode
# with physics, FRAMES output frames from t = 0 each. Prints per run: substeps
# per frame, ms per output frame (all stages, output included), every stage
# over 0.5 ms, and max / 99th-percentile link strain over the run.
#
# Usage: bench/modes.sh [FRAMES] [FULL_LATTICE_FRAMES]
#   FRAMES               hybrid runs (default 61: 2 s of flag)
#   FULL_LATTICE_FRAMES  mass-spring and bullet on 129x193, seconds per frame
#                        each (default 16)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:-61}"
full_frames="${2:-16}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

run() {  # name frames flag-sim-args...
  local name="$1" n="$2"
  shift 2
  "$root/build/flag-sim" run --frames "$n" -o "$out/$name.h5" --quiet "$@" >/dev/null
  /usr/bin/python3 - "$out/$name.h5" "$name" "$root/bench" <<'PY'
import sys
import h5py

sys.path.insert(0, sys.argv[3])
from strain_summary import p99_strain

path, name = sys.argv[1], sys.argv[2]
with h5py.File(path, "r") as f:
    stages = list(f["stats/stage_seconds"].attrs["stages"])
    seconds = f["stats/stage_seconds"][1:].mean(axis=0)
    substeps = f.attrs["substeps_per_frame"]
    max_strain = float(f["stats/max_strain"][...].max())
p99 = p99_strain(path)
total = seconds.sum()
split = " ".join(f"{s}={1e3 * t:.2f}" for s, t in zip(stages, seconds) if t > 0.0005)
print(f"{name:<16} {substeps:6.0f} {1e3 * total:10.1f} {100 * max_strain:8.2f}% {100 * p99:7.2f}%  {split}")
PY
}

printf "%-16s %6s %10s %9s %8s  %s\n" run substeps ms/frame max p99 "ms per stage"
run hybrid          "$frames"
run hybrid-bullet   "$frames" --set solver.backend=bullet
run mass-spring     "$full_frames" --mode mass-spring
run bullet          "$full_frames" --mode bullet
