#!/usr/bin/env bash
# The whole hybrid frame on the default scene (physics, infill, checks, output),
# from a real run's /stats: median and 99th percentile of the frame's wall time
# and of its infill stages, over frames 1..300, for each of RUNS runs (default 3).
# Usage: bench/hybrid_frame.sh [RUNS] [-- extra flag-sim run arguments]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs="${1:-3}"
shift || true
[ "${1:-}" = "--" ] && shift
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
for i in $(seq 1 "$runs"); do
  "$root/build/flag-sim" run --quiet -o "$out/run$i.h5" "$@" >/dev/null
  /usr/bin/python3 - "$out/run$i.h5" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1], "r") as f:
    wall = 1e3 * f["/stats/wall_seconds"][1:]
    stages = f["/stats/stage_seconds"]
    names = [n.decode() if isinstance(n, bytes) else str(n) for n in stages.attrs["stages"]]
    cols = [i for i, n in enumerate(names) if n.startswith("infill") or n == "coarse_slack"]
    infill = 1e3 * stages[1:, cols].sum(axis=1)
    print(f"frame ms median {np.median(wall):.2f} p99 {np.percentile(wall, 99):.2f} | "
          f"infill ms median {np.median(infill):.2f} p99 {np.percentile(infill, 99):.2f} | "
          f"max strain {100 * f['/stats/max_strain'][()].max():.3f}%")
PY
done
