#!/usr/bin/env bash
# Measures the cost of counting: wall time of `rtprof count` over `rtprof render` on SPD
# rings, one thread, alternating runs and keeping the best of each (noise only adds time).
# Usage: scripts/count-overhead.sh [RTPROF_BINARY] [SIZE] [REPEATS]
set -euo pipefail
cd "$(dirname "$0")/.."
rtprof="${1:-target/release/rtprof}"
size="${2:-96x72}"
repeats="${3:-5}"
scene=../shared/spd/rings.nff
img="$(mktemp --suffix .png)"
trap 'rm -f "$img"' EXIT

best() { sort -g | head -n 1; }
seconds() {
    local start end
    start=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    end=$(date +%s.%N)
    awk -v a="$start" -v b="$end" 'BEGIN { print b - a }' 
}
render_times=()
count_times=()
for _ in $(seq "$repeats"); do
    render_times+=("$(seconds "$rtprof" render "$scene" --size "$size" --threads 1 -o "$img")")
    count_times+=("$(seconds "$rtprof" count "$scene" --size "$size" --threads 1 --json)")
done
r=$(printf '%s\n' "${render_times[@]}" | best)
c=$(printf '%s\n' "${count_times[@]}" | best)
printf 'count overhead on rings %s, 1 thread, best of %s: render %.3f s, count %.3f s, ratio %.3f\n' \
    "$size" "$repeats" "$r" "$c" "$(awk -v c="$c" -v r="$r" 'BEGIN { print c / r }')"
