#!/usr/bin/env bash
# Coverage-guided fuzzing of the NFF parser, scene build, accelerators and a tiny render
# (fuzz/fuzz_targets/nff_scene.rs; docs/fuzzing.md). Stable toolchain: cargo fuzz with
# RUSTC_BOOTSTRAP=1 and no sanitizer.
#
#   scripts/fuzz.sh [--runs N | --seconds S] [--workers W] [--max-len BYTES] [-- LIBFUZZER_ARGS]
#
# Defaults: --seconds 60, --workers 1 (the machine is shared: use 2 only when it is
# otherwise idle), --max-len 4096. The seed corpus is rebuilt on every run, outside the
# repository, from scenes/*.nff and ../shared/spd/*.nff (cut to --max-len at a line end;
# for the big SPD files also the view block followed by a slice from the middle of the
# file, so that patches, polygons and cones are among the seeds). The working corpus,
# findings and logs live under $RTPROF_FUZZ_DIR (default ~/.cache/rtprof-fuzz); every run
# appends one line of figures to $RTPROF_FUZZ_DIR/campaign.tsv. Exits 1 when the run
# found a crash, timeout or out-of-memory input.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
runs=""
seconds=""
workers=1
max_len=4096
extra=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --runs) runs=$2; shift 2 ;;
        --seconds) seconds=$2; shift 2 ;;
        --workers) workers=$2; shift 2 ;;
        --max-len) max_len=$2; shift 2 ;;
        --) shift; extra=("$@"); break ;;
        -h | --help) sed -n '2,16p' "$0"; exit 0 ;;
        *) echo "fuzz.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
done
if [[ -n $runs && -n $seconds ]]; then
    echo "fuzz.sh: give --runs or --seconds, not both" >&2
    exit 2
fi
[[ -z $runs && -z $seconds ]] && seconds=60
if ! [[ $workers =~ ^[1-9][0-9]*$ && $max_len =~ ^[1-9][0-9]*$ && ${runs:-1} =~ ^[0-9]+$ && ${seconds:-1} =~ ^[0-9]+$ ]]; then
    echo "fuzz.sh: --runs, --seconds, --workers and --max-len take whole numbers" >&2
    exit 2
fi

work=${RTPROF_FUZZ_DIR:-$HOME/.cache/rtprof-fuzz}
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$HOME/.cache/rtprof-target-fuzz}
cargo_fuzz_root=$HOME/.cache/cargo-fuzz
export PATH=$cargo_fuzz_root/bin:$PATH
# libFuzzer's runtime is built from cargo fuzz's nightly flags; stable accepts them so.
export RUSTC_BOOTSTRAP=1

if ! command -v cargo-fuzz > /dev/null; then
    echo "== installing cargo-fuzz into $cargo_fuzz_root"
    cargo install --locked cargo-fuzz --root "$cargo_fuzz_root"
fi

echo "== building the fuzz target"
(cd "$root/fuzz" && cargo fuzz build --sanitizer none --debug-assertions nff_scene)
binary=$CARGO_TARGET_DIR/x86_64-unknown-linux-gnu/release/nff_scene

# Seeds: rebuilt every run (never stored in the repository).
seeds=$work/seeds
corpus=$work/corpus
rm -rf "$seeds"
mkdir -p "$seeds" "$corpus"
# The first max_len bytes of a file, cut back to the last complete line.
head_lines() {
    head -c "$max_len" "$1" | awk -v limit="$max_len" '{ n += length($0) + 1; if (n > limit) exit; print }'
}
# The view block (every line up to 'resolution') followed by the lines from the first
# entity keyword after the middle of the file, within max_len bytes.
middle_slice() {
    awk -v limit="$max_len" '
        { line[NR] = $0 }
        END {
            header = 0
            for (i = 1; i <= NR; i++) if (line[i] ~ /^[ \t]*resolution/) { header = i; break }
            if (header == 0) exit
            start = int(NR / 2)
            while (start <= NR && line[start] !~ /^[ \t]*(s|c|p|pp|f|l)([ \t]|$)/) start++
            n = 0
            for (i = 1; i <= header; i++) { print line[i]; n += length(line[i]) + 1 }
            for (i = start; i <= NR; i++) {
                n += length(line[i]) + 1
                if (n > limit) break
                print line[i]
            }
        }' "$1"
}
spd_dir=$root/../shared/spd
for file in "$root"/scenes/*.nff "$spd_dir"/*.nff; do
    [[ -f $file ]] || continue
    name=$(basename "$(dirname "$file")")-$(basename "$file" .nff)
    head_lines "$file" > "$seeds/$name.nff"
    if [[ $(stat -c %s "$file") -gt $max_len ]]; then
        middle_slice "$file" > "$seeds/$name-middle.nff"
    fi
done
[[ -d $spd_dir ]] || echo "note: $spd_dir not found; seeding from scenes/ only"
echo "== $(ls "$seeds" | wc -l) seeds in $seeds, $(ls "$corpus" | wc -l) inputs in $corpus"

stamp=$(date +%Y%m%d-%H%M%S)
# The code fuzzed: the commit when the run starts (-dirty with uncommitted changes).
commit=$(git -C "$root" describe --always --dirty 2> /dev/null || echo "?")
run_dir=$work/runs/$stamp
artifacts=$work/artifacts/$stamp
mkdir -p "$run_dir" "$artifacts"
args=(
    -dict="$root/fuzz/nff.dict"
    -max_len="$max_len"
    -rss_limit_mb=2048
    -timeout=5
    -print_final_stats=1
    -artifact_prefix="$artifacts/"
)
if [[ -n $runs ]]; then
    # -runs counts per job, so split the total between the workers.
    args+=(-runs=$(((runs + workers - 1) / workers)))
else
    args+=(-max_total_time="$seconds")
fi
if [[ $workers -gt 1 ]]; then
    args+=(-jobs="$workers" -workers="$workers")
fi
args+=("${extra[@]}")

echo "== fuzzing: $binary ${args[*]} $corpus $seeds"
echo "   logs in $run_dir"
start=$(date +%s)
status=0
# With -jobs libFuzzer writes fuzz-N.log into the current directory.
(cd "$run_dir" && "$binary" "${args[@]}" "$corpus" "$seeds") > "$run_dir/fuzz.log" 2>&1 || status=$?
wall=$(($(date +%s) - start))

logs=("$run_dir"/fuzz.log)
[[ $workers -gt 1 ]] && logs=("$run_dir"/fuzz-*.log)
executions=0
for log in "${logs[@]}"; do
    # The final stat when the job ended normally, else its last status line '#N ...'.
    n=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || true)
    if [[ -z $n ]]; then
        n=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#' || true)
    fi
    executions=$((executions + ${n:-0}))
done
last_status=$(cat "${logs[@]}" | grep -E '^#[0-9]+' | grep 'cov:' | tail -1 || true)
cov=$(grep -o 'cov: [0-9]*' <<< "$last_status" | grep -o '[0-9]*' || echo "?")
features=$(grep -o 'ft: [0-9]*' <<< "$last_status" | grep -o '[0-9]*' || echo "?")
count() { find "$artifacts" -maxdepth 1 -name "$1-*" | wc -l; }
crashes=$(count crash)
timeouts=$(count timeout)
ooms=$(count oom)
per_second=$((executions / (wall > 0 ? wall : 1)))
corpus_size=$(ls "$corpus" | wc -l)

summary_header="date	commit	workers	executions	wall_s	exec_per_s	cov	ft	corpus	crashes	timeouts	ooms"
[[ -f $work/campaign.tsv ]] || echo "$summary_header" > "$work/campaign.tsv"
echo "$stamp	$commit	$workers	$executions	$wall	$per_second	$cov	$features	$corpus_size	$crashes	$timeouts	$ooms" >> "$work/campaign.tsv"

echo "== done in ${wall}s"
echo "   total executions: $executions ($per_second/s over $workers worker(s))"
echo "   coverage: cov $cov, features $features, corpus $corpus_size inputs"
echo "   findings: $crashes crashes, $timeouts timeouts, $ooms out-of-memory (in $artifacts)"
echo "   campaign totals: $(awk -F'\t' 'NR > 1 { e += $4; t += $5 } END { printf "%d executions in %d s over %d runs", e, t, NR - 1 }' "$work/campaign.tsv")"
if [[ $((crashes + timeouts + ooms)) -gt 0 ]]; then
    echo "   reproduce one with: $binary <artifact>; minimise with: (cd fuzz && RUSTC_BOOTSTRAP=1 cargo fuzz tmin --sanitizer none nff_scene <artifact>)"
    exit 1
fi
if [[ $status -ne 0 ]]; then
    echo "fuzz.sh: the fuzzer exited with status $status (see $run_dir)" >&2
    exit "$status"
fi
