#!/usr/bin/env bash
# Fuzzes with libFuzzer (clang, ASan + UBSan), SECONDS (default 60) per target:
#  - scene_parser_fuzz: the scene parser and validator, and the --set parser,
#    starting from every scene under scenes/;
#  - output_reader_fuzz: the output reader on HDF5 files whose shapes,
#    types and attributes the fuzzer chooses (see fuzz/output_reader_fuzz.cpp).
# Builds into build-fuzz/. A crash, leak, sanitizer report or timeout fails the
# script and leaves the input that caused it in build-fuzz/ (crash-*, leak-*,
# timeout-*); replay one with build-fuzz/<target> FILE.
#
# Longer runs: scripts/fuzz.sh 3600 (new interesting inputs accumulate in
# build-fuzz/corpus-<target>/ and are reused by the next run).
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
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" \
  --target scene_parser_fuzz output_reader_fuzz >/dev/null
mkdir -p "$build/corpus-scene_parser_fuzz" "$build/corpus-output_reader_fuzz" "$build/seeds"
find "$root/scenes" -name '*.toml' -exec cp {} "$build/seeds/" \;
cd "$build"
# The HDF5 library keeps a little memory for the life of the process: not a leak of ours.
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
for target in scene_parser_fuzz output_reader_fuzz; do
  echo "== $target, ${seconds} s" >&2
  seeds=()
  if [ "$target" = scene_parser_fuzz ]; then seeds=(seeds); fi
  "./$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 "corpus-$target" "${seeds[@]}" 2>&1 | tail -n 12
  status=${PIPESTATUS[0]}
  if [ "$status" -ne 0 ]; then exit "$status"; fi
done
