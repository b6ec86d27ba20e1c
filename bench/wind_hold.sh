#!/usr/bin/env bash
# What the held wind saves (issue 35 item 6; coarse_physics spring_damper.hpp):
# the default hybrid (FRAMES frames, default 300) and mass-spring at 65 x 97
# (REF_FRAMES frames, default 15) with the wind held over substeps (the
# default, solver.wind_hold = 0.1) and evaluated every substep (wind_hold = 0:
# the bits of before), alternately ROUNDS times (default 3) so a drift of the
# machine hits both. Prints each run's per-stage medians from /stats and each
# round's ratio held / every substep of the whole frame's median; a round
# whose two runs' update stages ("integrate": the same work in both) differ by
# more than 10% ran at two machine speeds and is marked so. (The held sum's
# extrapolation between evaluations is timed in the wind's stage.)
# Usage: bench/wind_hold.sh [FRAMES] [ROUNDS] [REF_FRAMES]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:-300}"
rounds="${2:-3}"
ref_frames="${3:-15}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
for r in $(seq 1 "$rounds"); do
  for hold in 0.1 0; do
    "$root/build/flag-sim" run --quiet -o "$out/hybrid_${hold}_r$r.h5" --frames "$frames" \
      --set "solver.wind_hold=$hold" >/dev/null
    "$root/build/flag-sim" run --quiet -o "$out/ms65_${hold}_r$r.h5" --frames "$ref_frames" \
      --mode mass-spring --set "flag.fine=[65,97]" --set "solver.wind_hold=$hold" >/dev/null
  done
done
/usr/bin/python3 - "$out" "$rounds" "$root/bench" <<'PY'
import sys
out, rounds = sys.argv[1], int(sys.argv[2])
sys.path.insert(0, sys.argv[3])
from stage_medians import show, stages
for config in ("hybrid", "ms65"):
    for r in range(1, rounds + 1):
        held, every = (stages(f"{out}/{config}_{h}_r{r}.h5") for h in ("0.1", "0"))
        show(f"{config} held {r}", held)
        show(f"{config} every {r}", every)
        same = abs(held["integrate"] / every["integrate"] - 1.0) < 0.1
        print(f"{config} round {r}: whole frame {held['whole']:.2f} against {every['whole']:.2f} ms, "
              f"ratio {held['whole'] / every['whole']:.3f}"
              + ("" if same else "  (two machine speeds: not counted)"))
PY
