#!/usr/bin/env bash
# Sets up what is missing (scripts/setup.sh, with the test dependencies), builds, and runs the whole test
# suite with CTest. Extra arguments go to ctest (e.g. -R Scene).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh" --test-deps
jobs="$(nproc 2>/dev/null || echo 2)"
cd "$root/build"
ctest --output-on-failure -j "$jobs" "$@"
