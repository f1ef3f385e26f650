#!/usr/bin/env bash
# The suite on a real Slurm cluster: starts a single-node Slurm on this machine (munge,
# slurmctld and slurmd on localhost, a private configuration under OUT), submits the
# suite as a two-task job array (`rtprof suite --shard $SLURM_ARRAY_TASK_ID/2`) and a
# merge job that depends on it, waits for the merge, and checks the merged results equal
# an unsharded run of the same suite (scripts/same-counts.py). Stops the daemons it
# started on exit. Needs root (it installs slurm-wlm and munge when missing).
#
#   scripts/slurm-suite.sh RTPROF WHOLE_DIR OUT_DIR [SUITE_ARGS...]
#
# RTPROF: the rtprof binary; WHOLE_DIR: an unsharded `rtprof suite SUITE_ARGS -o
# WHOLE_DIR` run; OUT_DIR: where the parts, the merge and Slurm's files go (emptied).
# CI runs it with the quick suite; docs/sharding.md explains it.
set -euo pipefail

if [ "$#" -lt 3 ]; then
    sed -n '2,13p' "$0" >&2
    exit 2
fi
rtprof=$(realpath "$1")
whole=$(realpath "$2")
out=$3
shift 3
suite_args=("$@")
here=$(dirname "$(realpath "$0")")

bash "$here/install-packages.sh" --no-recommends slurm-wlm munge

rm -rf "$out"
mkdir -p "$out/slurm/state" "$out/slurm/spool"
out=$(realpath "$out")
etc="$out/slurm"
started=()
cleanup() {
    for pidfile in "${started[@]}"; do
        [ -f "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null || true
    done
}
trap cleanup EXIT

# Munge authenticates Slurm's messages; its Debian package ships a key.
if ! munge -n >/dev/null 2>&1; then
    mkdir -p /run/munge && chown munge:munge /run/munge
    [ -s /etc/munge/munge.key ] || (umask 077 && dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none && chown munge:munge /etc/munge/munge.key)
    runuser -u munge -- /usr/sbin/munged
    # munged runs as its own user and cannot write under OUT: record its pid here.
    pgrep -u munge -n -x munged > "$etc/munged.pid"
    started+=("$etc/munged.pid")
    munge -n >/dev/null
fi

# One node, this machine, with its cores; no cgroups (containers often lack them), no
# accounting database. Private ports so a site's Slurm, if any, is left alone.
node=$(hostname -s)
cpus=$(nproc)
memory=$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)
cat > "$etc/slurm.conf" <<EOF
ClusterName=rtprof
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$etc/state
SlurmdSpoolDir=$etc/spool
SlurmctldPidFile=$etc/slurmctld.pid
SlurmdPidFile=$etc/slurmd.pid
SlurmctldLogFile=$etc/slurmctld.log
SlurmdLogFile=$etc/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=rtprof Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$etc/slurm.conf"
slurmctld -c -f "$SLURM_CONF"
started+=("$etc/slurmctld.pid")
slurmd -c -f "$SLURM_CONF"
started+=("$etc/slurmd.pid")
for _ in $(seq 60); do
    state=$(sinfo -h -n "$node" -o %T 2>/dev/null || true)
    [ "$state" = "idle" ] && break
    sleep 1
done
if [ "${state:-}" != "idle" ]; then
    echo "slurm-suite: the node is '${state:-unknown}', not idle, after 60 s" >&2
    tail -5 "$etc/slurmctld.log" "$etc/slurmd.log" >&2 || true
    exit 1
fi
echo "slurm-suite: Slurm $(sinfo -V | awk '{print $2}') up: node $node, $cpus CPUs"

# The job array: shard I of 2 per task, each on one CPU (the shards may run together).
start=$(date +%s)
quoted=$(printf ' %q' "${suite_args[@]}")
array=$(sbatch --parsable --job-name=rtprof-suite --array=1-2 --cpus-per-task=1 \
    --output="$out/shard-%a.log" \
    --wrap="$(printf %q "$rtprof") suite$quoted --shard \$SLURM_ARRAY_TASK_ID/2 -o $(printf %q "$out")/part-\$SLURM_ARRAY_TASK_ID")
echo "slurm-suite: job array $array submitted"
# The merge starts when every task of the array ended well; --wait returns its exit code.
if ! sbatch --wait --parsable --job-name=rtprof-merge --dependency=afterok:"$array" \
    --kill-on-invalid-dep=yes --output="$out/merge.log" \
    --wrap="$(printf %q "$rtprof") merge $(printf %q "$out")/part-1 $(printf %q "$out")/part-2 -o $(printf %q "$out")/merged" >/dev/null; then
    echo "slurm-suite: the merge job failed" >&2
    tail -5 "$out"/shard-*.log "$out/merge.log" >&2 || true
    exit 1
fi
echo "slurm-suite: array and merge done in $(($(date +%s) - start)) s"
python3 "$here/same-counts.py" "$whole/results.json" "$out/merged/results.json" "$out/merged"
