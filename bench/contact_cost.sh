#!/usr/bin/env bash
# What contact costs (issue 31): the default scene (FRAMES frames, default 150)
# without and with a solid pole ([pole] radius = 0.04 m), and with the pole
# and self-contact ([contact] thickness = 0.005 m), and scenes/contact/
# pole_wrap in the full-lattice modes (mass-spring and XPBD at 17 x 25) without
# and with self-contact ([contact] thickness = 0.005 m), each pair run
# alternately ROUNDS times (default 3) so a drift of the machine hits both; the
# contact scenes once each. Prints per run the median ms/frame of the whole
# frame and of each stage, from /stats, and per configuration the median over
# its rounds, and the ratios with/without of the rounds whose runs ran at one
# machine speed (the figures to quote).
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
# The ratio that survives a machine changing speed (this one does, by about
# 1.6x, for minutes at a time): each round's runs back to back, counted only
# where the coarse springs' stage (the same work in all three) took the same
# time within 10% in both; and without the output stage, whose writes to the
# disk now and then take 1.3 ms instead of 0.25 in any run.
for config in ("pole", "pole_self"):
    same, same_computing = [], []
    for r in range(rounds):
        a, b = runs[config][r], runs["default"][r]
        ratio = a["whole"] / b["whole"]
        computing = (a["whole"] - a["output"]) / (b["whole"] - b["output"])
        counted = abs(a["stretch"] / b["stretch"] - 1.0) < 0.1
        if counted:
            same.append(ratio)
            same_computing.append(computing)
        print(f"round {r + 1}: {config} / default {ratio:.2f}, without output {computing:.2f} "
              f"(stretch stage {a['stretch']:.2f} / {b['stretch']:.2f} ms"
              f"{'' if counted else ', the machine changed speed: not counted'})")
    if same:
        print(f"{config} / default at one machine speed ({len(same)} of {rounds} rounds): "
              f"{min(same):.2f}-{max(same):.2f}, median {np.median(same):.2f}; without output "
              f"{min(same_computing):.2f}-{max(same_computing):.2f}, "
              f"median {np.median(same_computing):.2f}")
for mode in ("mass-spring", "xpbd"):
    plain, self_contact = whole[mode], whole[f"{mode}_self"]
    print(f"pole_wrap, {mode} 17 x 25: {plain:.2f} ms, with [contact] {self_contact:.2f} ms, "
          f"ratio {self_contact / plain:.2f}")
for scene in ("pole_wrap", "pole_calm", "banner_ground"):
    show(scene, stages(scene))
PY
