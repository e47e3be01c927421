#!/usr/bin/env bash
# A sharded study on a real Slurm, compared byte for byte with the single-machine run.
#
# Installs the Debian packages slurmctld, slurmd, slurm-client and munge (apt-get; root
# needed, as in CI), writes a one-node slurm.conf for this host (select/cons_tres,
# proctrack/linuxproc, task/none: no cgroups), starts munged, slurmctld and slurmd, writes the
# scripts with `jointid cluster slurm --shards 4`, submits them with the generated submit
# script (a job array of 4 shard tasks and the merge job depending on it), waits, and
# compares the merged CSV with `jointid study` run on this machine; `jointid check
# --results` then holds the merged CSV to the study's [check].
#
# Exit 0 with a line starting `SKIP:` when Slurm cannot be installed or started here (no
# apt-get, not root, no package, daemons that do not come up). Exit 1 when Slurm runs and
# the shards fail or the merged result differs. Every daemon this script starts is stopped
# by its process id on exit.
#
# Environment: JOINTID (the binary; default target/release/jointid), SLURM_TEST_TIMEOUT
# (seconds to wait for the jobs; default 300). Worst case in
# all, apt-get included: about 13 minutes, inside the 20 minutes .ci/run allows.
set -uo pipefail
cd "$(dirname "$0")/../.."
ROOT=$PWD
JOINTID=${JOINTID:-$ROOT/target/release/jointid}
WAIT=${SLURM_TEST_TIMEOUT:-300}

skip() { echo "SKIP: slurm test: $*"; exit 0; }
fail() { echo "FAIL: slurm test: $*" >&2; exit 1; }

[ -x "$JOINTID" ] || fail "$JOINTID is not built (cargo build --release)"
[ "$(id -u)" = 0 ] || skip "needs root to install and start Slurm (CI runs as root)"

# 1. Packages.
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null \
    || ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
    command -v apt-get >/dev/null || skip "no apt-get to install slurmctld, slurmd, slurm-client, munge"
    export DEBIAN_FRONTEND=noninteractive
    install() { timeout 300 apt-get install -y --no-install-recommends slurmctld slurmd slurm-client munge >/tmp/jointid-slurm-apt.log 2>&1; }
    if ! install; then
        timeout 120 apt-get update >>/tmp/jointid-slurm-apt.log 2>&1
        install || skip "apt-get cannot install slurmctld slurmd slurm-client munge (see /tmp/jointid-slurm-apt.log)"
    fi
fi

WORK=$(mktemp -d /tmp/jointid-slurm.XXXXXX)
PIDS=()
cleanup() {
    for pid in "${PIDS[@]}"; do kill "$pid" 2>/dev/null; done
    sleep 1
    for pid in "${PIDS[@]}"; do kill -9 "$pid" 2>/dev/null; done
}
trap cleanup EXIT

# 2. Munge (authentication of the daemons and clients), else auth/none.
AUTH=auth/munge
MUNGE_SOCKET=$WORK/munge/munge.socket.2
# munged runs as user munge and wants its socket directory traversable by everyone.
chmod 755 "$WORK"
mkdir -p "$WORK/munge" && chown munge:munge "$WORK/munge" 2>/dev/null && chmod 755 "$WORK/munge"
if [ -r /etc/munge/munge.key ] && id munge >/dev/null 2>&1 \
    && runuser -u munge -- munged --socket="$MUNGE_SOCKET" --pid-file="$WORK/munge/munged.pid" \
        --log-file="$WORK/munge/munged.log" --seed-file="$WORK/munge/munged.seed" 2>"$WORK/munged.err"; then
    sleep 1
    PIDS+=("$(cat "$WORK/munge/munged.pid")")
else
    echo "munged does not start ($(head -c 300 "$WORK/munged.err" 2>/dev/null)); using auth/none"
    AUTH=auth/none
fi

# 3. A one-node cluster on this host.
HOST=$(hostname -s)
CPUS=$(nproc)
PORT_CTLD=${SLURM_TEST_PORT:-16817}
mkdir -p "$WORK/state" "$WORK/spool"
cat >"$WORK/slurm.conf" <<EOF
ClusterName=jointid-test
SlurmctldHost=$HOST
SlurmctldPort=$PORT_CTLD
SlurmdPort=$((PORT_CTLD + 1))
AuthType=$AUTH
CredType=cred/$([ "$AUTH" = auth/munge ] && echo munge || echo none)
AuthInfo=socket=$MUNGE_SOCKET
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SchedulerType=sched/builtin
NodeName=$HOST CPUs=$CPUS State=UNKNOWN
PartitionName=test Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$WORK/slurm.conf
slurmctld -D -f "$SLURM_CONF" >"$WORK/slurmctld.out" 2>&1 &
PIDS+=($!)
slurmd -D -f "$SLURM_CONF" -N "$HOST" >"$WORK/slurmd.out" 2>&1 &
PIDS+=($!)
up=
for _ in $(seq 60); do
    state=$(sinfo -h -n "$HOST" -o %t 2>/dev/null)
    case "$state" in idle*|mix*|alloc*) up=1; break ;; esac
    sleep 1
done
if [ -z "$up" ]; then
    echo "--- slurmctld.log"; tail -20 "$WORK/slurmctld.log" 2>/dev/null; tail -5 "$WORK/slurmctld.out"
    echo "--- slurmd.log"; tail -20 "$WORK/slurmd.log" 2>/dev/null; tail -5 "$WORK/slurmd.out"
    skip "slurmctld/slurmd did not bring node $HOST up within 60 s (node state: ${state:-none})"
fi
echo "slurm up: node $HOST ($CPUS cpus), $AUTH, $(sinfo --version)"

# 4. The study: the CI gate's, its model by absolute path, results in the work directory.
sed -e "s|^model = .*|model = \"$ROOT/models/paper-case-1.toml\"|" \
    -e "s|^csv = .*|csv = \"$WORK/single.csv\"|" studies/ci-bias.toml >"$WORK/study.toml"
"$JOINTID" study "$WORK/study.toml" --quiet >/dev/null || fail "the single-machine run failed"

# 5. The two commands of a cluster user.
"$JOINTID" cluster slurm "$WORK/study.toml" --shards 4 --partition test --time 00:10:00 \
    --dir "$WORK/slurm" --out "$WORK/merged.csv" || fail "jointid cluster slurm failed"
submitted=$(sh "$WORK/slurm/ci-bias.submit.sh") || fail "submission failed"
echo "$submitted"
merge_job=$(echo "$submitted" | sed -n 's/.*merge \([0-9]*\).*/\1/p')
array_job=$(echo "$submitted" | sed -n 's/.*shards \([0-9]*\).*/\1/p')

deadline=$((SECONDS + WAIT))
while squeue -h -j "$array_job,$merge_job" 2>/dev/null | grep -q .; do
    [ $SECONDS -lt $deadline ] || { squeue; fail "jobs still queued or running after $WAIT s"; }
    sleep 2
done
ls "$WORK/slurm/logs"
for log in "$WORK"/slurm/logs/*; do echo "--- $log"; cat "$log"; done

# 6. The comparison.
[ -f "$WORK/merged.csv" ] || fail "no merged CSV: a shard or the merge job failed (logs above)"
for k in 1 2 3 4; do
    [ -f "$WORK/slurm/ci-bias.shard-$k-of-4.csv" ] || fail "shard $k of 4 wrote no file"
done
cmp "$WORK/single.csv" "$WORK/merged.csv" || fail "the merged CSV differs from the single-machine CSV"
"$JOINTID" check "$WORK/study.toml" --results "$WORK/merged.csv" || fail "check --results on the merged CSV"
echo "PASS: slurm test: 4 shards through sbatch, merged CSV byte-identical to the single run ($(wc -c <"$WORK/merged.csv") bytes)"
rm -rf "$WORK"
