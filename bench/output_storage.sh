#!/usr/bin/env bash
# What a run costs on disk, and in time to write: the default scene (FRAMES
# frames, default 300 = 10 s) stored as it ships, with [output] compression
# 1, 4 and 9, with fields = [] (positions only) and with dense = false (the
# coarse trajectory; `flag-sim refine` recomputes the dense frames). Prints
# the file size and the output stage's median ms/frame, from /stats.
# Usage: bench/output_storage.sh [FRAMES]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:-300}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
run() {  # NAME, then --set arguments
  local name="$1"
  shift
  "$root/build/flag-sim" run --quiet --frames "$frames" -o "$out/$name.h5" "$@" >/dev/null
  /usr/bin/python3 - "$out/$name.h5" "$name" <<'PY'
import os
import sys
import h5py
import numpy as np
path, name = sys.argv[1], sys.argv[2]
with h5py.File(path, "r") as f:
    stages = f["/stats/stage_seconds"]
    names = [n.decode() if isinstance(n, bytes) else str(n) for n in stages.attrs["stages"]]
    output = 1e3 * np.median(stages[1:, names.index("output")])
    wall = 1e3 * np.median(f["/stats/wall_seconds"][1:])
print(f"{name:<16} {os.path.getsize(path) / 1e6:8.2f} MB  output {output:6.2f} ms/frame"
      f"  whole frame {wall:6.2f} ms")
PY
}
echo "default scene, $frames frames, 129 x 193 dense, $(date -I)"
run shipped
for level in 1 4 9; do run "compression=$level" --set "output.compression=$level"; done
run "fields=[]" --set "output.fields=[]"
run "dense=false" --set "output.dense=false"
