#!/usr/bin/env bash
# clang-tidy (.clang-tidy: bug-prone patterns, performance, the project's
# naming) over every C++ source git tracks that the build compiles, headers of
# every module included; any finding fails. .ci/run calls it after the build
# (it reads build/compile_commands.json). Arguments: files to check instead of
# all of them.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
if ! command -v run-clang-tidy >/dev/null; then
  "$root/scripts/setup.sh" --test-deps --no-build
fi
if [ ! -f build/compile_commands.json ]; then
  echo "check_tidy: no build/compile_commands.json; run scripts/setup.sh first" >&2
  exit 2
fi
if (($#)); then
  files=("$@")
else
  # The fuzz targets build with clang in their own tree (scripts/fuzz.sh); the
  # rest is in the main build's compile commands. The install test builds its
  # consumer against the installed package, outside that build.
  mapfile -t files < <(git ls-files '*.cpp' | grep -v -e '^fuzz/' -e '^tests/install/consumer/')
fi
jobs="$(nproc 2>/dev/null || echo 2)"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
# run-clang-tidy takes file regexes: anchor each path.
regexes=()
for f in "${files[@]}"; do regexes+=("$root/$f\$"); done
if ! run-clang-tidy -quiet -p build -j "$jobs" "${regexes[@]}" >"$log" 2>&1; then
  grep -E '(warning|error):' "$log" | sort -u >&2 || cat "$log" >&2
  echo "check_tidy: findings above (.clang-tidy)" >&2
  exit 1
fi
echo "check_tidy: ${#files[@]} sources clean"
