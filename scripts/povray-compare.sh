#!/usr/bin/env bash
# Compares rtprof's whole-process wall time against POV-Ray 3.7 (the peer renderer) on the
# SPD scenes, one thread, no antialiasing. A measurement, not a gate: always exits 0 once
# the runs succeed, and says whether the target (geomean ratio <= 0.5, max ratio <= 0.8)
# is met.
#
# Usage: scripts/povray-compare.sh [OPTIONS] RTPROF_BINARY [SIZE] [VARIANT] [SCENES...]
#   SIZE      N (NxN) or WxH, default 512
#   VARIANT   rtprof --variant value, default bvh
#   SCENES    default: balls gears mount rings teapot tetra tree
# Options:
#   --povray-only   time POV-Ray alone; RTPROF_BINARY is then not checked (may be "-" or
#                   left out when nothing follows it)
#   --tsv FILE      also write one tab-separated row per scene to FILE
#   --images DIR    keep the rendered PNGs and POV-Ray's logs in DIR (default: discarded)
#   -h, --help      this text
# Environment:
#   REPEATS=N       runs per renderer and scene; the median of each measure is reported
#   POVRAY=PATH     POV-Ray executable (default: povray on PATH)
#
# POV-Ray runs as
#   povray +INAME.pov +ONAME.png +WW +HH -D +FN +WT1 -A
# in a temporary directory holding the gunzipped scene, under a temporary HOME with an
# empty user povray.conf (no warning about a missing one, no user povray.ini), with
# POVINI and POVRAYOPT unset; the system /etc/povray/3.7/povray.ini applies. Nothing is
# declared: the scenes render exactly as exported (no #version, so POV-Ray applies its
# pre-3.7 compatibility, gamma correction off). rtprof runs as
#   RTPROF_BINARY render SHARED/spd/NAME.nff --spd --size WxH --threads 1 --variant V -o OUT.png
# Wall time is that of the whole process (start-up, parse, build, trace, write).
set -euo pipefail

readonly default_scenes=(balls gears mount rings teapot tetra tree)

usage() { sed -n '/^# Usage:/,/^# Wall time/s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"; }
die() { printf 'povray-compare: %s\n' "$1" >&2; exit "${2:-2}"; }

script_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
shared="$script_dir/../../shared"

povray_only=0
tsv=""
images=""
positional=()
while (($#)); do
    case "$1" in
        --povray-only) povray_only=1 ;;
        --tsv) (($# >= 2)) || die "--tsv needs a file"; tsv="$2"; shift ;;
        --tsv=*) tsv="${1#--tsv=}" ;;
        --images) (($# >= 2)) || die "--images needs a directory"; images="$2"; shift ;;
        --images=*) images="${1#--images=}" ;;
        -h | --help) usage; exit 0 ;;
        --) shift; positional+=("$@"); break ;;
        -?*) die "unknown option '$1' (see --help)" ;;
        *) positional+=("$1") ;;
    esac
    shift
done

if ((${#positional[@]} == 0)); then
    ((povray_only)) || die "missing RTPROF_BINARY (usage: scripts/povray-compare.sh [OPTIONS] RTPROF_BINARY [SIZE] [VARIANT] [SCENES...]; see --help)"
    positional=(-)
fi
rtprof="${positional[0]}"
size="${positional[1]:-512}"
variant="${positional[2]:-bvh}"
scenes=("${positional[@]:3}")
((${#scenes[@]})) || scenes=("${default_scenes[@]}")

if [[ "$size" =~ ^([0-9]+)$ ]]; then
    width="$size"; height="$size"
elif [[ "$size" =~ ^([0-9]+)[xX]([0-9]+)$ ]]; then
    width="${BASH_REMATCH[1]}"; height="${BASH_REMATCH[2]}"
else
    die "SIZE '$size' is neither N nor WxH"
fi
((width > 0 && height > 0)) || die "SIZE '$size' must be positive"

repeats="${REPEATS:-1}"
[[ "$repeats" =~ ^[1-9][0-9]*$ ]] || die "REPEATS='$repeats' is not a positive integer"

povray="${POVRAY:-povray}"
povray_path="$(command -v "$povray" 2>/dev/null)" ||
    die "POV-Ray not found ('$povray'); install Debian's povray package or set POVRAY"
[[ -d "$shared" ]] || die "shared directory not found: $shared (expected at script dir/../../shared)"
shared="$(cd "$shared" && pwd)"
[[ -d "$shared/peers/povray" ]] || die "missing $shared/peers/povray"
if ((!povray_only)); then
    [[ -f "$rtprof" && -x "$rtprof" ]] || die "rtprof binary not found or not executable: '$rtprof'"
    rtprof="$(cd "$(dirname "$rtprof")" && pwd)/$(basename "$rtprof")"
fi
for scene in "${scenes[@]}"; do
    [[ -f "$shared/peers/povray/$scene.pov.gz" ]] || die "no POV-Ray scene: $shared/peers/povray/$scene.pov.gz"
    ((povray_only)) || [[ -f "$shared/spd/$scene.nff" ]] || die "no NFF scene: $shared/spd/$scene.nff"
done
command -v gzip >/dev/null || die "gzip not found"
if [[ -n "$images" ]]; then
    mkdir -p "$images" || die "cannot create $images"
fi
if [[ -n "$tsv" ]]; then
    : >"$tsv" || die "cannot write $tsv"
fi

work="$(mktemp -d "${TMPDIR:-/tmp}/povray-compare.XXXXXX")"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/home/.povray/3.7"
: >"$work/home/.povray/3.7/povray.conf"

# Runs "$@" with stdout and stderr to file $1 (shifted off); prints "wall cpu" in seconds,
# cpu being user + system time of the process and its children (bash's time keyword).
# Returns the command's status.
timed() {
    local log="$1" TIMEFORMAT='%3R %3U %3S' times status=0
    shift
    times="$({ time "$@" >"$log" 2>&1; } 2>&1)" || status=$?
    awk -v t="${times##*$'\n'}" 'BEGIN { split(t, f, " "); printf "%.3f %.3f\n", f[1], f[2] + f[3] }'
    return "$status"
}
# Median of the numbers on stdin ("NA" when there are none).
median() {
    sort -g | awk '{ v[NR] = $1 }
        END { if (NR == 0) print "NA"
              else if (NR % 2) print v[(NR + 1) / 2]
              else printf "%.3f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
# POV-Ray's statistics from its console log: parse, bounding and trace seconds; total,
# shadow, reflected, refracted and transmitted rays (0 when POV-Ray omits the line).
povray_stats() {
    awk '
        function secs(line) { sub(/.*\(/, "", line); sub(/ seconds\).*/, "", line); return line }
        /^ *Parse Time:/ { parse = secs($0) }
        /^ *Bounding Time:/ { bound = secs($0) }
        /^ *Trace Time:/ { trace = secs($0) }
        $1 == "Rays:" { rays = $2 }
        /^Shadow Ray Tests:/ { shadow = $4 }
        /^Reflected Rays:/ { refl = $3 }
        /^Refracted Rays:/ { refr = $3 }
        /^Transmitted Rays:/ { trans = $3 }
        END { printf "%s %s %s %d %d %d %d %d\n", (parse == "" ? "NA" : parse), (bound == "" ? "NA" : bound),
              (trace == "" ? "NA" : trace), rays, shadow, refl, refr, trans }' "$1"
}

# Median of column $2 of the lines in the array named $1 ("NA" entries skipped).
median_col() {
    local -n lines="$1"
    printf '%s\n' "${lines[@]}" | awk -v c="$2" 'NF >= c && $c != "NA" { print $c }' | median
}

run_povray() { # scene run -> prints "wall cpu", leaves $work/NAME.log and NAME.png
    local scene="$1" run="$2" t status=0
    rm -f "$work/$scene.png"
    t="$(cd "$work" && timed "$work/$scene.log" env -u POVINI -u POVRAYOPT HOME="$work/home" \
        "$povray_path" "+I$scene.pov" "+O$scene.png" "+W$width" "+H$height" -D +FN +WT1 -A)" ||
        status=$?
    if ((status != 0)) || [[ ! -s "$work/$scene.png" ]] || ! grep -q '^POV-Ray finished' "$work/$scene.log"; then
        tail -n 30 "$work/$scene.log" >&2
        die "POV-Ray failed on $scene (run $run, exit $status); log above" 1
    fi
    if grep -qiE 'Parse Error' "$work/$scene.log"; then
        grep -iE -A3 'Parse Error' "$work/$scene.log" >&2
        die "POV-Ray reported a parse error on $scene" 1
    fi
    printf '%s\n' "$t"
}

run_rtprof() { # scene run -> prints "wall cpu"
    local scene="$1" run="$2" t status=0
    rm -f "$work/$scene.rtprof.png"
    t="$(timed "$work/$scene.rtprof.log" "$rtprof" render "$shared/spd/$scene.nff" --spd \
        --size "${width}x$height" --threads 1 --variant "$variant" -o "$work/$scene.rtprof.png")" ||
        status=$?
    if ((status != 0)) || [[ ! -s "$work/$scene.rtprof.png" ]]; then
        tail -n 30 "$work/$scene.rtprof.log" >&2
        die "rtprof failed on $scene (run $run, exit $status); log above" 1
    fi
    printf '%s\n' "$t"
}

if [[ -n "$tsv" ]]; then
    printf '%s\t' scene width height variant repeats povray_s rtprof_s ratio povray_cpu_s rtprof_cpu_s \
        povray_parse_s povray_bounding_s povray_trace_s povray_rays povray_shadow_rays \
        povray_reflected_rays povray_refracted_rays >"$tsv"
    printf '%s\n' povray_transmitted_rays >>"$tsv"
fi

printf 'POV-Ray: %s +IN.pov +ON.png +W%s +H%s -D +FN +WT1 -A\n' "$povray_path" "$width" "$height"
((povray_only)) ||
    printf 'rtprof:  %s render SHARED/spd/N.nff --spd --size %sx%s --threads 1 --variant %s -o N.png\n' \
        "$rtprof" "$width" "$height" "$variant"
printf 'seconds of wall time of the whole process (cpu: user + system), median of %s run(s)\n' "$repeats"
printf 'POV-Ray parse, trace, rays and shadow rays from its own statistics\n\n'
row() { printf '%-8s %9s %9s %7s  %8s %8s  %9s %9s %9s %10s\n' "$@"; }
# Progress on stderr, only when it is a terminal.
progress() { [[ -t 2 ]] && printf '%-60s\r' "$1" >&2 || true; }
row scene 'povray s' 'rtprof s' ratio 'pov cpu' 'rt cpu' 'pov parse' 'pov trace' 'pov rays' 'pov shadow'

ratios=()
for scene in "${scenes[@]}"; do
    gzip -dc "$shared/peers/povray/$scene.pov.gz" >"$work/$scene.pov"
    pov_runs=() rt_runs=() stats_runs=()
    for run in $(seq "$repeats"); do
        progress "  $scene: POV-Ray run $run/$repeats..."
        pov_runs+=("$(run_povray "$scene" "$run")")
        stats_runs+=("$(povray_stats "$work/$scene.log")")
        if ((!povray_only)); then
            progress "  $scene: rtprof run $run/$repeats..."
            rt_runs+=("$(run_rtprof "$scene" "$run")")
        fi
    done
    progress ""
    pov_s="$(median_col pov_runs 1)" pov_cpu="$(median_col pov_runs 2)"
    parse_s="$(median_col stats_runs 1)" bound_s="$(median_col stats_runs 2)"
    trace_s="$(median_col stats_runs 3)" rays="$(median_col stats_runs 4)"
    shadow="$(median_col stats_runs 5)" refl="$(median_col stats_runs 6)"
    refr="$(median_col stats_runs 7)" trans="$(median_col stats_runs 8)"
    if ((povray_only)); then
        rt_s=NA rt_cpu=NA ratio=NA
    else
        rt_s="$(median_col rt_runs 1)" rt_cpu="$(median_col rt_runs 2)"
        ratio="$(awk -v r="$rt_s" -v p="$pov_s" 'BEGIN { printf "%.3f\n", (p > 0 ? r / p : 0) }')"
        ratios+=("$ratio")
    fi
    row "$scene" "$pov_s" "$rt_s" "$ratio" "$pov_cpu" "$rt_cpu" "$parse_s" "$trace_s" "$rays" "$shadow"
    if [[ -n "$tsv" ]]; then
        printf '%s\t' "$scene" "$width" "$height" "$variant" "$repeats" "$pov_s" "$rt_s" "$ratio" \
            "$pov_cpu" "$rt_cpu" "$parse_s" "$bound_s" "$trace_s" "$rays" "$shadow" "$refl" "$refr" >>"$tsv"
        printf '%s\n' "$trans" >>"$tsv"
    fi
    if [[ -n "$images" ]]; then
        cp "$work/$scene.png" "$images/$scene.povray.png"
        cp "$work/$scene.log" "$images/$scene.povray.log"
        if ((!povray_only)); then
            cp "$work/$scene.rtprof.png" "$images/$scene.rtprof.png"
            cp "$work/$scene.rtprof.log" "$images/$scene.rtprof.log"
        fi
    fi
    rm -f "$work/$scene.pov" "$work/$scene.png" "$work/$scene.rtprof.png"
done

echo
if ((povray_only)); then
    echo "POV-Ray only: no ratios, target not evaluated (target: geomean <= 0.5, max <= 0.8)"
    exit 0
fi
read -r geomean max < <(printf '%s\n' "${ratios[@]}" | awk '
    { s += log($1 > 0 ? $1 : 1e-9); if (NR == 1 || $1 > m) m = $1 }
    END { printf "%.3f %.3f\n", exp(s / NR), m }')
printf 'geomean ratio rtprof/povray: %s   max ratio: %s\n' "$geomean" "$max"
if awk -v g="$geomean" -v m="$max" 'BEGIN { exit !(g <= 0.5 && m <= 0.8) }'; then
    echo "target met (geomean <= 0.5 and max <= 0.8)"
else
    echo "target missed (needs geomean <= 0.5 and max <= 0.8)"
fi
exit 0
