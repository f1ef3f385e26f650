#!/usr/bin/env bash
# Builds the Embree yardstick (peers/embree/, a standalone C++ tracer on Embree 3's
# API) against Debian's libembree-dev with g++, and installs it as PREFIX/bin/rtprof-embree
# (default /usr/local, on PATH like povray and tachyon), the program the built-in peers
# `embree` and `embree-single` run (runner/tracers/embree*.toml).
#
#   scripts/build-embree-peer.sh [PREFIX]
#
# Flags: -O3 -march=native, as Embree's users build a renderer they run where they
# built it (Embree itself picks its widest kernels at run time, whatever these flags
# are; they only shape the program's own camera, shading and loop). -std=c++17, and
# -pthread for the render threads.
set -euo pipefail
cd "$(dirname "$0")/.."

prefix="${1:-/usr/local}"
header=/usr/include/embree3/rtcore.h
command -v g++ > /dev/null || {
    echo "build-embree-peer: g++ is missing (apt-get install g++, or scripts/install-packages.sh g++)" >&2
    exit 1
}
# Debian's libembree-dev ships no embree3.pc; use pkg-config where a build has one.
if pkg-config --exists embree3 2> /dev/null; then
    read -r -a cflags <<< "$(pkg-config --cflags embree3)"
    read -r -a libs <<< "$(pkg-config --libs embree3)"
else
    [ -f "$header" ] || {
        echo "build-embree-peer: $header is missing: apt-get install libembree-dev (or scripts/install-packages.sh libembree-dev)" >&2
        exit 1
    }
    cflags=()
    libs=(-lembree3)
fi

build=$(mktemp -d)
trap 'rm -rf "$build"' EXIT
g++ -std=c++17 -O3 -march=native -pthread -Wall -Wextra "${cflags[@]}" \
    peers/embree/*.cpp -o "$build/rtprof-embree" "${libs[@]}"
mkdir -p "$prefix/bin"
install -m 755 "$build/rtprof-embree" "$prefix/bin/rtprof-embree"
echo "$prefix/bin/rtprof-embree"
