#!/usr/bin/env bash
# What contact costs (issue 31): the default scene (FRAMES frames, default 150)
# without and with a solid pole ([pole] radius = 0.04 m), and with the pole
# and self-contact ([contact] thickness = 0.005 m), and scenes/contact/
# pole_wrap in the full-lattice modes (mass-spring and XPBD at 17 x 25) without
# and with self-contact ([contact] thickness = 0.005 m), each pair run
# alternately ROUNDS times (default 3) so a drift of the machine hits both; the
# contact scenes once each. Prints per run the median ms/frame of the whole
# frame and of each stage, from /stats, and per configuration the median over
# its rounds; the ratios with/without are the figures to quote.
# Usage: bench/contact_cost.sh [FRAMES] [ROUNDS]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:-150}"
rounds="${2:-3}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
run() {  # NAME, then the run's arguments after its output
  local name="$1"
  shift
  "$root/build/flag-sim" run --quiet -o "$out/$name.h5" "$@" >/dev/null
}
wrap="$root/scenes/contact/pole_wrap.toml"
for r in $(seq 1 "$rounds"); do
  run "default_r$r" --frames "$frames"
  run "pole_r$r" --frames "$frames" --set pole.radius=0.04
  run "pole_self_r$r" --frames "$frames" --set pole.radius=0.04 --set contact.thickness=0.005
  for mode in mass-spring xpbd; do
    run "${mode}_r$r" "$wrap" --mode "$mode" --set "flag.fine=[17,25]"
    run "${mode}_self_r$r" "$wrap" --mode "$mode" --set "flag.fine=[17,25]" \
      --set contact.thickness=0.005
  done
done
for scene in pole_wrap pole_calm banner_ground; do
  run "$scene" "$root/scenes/contact/$scene.toml"
done
/usr/bin/python3 - "$out" "$rounds" "$root/bench" <<'PY'
import sys
import numpy as np
out, rounds = sys.argv[1], int(sys.argv[2])
sys.path.insert(0, sys.argv[3])
from stage_medians import show, stages as stages_of
def stages(name):
    return stages_of(f"{out}/{name}.h5")
runs = {}
for config in ("default", "pole", "pole_self", "mass-spring", "mass-spring_self", "xpbd", "xpbd_self"):
    runs[config] = [stages(f"{config}_r{r}") for r in range(1, rounds + 1)]
    for r, row in enumerate(runs[config], 1):
        show(f"{config} {r}", row)
whole = {c: float(np.median([row["whole"] for row in rows])) for c, rows in runs.items()}
print(f"whole frame, median over rounds: default {whole['default']:.2f} ms, "
      f"pole.radius = 0.04 {whole['pole']:.2f} ms, ratio {whole['pole'] / whole['default']:.2f}; "
      f"with contact.thickness = 0.005 too {whole['pole_self']:.2f} ms, "
      f"ratio {whole['pole_self'] / whole['default']:.2f}")
for mode in ("mass-spring", "xpbd"):
    plain, self_contact = whole[mode], whole[f"{mode}_self"]
    print(f"pole_wrap, {mode} 17 x 25: {plain:.2f} ms, with [contact] {self_contact:.2f} ms, "
          f"ratio {self_contact / plain:.2f}")
for scene in ("pole_wrap", "pole_calm", "banner_ground"):
    show(scene, stages(scene))
PY
