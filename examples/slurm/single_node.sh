#!/usr/bin/env bash
# Brings up a one-node Slurm cluster from Debian's packages (no systemd, no cgroups) and runs the
# scale-out recipes of docs/scaling.md on it: a sharded `generate` array job with an `afterok` merge, checked
# byte for byte against one unsharded run, and a sharded `study --quick` array job merged
# afterwards, checking that a merge without `--quick` is refused. For checking the recipes by hand
# on a scratch machine (it installs packages and starts daemons as root); not part of CI.
#
#   sudo bash examples/slurm/single_node.sh            # from the repository's root
#   SCENARIOS="situation1 situation2" STUDY=0 sudo bash examples/slurm/single_node.sh
set -euo pipefail
cd "$(dirname "$0")/../.."

WORK=${WORK:-/tmp/patchflow-slurm}
SCENARIOS=${SCENARIOS:-"situation1 situation2 situation3 situation4 situation5"}
SHARDS=${SHARDS:-4}
STUDY=${STUDY:-1}
mkdir -p "$WORK/logs"

# 1. Packages and the binary.
if ! command -v slurmctld >/dev/null; then
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
fi
cargo build --release -q
BIN=$(pwd)/target/release/patchflow

# 2. A one-node cluster: munge for authentication, slurmctld and slurmd in the foreground of
#    background jobs, Linux process tracking instead of cgroups (containers rarely allow them).
CPUS=$(nproc)
MEM_MB=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 512 ))
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm /run/munge
cat > /etc/slurm/slurm.conf <<CONF
ClusterName=patchflow
SlurmctldHost=localhost
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$WORK/logs/jobcomp.txt
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
SlurmUser=root
NodeName=localhost CPUs=$CPUS RealMemory=$MEM_MB State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
[ -f /etc/munge/munge.key ] || mungekey --create --keyfile /etc/munge/munge.key
chown -R munge:munge /etc/munge /run/munge 2>/dev/null || true
pgrep -x munged >/dev/null || su -s /bin/sh munge -c munged
pgrep -x slurmctld >/dev/null || (slurmctld -D >"$WORK/logs/slurmctld.out" 2>&1 &)
pgrep -x slurmd >/dev/null || (slurmd -D >"$WORK/logs/slurmd.out" 2>&1 &)
for _ in $(seq 30); do sinfo -h -o %T 2>/dev/null | grep -qE 'idle|mix|alloc' && break; sleep 1; done
sinfo

wait_for() { # job id: waits until the job (and its array tasks) left the queue; every one of
  # them must have ended COMPLETED in the job completion log (no accounting daemon here)
  while squeue -h -j "$1" 2>/dev/null | grep -q .; do sleep 5; done
  sleep 2
  local ended failed
  ended=$(grep -cE "JobId=$1[ _]|ArrayJobId=$1 " "$WORK/logs/jobcomp.txt" || true)
  failed=$(grep -E "JobId=$1[ _]|ArrayJobId=$1 " "$WORK/logs/jobcomp.txt" | grep -vc 'JobState=COMPLETED' || true)
  if [ "$ended" = 0 ] || [ "$failed" != 0 ]; then
    echo "job $1 did not complete:"; grep -E "JobId=$1|ArrayJobId=$1 " "$WORK/logs/jobcomp.txt"; exit 1
  fi
}

# 3. Generate: docs/scaling.md's array job, then the same command without --shard once (afterok).
DATA=$WORK/data-sharded
rm -rf "$DATA" "$WORK/data-single"
ARRAY=$(sbatch --parsable --array=0-$((SHARDS - 1)) --cpus-per-task=1 \
  --output="$WORK/logs/generate-%A_%a.out" --error="$WORK/logs/generate-%A_%a.err" \
  --wrap "$BIN generate $SCENARIOS --out $DATA --seed 7 --shard \${SLURM_ARRAY_TASK_ID}/$SHARDS")
MERGE=$(sbatch --parsable --kill-on-invalid-dep=yes --dependency=afterok:"$ARRAY" --output="$WORK/logs/generate-merge.out" \
  --wrap "$BIN generate $SCENARIOS --out $DATA --seed 7")
wait_for "$ARRAY"; wait_for "$MERGE"
"$BIN" generate $SCENARIOS --out "$WORK/data-single" --seed 7 >/dev/null
diff -r "$DATA" "$WORK/data-single" && echo "generate: sharded == single run ($(find "$DATA" -type f | wc -l) files)"

# 4. Study: docs/scaling.md's array job with --quick, merged with --quick; a merge without it refused.
if [ "$STUDY" = 1 ]; then
  OUT=$WORK/study-rate
  rm -rf "$OUT"
  ARRAY=$(sbatch --parsable --array=0-2 --cpus-per-task=1 \
    --output="$WORK/logs/study-%A_%a.out" --error="$WORK/logs/study-%A_%a.err" \
    --wrap "$BIN study rate --quick --out $OUT --shard \${SLURM_ARRAY_TASK_ID}/3")
  MERGE=$(sbatch --parsable --kill-on-invalid-dep=yes --dependency=afterok:"$ARRAY" --output="$WORK/logs/study-merge.out" \
    --wrap "$BIN study rate --quick --merge --out $OUT")
  wait_for "$ARRAY"; wait_for "$MERGE"
  test -s "$OUT/study.json" && echo "study: merged $(ls "$OUT/points" | wc -l) points"
  rm -rf "$WORK/study-rate-full"; cp -r "$OUT" "$WORK/study-rate-full"
  if "$BIN" study rate --merge --out "$WORK/study-rate-full" 2>"$WORK/logs/refused.err"; then
    echo "a quick study merged without --quick was accepted"; exit 1
  fi
  echo "study: merge without --quick refused: $(head -c 300 "$WORK/logs/refused.err")"
fi
echo "all recipes held; delete $WORK when done"
