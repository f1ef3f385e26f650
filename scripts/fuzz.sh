#!/usr/bin/env bash
# Coverage-guided fuzzing (docs/fuzzing.md) of one of three targets:
#   nff_scene     the NFF parser, scene build, accelerators and a tiny render
#                 (fuzz/fuzz_targets/nff_scene.rs; the default);
#   results_file  reading and validating a results file, the regression gate and the
#                 HTML report (fuzz/fuzz_targets/results_file.rs);
#   probe_file    the probe file's reader (fuzz/fuzz_targets/probe_file.rs).
# Stable toolchain: cargo fuzz with RUSTC_BOOTSTRAP=1 and no sanitizer.
#
#   scripts/fuzz.sh [--target NAME] [--runs N | --seconds S] [--workers W] [--max-len BYTES] [-- LIBFUZZER_ARGS]
#
# Defaults: --seconds 60, --workers 1 (the machine is shared: use 2 only when it is
# otherwise idle), --max-len 4096 (nff_scene) or 16384 (results_file). The seed corpus is
# rebuilt on every run, outside the repository. nff_scene: from scenes/*.nff and
# ../shared/spd/*.nff (cut to --max-len at a line end; for the big SPD files also the
# view block followed by a slice from the middle of the file, so that patches, polygons
# and cones are among the seeds). results_file: real results files, written by running
# rtprof's suite on results/tests/data/v1-main-d19ee0e/suite.toml (the binary is
# $RTPROF_BIN, else built with cargo build --release), minified, with and without
# histograms, plus the /1 file of main and the regression inputs. The working corpus,
# findings and logs live under $RTPROF_FUZZ_DIR/<target> (default ~/.cache/rtprof-fuzz;
# nff_scene keeps the top level for its earlier corpus); every run appends one line of
# figures to campaign.tsv there. Exits 1 when the run found a crash, timeout or
# out-of-memory input.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
target=nff_scene
runs=""
seconds=""
workers=1
max_len=""
extra=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --target) target=$2; shift 2 ;;
        --runs) runs=$2; shift 2 ;;
        --seconds) seconds=$2; shift 2 ;;
        --workers) workers=$2; shift 2 ;;
        --max-len) max_len=$2; shift 2 ;;
        --) shift; extra=("$@"); break ;;
        -h | --help) sed -n '2,24p' "$0"; exit 0 ;;
        *) echo "fuzz.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
done
if [[ -n $runs && -n $seconds ]]; then
    echo "fuzz.sh: give --runs or --seconds, not both" >&2
    exit 2
fi
[[ -z $runs && -z $seconds ]] && seconds=60
case "$target" in
    nff_scene) max_len=${max_len:-4096}; dict=$root/fuzz/nff.dict ;;
    results_file) max_len=${max_len:-16384}; dict=$root/fuzz/results.dict ;;
    probe_file) max_len=${max_len:-8192}; dict=$root/fuzz/probe.dict ;;
    *) echo "fuzz.sh: unknown target '$target' (nff_scene, results_file, probe_file)" >&2; exit 2 ;;
esac
if ! [[ $workers =~ ^[1-9][0-9]*$ && $max_len =~ ^[1-9][0-9]*$ && ${runs:-1} =~ ^[0-9]+$ && ${seconds:-1} =~ ^[0-9]+$ ]]; then
    echo "fuzz.sh: --runs, --seconds, --workers and --max-len take whole numbers" >&2
    exit 2
fi

work=${RTPROF_FUZZ_DIR:-$HOME/.cache/rtprof-fuzz}
[[ $target == nff_scene ]] || work=$work/$target
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$HOME/.cache/rtprof-target-fuzz}
cargo_fuzz_root=$HOME/.cache/cargo-fuzz
export PATH=$cargo_fuzz_root/bin:$PATH
# libFuzzer's runtime is built from cargo fuzz's nightly flags; stable accepts them so.
export RUSTC_BOOTSTRAP=1

if ! command -v cargo-fuzz > /dev/null; then
    echo "== installing cargo-fuzz into $cargo_fuzz_root"
    cargo install --locked cargo-fuzz --root "$cargo_fuzz_root"
fi

echo "== building the fuzz target $target"
(cd "$root/fuzz" && cargo fuzz build --sanitizer none --debug-assertions "$target")
binary=$CARGO_TARGET_DIR/x86_64-unknown-linux-gnu/release/$target

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
# Real results files: a tiny suite run by rtprof, written minified, and again without
# its histograms (the bulk of the file), with the /1 file of main and the regression
# inputs; only files within max_len bytes are kept.
results_seeds() {
    local bin=${RTPROF_BIN:-}
    if [[ -z $bin ]]; then
        echo "== building rtprof for the seed runs (set RTPROF_BIN to skip)"
        (cd "$root" && CARGO_TARGET_DIR=${RTPROF_TARGET_DIR:-$root/target} cargo build --release --bin rtprof)
        bin=${RTPROF_TARGET_DIR:-$root/target}/release/rtprof
    fi
    local runs_dir=$work/seed-runs
    rm -rf "$runs_dir"
    mkdir -p "$runs_dir"
    "$bin" suite "$root/results/tests/data/v1-main-d19ee0e/suite.toml" -o "$runs_dir/tiny" > "$runs_dir/suite.log" 2>&1 || true
    local n=0
    for file in "$runs_dir"/tiny/results.json "$root"/results/tests/data/*/results.json "$root"/reports/tests/fuzz-regressions/*.json; do
        [[ -f $file ]] || continue
        n=$((n + 1))
        python3 -c 'import json, sys
r = json.load(open(sys.argv[1]))
json.dump(r, open(sys.argv[2], "w"), separators=(",", ":"))
for s in r.get("scenes", []):
    for v in s.get("variants", []):
        v["histogram"] = []
json.dump(r, open(sys.argv[3], "w"), separators=(",", ":"))' "$file" "$seeds/$n.json" "$seeds/$n-no-histograms.json"
    done
    find "$seeds" -name '*.json' -size +"$max_len"c -delete
    [[ -f $runs_dir/tiny/results.json ]] || echo "note: the seed suite run failed (see $runs_dir/suite.log)"
}
nff_seeds() {
    local spd_dir=$root/../shared/spd
    for file in "$root"/scenes/*.nff "$spd_dir"/*.nff; do
        [[ -f $file ]] || continue
        name=$(basename "$(dirname "$file")")-$(basename "$file" .nff)
        head_lines "$file" > "$seeds/$name.nff"
        if [[ $(stat -c %s "$file") -gt $max_len ]]; then
            middle_slice "$file" > "$seeds/$name-middle.nff"
        fi
    done
    [[ -d $spd_dir ]] || echo "note: $spd_dir not found; seeding from scenes/ only"
}
# Probe files: the ones the probe's own tests wrote (the C fixture, RTIOW, the Rust
# recorder), if they ran.
probe_seeds() {
    local n=0
    for file in "${CARGO_TARGET_DIR_TESTS:-$HOME/.cache/rtprof-target}"/tmp/probe-*/*.txt; do
        [[ -f $file ]] || continue
        n=$((n + 1))
        cp "$file" "$seeds/$n.txt"
    done
    printf 'rtprof.probe 1\nwriter c\npid 1\nreason exit\nthreads 1\nperiod_ns 0\nsamples 0\ncpu_ns 0\nunbalanced 0\ncounter 1 rays.primary\noutside 0\nend\n' > "$seeds/minimal.txt"
}
case "$target" in
    results_file) results_seeds ;;
    probe_file) probe_seeds ;;
    *) nff_seeds ;;
esac
echo "== $(ls "$seeds" | wc -l) seeds in $seeds, $(ls "$corpus" | wc -l) inputs in $corpus"

stamp=$(date +%Y%m%d-%H%M%S)
# The code fuzzed: the commit when the run starts (-dirty with uncommitted changes).
commit=$(git -C "$root" describe --always --dirty 2> /dev/null || echo "?")
run_dir=$work/runs/$stamp
artifacts=$work/artifacts/$stamp
mkdir -p "$run_dir" "$artifacts"
args=(
    -dict="$dict"
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
    echo "   reproduce one with: $binary <artifact>; minimise with: (cd fuzz && RUSTC_BOOTSTRAP=1 cargo fuzz tmin --sanitizer none $target <artifact>)"
    exit 1
fi
if [[ $status -ne 0 ]]; then
    echo "fuzz.sh: the fuzzer exited with status $status (see $run_dir)" >&2
    exit "$status"
fi
