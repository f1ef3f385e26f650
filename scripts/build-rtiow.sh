#!/usr/bin/env bash
# Builds a patched copy of Ray Tracing: The Next Week (../shared/peers/rtiow, CC0) for
# `rtprof record`'s checks, never touching the shared tree: scene 1 (random spheres,
# about 480 spheres in a BVH) at SAMPLES samples per pixel instead of the default final
# scene, compiled with the flags a profiled build needs.
#
#   scripts/build-rtiow.sh OUT_DIR [SAMPLES] [EXTRA_FLAG...]
#
# Writes OUT_DIR/rtiow (and the patched sources beside it); prints its path. The image
# goes to stdout (P3 PPM), progress to stderr. Default flags: -O2 -g
# -fno-omit-frame-pointer (frame pointers for perf's fp call graphs, debug info for
# names and inlined frames); EXTRA_FLAGs follow them (e.g. -fno-inline).
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "$#" -lt 1 ]; then
    echo "build-rtiow: name the output directory" >&2
    exit 2
fi
out="$1"
samples="${2:-4}"
shift $(( $# >= 2 ? 2 : 1 ))
src=../shared/peers/rtiow
[ -f "$src/main.cc" ] || { echo "build-rtiow: $src/main.cc is missing" >&2; exit 1; }
case "$samples" in ''|*[!0-9]*) echo "build-rtiow: SAMPLES must be a whole number" >&2; exit 2;; esac

mkdir -p "$out"
cp -r "$src"/. "$out"/
chmod -R u+w "$out"
# Scene 1 instead of the default final scene (minutes of work); its samples per pixel.
sed -i 's/switch (0)/switch (1)/' "$out/main.cc"
sed -i "0,/cam.samples_per_pixel = 100;/s//cam.samples_per_pixel = $samples;/" "$out/main.cc"
grep -q 'switch (1)' "$out/main.cc" || { echo "build-rtiow: main.cc's scene switch changed" >&2; exit 1; }
g++ -std=c++17 -O2 -g -fno-omit-frame-pointer "$@" "$out/main.cc" -o "$out/rtiow"
echo "$out/rtiow"
