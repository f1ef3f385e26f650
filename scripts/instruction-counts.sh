#!/usr/bin/env bash
# Instruction counts of the `sqrt` and `intersect` kernels under valgrind (gungraun),
# saved as <target dir>/gungraun/**/summary.json for `rtprof suite` and
# `rtprof report --instructions` to show beside criterion's times.
#
# Installs what it needs once: valgrind (Debian package) and gungraun-runner of the
# exact version the benches crate uses, into $GUNGRAUN_HOME (default
# ~/.cache/gungraun, outside any checkout, so CI reuses it).
# Usage: scripts/instruction-counts.sh [--install-only | extra gungraun arguments, e.g. a filter]
#   --install-only   install valgrind and the runner, measure nothing (CI does it while
#                    it compiles)
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-packages.sh valgrind >&2

# The runner must match the library version exactly (gungraun refuses otherwise).
version=$(cargo metadata --format-version 1 --locked --all-features \
    | python3 -c 'import json,sys; print(next(p["version"] for p in json.load(sys.stdin)["packages"] if p["name"] == "gungraun"))')
home="${GUNGRAUN_HOME:-$HOME/.cache/gungraun}"
runner="$home/$version/bin/gungraun-runner"
if [ ! -x "$runner" ]; then
    echo "instruction-counts: installing gungraun-runner $version into $home/$version" >&2
    cargo install --locked --quiet --version "$version" --root "$home/$version" gungraun-runner
fi
if [ "${1:-}" = "--install-only" ]; then
    echo "instruction-counts: valgrind and gungraun-runner $version are installed"
    exit 0
fi

GUNGRAUN_RUNNER="$runner" cargo bench -p benches --features instructions --bench instructions \
    -- --save-summary=json "$@"
