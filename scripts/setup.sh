#!/usr/bin/env bash
# Installs the Debian packages flag-sim needs (skipping those already present),
# then configures and builds the project into build/. Idempotent: a second run
# only rebuilds what changed.
#
# Usage: scripts/setup.sh [--test-deps] [--no-build]
#   --test-deps  also the outside programs the tests run for real (ParaView's
#                pvpython, meshio, Slurm and munge); scripts/test.sh passes it
set -euo pipefail
test_deps=0
build=1
for arg in "$@"; do
  case "$arg" in
    --test-deps) test_deps=1 ;;
    --no-build) build=0 ;;
    *) echo "setup.sh: unknown option $arg (use --test-deps, --no-build)" >&2; exit 2 ;;
  esac
done

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# Build tools and the libraries the modules link against (see CMakeLists.txt).
packages=(
  cmake g++ make pkg-config
  libhdf5-dev libtomlplusplus-dev libcli11-dev libfmt-dev libeigen3-dev
  libgtest-dev libbenchmark-dev
  libbullet-dev libosmesa6-dev libpng-dev ffmpeg
  python3-h5py python3-numpy python3-matplotlib
  pybind11-dev python3-dev
)
if ((test_deps)); then
  # tests/app/paraview_test.py: ParaView's default XDMF reader, run by pvpython;
  # tests/app/export_test.py: meshio reads the exported OBJ;
  # tests/app/slurm_test.py: a one-node Slurm (no daemon starts by itself)
  packages+=(paraview python3-paraview python3-meshio slurmctld slurmd slurm-client munge)
  # tests/app/paraview_test.py: pvpython's SaveScreenshot needs an X display;
  # README's xvfb-run needs xauth (only a Recommends of xvfb)
  packages+=(xvfb xauth)
  # scripts/check_format.sh, scripts/check_tidy.sh
  packages+=(clang-format clang-tidy)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if ((!build)); then exit 0; fi

jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" \
  -DFLAGSIM_WERROR="${FLAGSIM_WERROR:-OFF}" >/dev/null
cmake --build "$root/build" -j "$jobs"
