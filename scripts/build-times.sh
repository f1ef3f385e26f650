#!/usr/bin/env bash
# Cold build times: the README's two commands' builds in an empty target directory, as a
# new user's machine does them (docs/build-times.md keeps the figures). Downloads are
# made first (`cargo fetch`) and not counted. Prints each build's wall and CPU time and
# its slowest units from cargo's --timings (the HTML report is kept in the target
# directory's cargo-timings/ when --keep is given).
#
#   scripts/build-times.sh [release|test|all] [--keep]
#
#   release  cargo build --release            (what `cargo run --release -- suite` builds)
#   test     cargo test --workspace --no-run  (the test binaries; running them is apart)
#   all      both, one after the other, each from an empty target directory (default)
#
# Run it on an otherwise idle machine: a second process on 2 cores doubles the figures.
set -euo pipefail
cd "$(dirname "$0")/.."

what="${1:-all}"
keep=""
[ "${2:-}" = "--keep" ] && keep=1
case "$what" in
    release | test | all) ;;
    -h | --help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "build-times.sh: give release, test or all (see --help)" >&2; exit 2 ;;
esac

cargo fetch --locked >/dev/null

measure() {
    local name=$1; shift
    local dir
    dir=$(mktemp -d "${TMPDIR:-/tmp}/rtprof-build-times.XXXXXX")
    local start=$SECONDS
    local cpu_before cpu_after
    cpu_before=$(awk '{print $14 + $15 + $16 + $17}' /proc/$$/stat)
    CARGO_TARGET_DIR="$dir" "$@" --timings >/dev/null 2>"$dir.log" || { cat "$dir.log" >&2; exit 1; }
    cpu_after=$(awk '{print $14 + $15 + $16 + $17}' /proc/$$/stat)
    local wall=$((SECONDS - start))
    local ticks
    ticks=$(getconf CLK_TCK)
    printf '%s: %d min %02d s wall, %.0f s CPU\n' "$name" $((wall / 60)) $((wall % 60)) \
        "$(awk -v a="$cpu_before" -v b="$cpu_after" -v t="$ticks" 'BEGIN { print (b - a) / t }')"
    python3 - "$dir"/cargo-timings/cargo-timing.html <<'PY'
import json, re, sys
text = open(sys.argv[1]).read()
units = json.loads(re.search(r"const UNIT_DATA = (\[.*?\]);\n", text, re.S).group(1))
print(f"  {len(units)} units, {sum(u['duration'] for u in units):.0f} s of unit time; slowest:")
for u in sorted(units, key=lambda u: -u["duration"])[:12]:
    print(f"  {u['duration']:6.1f} s  {u['name']} {u['version']}")
PY
    if [ -n "$keep" ]; then
        echo "  kept $dir (cargo-timings/cargo-timing.html)"
    else
        rm -rf "$dir" "$dir.log"
    fi
}

if [ "$what" = release ] || [ "$what" = all ]; then
    measure "cold cargo build --release" cargo build --release --locked
fi
if [ "$what" = test ] || [ "$what" = all ]; then
    measure "cold cargo test --workspace --no-run" cargo test --workspace --no-run --locked
fi
