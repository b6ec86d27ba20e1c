#!/usr/bin/env bash
# Fuzzes the scene parser and validator with libFuzzer (clang, ASan + UBSan)
# for SECONDS (default 60), starting from every scene under scenes/. Builds
# into build-fuzz/. A crash, leak, sanitizer report or timeout fails the
# script and leaves the input that caused it in build-fuzz/ (crash-*, leak-*,
# timeout-*); replay one with build-fuzz/scene_parser_fuzz FILE.
#
# Longer runs: scripts/fuzz.sh 3600 (new interesting inputs accumulate in
# build-fuzz/corpus/ and are reused by the next run).
#
# Usage: scripts/fuzz.sh [SECONDS]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
"$root/scripts/setup.sh" --no-build
if ! command -v clang++ >/dev/null; then
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends clang >/dev/null
fi
build="$root/build-fuzz"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFLAGSIM_FUZZ=ON \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" --target scene_parser_fuzz >/dev/null
mkdir -p "$build/corpus" "$build/seeds"
find "$root/scenes" -name '*.toml' -exec cp {} "$build/seeds/" \;
cd "$build"
./scene_parser_fuzz -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 corpus seeds 2>&1 | tail -n 12
