#!/usr/bin/env bash
# Builds a patched copy of Ray Tracing: The Next Week (../shared/peers/rtiow, CC0) with
# rtprof's probe, or with the independent count the probe's tests compare it with,
# never touching the shared tree (docs/instrumenting.md uses it as the worked example).
#
#   scripts/rtiow-probe.sh OUT_DIR probe|count|plain [EXTRA_FLAG...]
#
# Every build: scripts/rtiow/args.patch (scene 1, random spheres in a BVH, run as
# `rtiow [SAMPLES [WIDTH]]`, default 4 and 400). Then
#   probe  scripts/rtiow/probe.patch and probe/rtprof.h: eye rays, closest-hit queries,
#          sphere tests and hits, shading calls, scattered rays (a user counter);
#          phases camera ray, closest hit (BVH traversal and sphere tests), shading;
#   count  scripts/rtiow/count.patch: eye rays, sphere tests and hits in plain global
#          atomics, printed to stderr at the end ("rtiow count: ...");
#   plain  nothing more.
# Compiled with g++ -std=c++17 -O2 -g; EXTRA_FLAGs follow (e.g. -DRTPROF_DISABLE).
# Writes OUT_DIR/src (the patched sources) and OUT_DIR/rtiow-KIND; prints its path.
# RTIOW is single-threaded: one thread renders every pixel in turn.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

if [ "$#" -lt 2 ]; then
    echo "rtiow-probe: usage: scripts/rtiow-probe.sh OUT_DIR probe|count|plain [EXTRA_FLAG...]" >&2
    exit 2
fi
out=$1
kind=$2
shift 2
case "$kind" in
    probe | count | plain) ;;
    *) echo "rtiow-probe: the kind is probe, count or plain, not '$kind'" >&2; exit 2 ;;
esac
src="$root/../shared/peers/rtiow"
[ -f "$src/main.cc" ] || { echo "rtiow-probe: $src/main.cc is missing (../shared beside the checkout)" >&2; exit 1; }
command -v g++ > /dev/null || { echo "rtiow-probe: g++ is missing (scripts/install-packages.sh g++)" >&2; exit 1; }

mkdir -p "$out"
work="$out/src-$kind"
rm -rf "$work"
mkdir -p "$work"
cp -r "$src"/. "$work"/
chmod -R u+w "$work"
apply() {
    # git apply works outside a repository too; --check first so a changed upstream
    # file fails here, naming the patch, not half-applied.
    (cd "$work" && git apply --check "$1" && git apply "$1") \
        || { echo "rtiow-probe: $1 does not apply to $src" >&2; exit 1; }
}
apply "$root/scripts/rtiow/args.patch"
case "$kind" in
    probe)
        apply "$root/scripts/rtiow/probe.patch"
        cp "$root/probe/rtprof.h" "$work/"
        ;;
    count) apply "$root/scripts/rtiow/count.patch" ;;
    plain) ;;
esac
g++ -std=c++17 -O2 -g "$@" "$work/main.cc" -o "$out/rtiow-$kind"
echo "$out/rtiow-$kind"
