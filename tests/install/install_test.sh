#!/usr/bin/env bash
# `cmake --install` of the build into a fresh prefix, then a program outside
# the project found through find_package(flagsim) and linked to
# flagsim::flagsim (tests/install/consumer): it must build, and its frame 5 of
# the default scene at 17 x 25 must be the Python module's, digit for digit
# (one library, two ways in). Also: the installed flag-sim runs.
# Usage: install_test.sh BUILD_DIR
set -euo pipefail
build="$(cd "$1" && pwd)"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
test -f "$tmp/prefix/lib/cmake/flagsim/flagsimConfig.cmake"
test -f "$tmp/prefix/include/flagsim/sim/simulation.hpp"
"$tmp/prefix/bin/flag-sim" --version >/dev/null
# No path back into the source or build tree may be left in the package.
if grep -rl -e "$build" -e "$(cd "$here/../.." && pwd)/" "$tmp/prefix/lib/cmake/flagsim"; then
  echo "install_test: the installed package names the build or source tree" >&2
  exit 1
fi
if ! { cmake -S "$here/consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_BUILD_TYPE=Release && cmake --build "$tmp/consumer" -j 2; } >"$tmp/log" 2>&1; then
  tail -40 "$tmp/log" >&2
  echo "install_test: the consumer did not build against the installed package" >&2
  exit 1
fi
got="$("$tmp/consumer/consumer" 5)"
want="$(PYTHONPATH="$build/python" /usr/bin/python3 -c '
import flagsim
sim = flagsim.Simulation(None, overrides={"flag.fine": [17, 25]})
sim.step(5)
print(" ".join("%.17g" % v for v in sim.positions[8, -1]))')"
if [ "$got" != "$want" ]; then
  echo "install_test: the installed library gave '$got', the Python module '$want'" >&2
  exit 1
fi
echo "install_test: consumer built against $tmp/prefix; frame 5 fly end $got"
