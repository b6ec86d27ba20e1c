#!/usr/bin/env bash
# Sets up what is missing (scripts/setup.sh), builds, and runs flag-sim; with no
# arguments it runs the embedded default scene, writing out/default.h5.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh" >&2
if [ "$#" -eq 0 ]; then set -- run; fi
exec "$root/build/flag-sim" "$@"
