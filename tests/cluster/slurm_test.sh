#!/usr/bin/env bash
# scripts/cluster/slurm-render through a real Slurm: a single-node cluster
# (munged, slurmctld, slurmd on localhost, configured here) renders a scene as a job
# array and merges it, bit for bit the single render; then a task is cancelled on
# purpose, the gap is named, and running the command again renders only what is
# missing.
#   slurm_test.sh VKRT SOURCE_DIR
source "$(dirname "$0")/cluster_lib.sh"

step "starting munged, slurmctld and slurmd"
for program in munged slurmctld slurmd sbatch; do
  command -v "$program" >/dev/null || fail "no $program: scripts/setup --tests installs slurm-wlm and munge"
done
mkdir -m 700 "$scratch/munge"
mkdir -p "$scratch/state" "$scratch/spool"
head -c 1024 /dev/urandom >"$scratch/munge/munge.key"
chmod 400 "$scratch/munge/munge.key"
munged --force --key-file="$scratch/munge/munge.key" --socket="$scratch/munge/socket" \
  --pid-file="$scratch/munge/pid" --log-file="$scratch/munge/log" --seed-file="$scratch/munge/seed"
cleanups+=('stop_daemon "$scratch/munge/pid"')
node=$(hostname -s)
export SLURM_CONF="$scratch/slurm.conf"
cat >"$SLURM_CONF" <<CONF
ClusterName=vkrt-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$scratch/munge/socket
CredType=cred/munge
StateSaveLocation=$scratch/state
SlurmdSpoolDir=$scratch/spool
SlurmctldPidFile=$scratch/slurmctld.pid
SlurmdPidFile=$scratch/slurmd.pid
SlurmctldLogFile=$scratch/slurmctld.log
SlurmdLogFile=$scratch/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF"
cleanups+=('stop_daemon "$scratch/slurmctld.pid"')
slurmd -f "$SLURM_CONF" -N "$node"
cleanups+=('stop_daemon "$scratch/slurmd.pid"')
node_idle() { [ "$(sinfo -h -o %t)" = idle ]; }
wait_for 180 node_idle || fail "the node never became idle: $(sinfo 2>&1); $(tail -5 "$scratch/slurmctld.log")"

slurm_render() {
  "$scripts/slurm-render" "$scene" --spp "$spp" --tasks 4 --vkrt "$vkrt" "$@" -- "${render_options[@]}"
}

step "a job array and a merge job: the single render, bit for bit"
slurm_render --dir "$scratch/parts" -o "$scratch/slurm.exr" --wait
expect_whole "$scratch/slurm.exr"
[ "$(ls "$scratch/parts"/samples-*.exr | wc -l)" -eq 4 ] || fail "expected 4 partials: $(ls "$scratch/parts")"

step "a task cancelled on purpose leaves a gap that merge names"
out=$(slurm_render --dir "$scratch/gap" -o "$scratch/gap.exr" --sbatch --hold)
echo "$out"
render_job=$(sed -n 's/^render job \([0-9]*\).*/\1/p' <<<"$out")
merge_job=$(sed -n 's/^merge job \([0-9]*\).*/\1/p' <<<"$out")
[ -n "$render_job" ] && [ -n "$merge_job" ] || fail "slurm-render did not name its jobs"
scancel "${render_job}_3"
scontrol release "$render_job" "$merge_job" 2>/dev/null || scontrol release "$render_job"
jobs_gone() { [ -z "$(squeue -h -j "$render_job,$merge_job" 2>/dev/null)" ]; }
wait_for 600 jobs_gone || fail "the jobs did not end: $(squeue)"
[ ! -e "$scratch/gap.exr" ] || fail "the merge job ran although a task was cancelled"
if "$vkrt" merge --samples "0:$spp" "$scratch/gap"/samples-*.exr -o "$scratch/gap.exr" 2>"$scratch/merge.err"; then
  fail "merge accepted partials with a gap"
fi
grep -q "samples 6:8 are missing" "$scratch/merge.err" || fail "merge did not name the gap: $(cat "$scratch/merge.err")"
missing=$("$vkrt" merge --missing --samples "0:$spp" "$scratch/gap"/samples-*.exr)
[ "$missing" = "6:8" ] || fail "merge --missing listed '$missing', not 6:8"

step "the same command again renders only the missing samples"
out=$(slurm_render --dir "$scratch/gap" -o "$scratch/gap.exr" --wait)
echo "$out"
grep -q "samples 6:7,7:8$" <<<"$out" || fail "the rerun did not submit only 6:8"
expect_whole "$scratch/gap.exr"
echo "PASS"
