#!/usr/bin/env bash
# Every C++ source and header git tracks is as clang-format (.clang-format:
# Google style, 100 columns) would write it; prints the places and fails
# otherwise. .ci/run calls it. To fix: clang-format -i on the files named.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
if ! command -v clang-format >/dev/null; then
  "$root/scripts/setup.sh" --test-deps --no-build
fi
git ls-files -z '*.cpp' '*.hpp' | xargs -0 clang-format --dry-run --Werror
echo "check_format: $(git ls-files '*.cpp' '*.hpp' | wc -l) files as clang-format writes them"
