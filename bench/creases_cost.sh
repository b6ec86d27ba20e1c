#!/usr/bin/env bash
# What creases cost (issue 32): the default scene (FRAMES frames, default 150)
# with [bending] D = 1e-4 N m (creases need it) against the same with
# [creases] (no fold line: the plastic bending and its bookkeeping) and with
# [creases] and the two fold lines of scenes/creases/ (their ridges drawn in the
# dense frames too), run alternately ROUNDS times (default 3) so a drift of the
# machine hits all three. Prints per run the median ms/frame of the whole frame
# and of each stage, from /stats, and per configuration the median over its
# rounds; the ratios to the first are the figures to quote.
# Usage: bench/creases_cost.sh [FRAMES] [ROUNDS]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:-150}"
rounds="${2:-3}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
run() {  # NAME, then the run's arguments after its output
  local name="$1"
  shift
  "$root/build/flag-sim" run --quiet -o "$out/$name.h5" --frames "$frames" \
    --set bending.stiffness=1e-4 "$@" >/dev/null
}
folds='flag.folds=[{axis="col",at=0.5,angle=1.2},{axis="row",at=0.5,angle=1.2,to=0.5},{axis="row",at=0.5,angle=-1.2,from=0.5}]'
for r in $(seq 1 "$rounds"); do
  run "bending_r$r"
  run "creases_r$r" --set creases.yield_angle=1.0
  run "folded_r$r" --set creases.yield_angle=1.0 --set "$folds"
done
/usr/bin/python3 - "$out" "$rounds" "$root/bench" <<'PY'
import sys
import numpy as np
out, rounds = sys.argv[1], int(sys.argv[2])
sys.path.insert(0, sys.argv[3])
from stage_medians import show, stages
configs = ("bending", "creases", "folded")
whole = {}
for config in configs:
    rows = [stages(f"{out}/{config}_r{r}.h5") for r in range(1, rounds + 1)]
    for r, row in enumerate(rows, 1):
        show(f"{config} {r}", row)
    whole[config] = float(np.median([row["whole"] for row in rows]))
print("whole frame, median over rounds: " +
      ", ".join(f"{c} {whole[c]:.2f} ms ({whole[c] / whole['bending']:.2f}x)" for c in configs))
PY
