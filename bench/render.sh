#!/usr/bin/env bash
# Issue 6's table: ms per frame to draw each style, and to encode PNG and MP4,
# at SIZE on the frames of FILE (default: a fresh 2 s run of the default
# scene, 129 x 193). The times are those `flag-sim render` prints: drawing
# (GL, read back) and encoding (PNG files, or the pipe to ffmpeg) separately.
#
# Usage: bench/render.sh [FILE.h5] [SIZE]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
file="${1:-}"
size="${2:-1280x720}"
if [ -z "$file" ]; then
  file="$out/default.h5"
  "$root/build/flag-sim" run --frames 61 -o "$file" --quiet >/dev/null
fi
for style in wireframe shaded textured; do
  "$root/build/flag-sim" render "$file" -o "$out/$style" --style "$style" --size "$size"
done
"$root/build/flag-sim" render "$file" -o "$out/shaded.mp4" --style shaded --size "$size"
