#!/usr/bin/env bash
# The test suite once more with assertions on: builds into build-assert/ at
# -O2 without NDEBUG (CMake's Release and RelWithDebInfo define it, so the
# project's own `assert`s - span sizes, lattice shapes, preconditions - run in
# no other build) and runs every test but the `large` cases (the same code at
# 257 x 385 and up). .ci/run calls it after scripts/test.sh. About 5 minutes
# to build and 1 to run on 2 cores. Extra arguments go to ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh" --test-deps --no-build
jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S "$root" -B "$root/build-assert" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2" -DFLAGSIM_BUILD_BENCH=OFF \
  -DFLAGSIM_WERROR="${FLAGSIM_WERROR:-OFF}" >/dev/null
cmake --build "$root/build-assert" -j "$jobs"
cd "$root/build-assert"
if (($#)); then
  ctest --output-on-failure -j "$jobs" "$@"
else
  ctest --output-on-failure -j "$jobs" -LE large
fi
