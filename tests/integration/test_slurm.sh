#!/usr/bin/env bash
# A real single-node Slurm on this machine: munged, slurmctld and slurmd started here (root, state
# in a temporary folder, free ports) and stopped on exit. Through tools/slurm/submit.sh it renders
# a 4-tile image (merged by a dependent job) and a 3-frame turntable, and checks that every
# channel of every pixel has the bits of a single-process render.
#   test_slurm.sh SOFTTRACE SAME_BITS SOURCE_DIR WORK_DIR
# Fails, saying why, when Slurm is not installed (tools/dev.sh installs it) or does not start.
set -euo pipefail
softtrace=$1 same_bits=$2 src=$3 work=$4
scene=$src/tests/scenes/turntable.json

fail() {
  echo "test_slurm: FAILED: $*" >&2
  exit 1
}
for c in munged slurmctld slurmd sbatch squeue sinfo scontrol; do
  command -v "$c" >/dev/null ||
    fail "'$c' is missing: Slurm is not installed (tools/dev.sh installs munge slurmctld slurmd slurm-client)"
done
[ "$(id -u)" -eq 0 ] || fail "slurmd must start as root to run jobs; run this test as root"

rm -rf "$work"
mkdir -p "$work"
# Short: the munge socket's path must fit a sockaddr_un.
state=$(mktemp -d /tmp/softtrace-slurm.XXXXXX)
chmod 711 "$state"
pids=()
stop() {
  local status=$?
  if [ -n "${SLURM_CONF:-}" ] && [ ${#pids[@]} -ge 2 ]; then scancel --quiet --full --user=root 2>/dev/null || true; fi
  # Ours only, newest first: slurmd, slurmctld, munged.
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [ $status -ne 0 ]; then
    for f in "$state"/*.log; do echo "--- $f (last lines)" >&2; tail -n 15 "$f" >&2; done
  fi
  rm -rf "$state"
  exit $status
}
trap stop EXIT
trap 'exit 1' INT TERM

# Between attempts at a condition: up to $1 seconds.
wait_for() {
  local seconds=$1
  shift
  for ((i = 0; i < seconds * 4; i++)); do
    if "$@"; then return 0; fi
    sleep 0.25
  done
  return 1
}
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
free_port() {
  local p
  for _ in $(seq 100); do
    p=$((20000 + RANDOM % 40000))
    if port_free "$p" && port_free "$((p + 1))"; then
      echo "$p"
      return
    fi
  done
  fail "no free TCP port pair for slurmctld and slurmd"
}

# munge: a fresh key, our own socket.
head -c 1024 /dev/urandom >"$state/munge.key"
chmod 400 "$state/munge.key"
munged --foreground --force --key-file="$state/munge.key" --socket="$state/munge.sock" \
  --pid-file="$state/munged.pid" --seed-file="$state/munged.seed" >"$state/munged.log" 2>&1 &
pids+=($!)
wait_for 10 test -S "$state/munge.sock" || fail "munged did not start"

# slurm.conf for this host with the cores and memory slurmd finds.
node=$(slurmd -C | head -n 1)
[[ $node == NodeName=* ]] || fail "slurmd -C printed no node line: $node"
port=$(free_port)
mkdir -p "$state/ctld" "$state/spool"
cat >"$state/slurm.conf" <<CONF
ClusterName=softtrace-test
SlurmctldHost=$(hostname -s)(127.0.0.1)
AuthType=auth/munge
AuthInfo=socket=$state/munge.sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/slurmctld.log
SlurmdLogFile=$state/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
SwitchType=switch/none
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=10 State=UP
CONF
export SLURM_CONF=$state/slurm.conf
# Slurm's own variables from a surrounding allocation would confuse sbatch.
unset SLURM_JOB_ID SLURM_JOBID SLURM_ARRAY_TASK_ID

slurmctld -D -c -f "$SLURM_CONF" >"$state/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >"$state/slurmd.out" 2>&1 &
pids+=($!)
node_idle() { [ "$(sinfo -h -o %T 2>/dev/null)" = idle ]; }
wait_for 30 node_idle || fail "the Slurm node did not come up (sinfo: $(sinfo -h 2>&1 || true))"
echo "test_slurm: Slurm is up: $node"

# The single-process references.
cd "$work"
"$softtrace" render "$scene" --aov depth,normal,steps -q -o full.exr
for f in 0 1 2; do "$softtrace" render "$scene" --frame $f -q -o "turn-ref.$f.exr"; done

export SOFTTRACE=$softtrace
read -r tiles merge < <("$src/tools/slurm/submit.sh" tiles 4 "$scene" "$work/tiled.exr" \
  --aov depth,normal,steps)
read -r frames < <("$src/tools/slurm/submit.sh" frames 3 "$scene" "$work/turn.####.exr")
jobs_done() { [ -z "$(squeue -h -j "$tiles,$merge,$frames" 2>/dev/null)" ]; }
wait_for 120 jobs_done || fail "jobs still queued or running after 120 s: $(squeue -h 2>&1)"

# Every array task and the merge completed (finished jobs stay visible for MinJobAge, 300 s).
states=$(for j in "$tiles" "$merge" "$frames"; do scontrol -o show job "$j"; done |
  grep -o 'JobState=[A-Z_]*' | sort | uniq -c)
echo "test_slurm: job states: $(echo $states)"
[ "$(echo "$states" | awk '{ print $2 }')" = JobState=COMPLETED ] || fail "not every job completed: $states"
[ "$(echo "$states" | awk '{ print $1 }')" = 8 ] || fail "expected 8 jobs (4 tiles, merge, 3 frames): $states"
[ "$(ls "$work"/tiled.logs/*.log | wc -l)" = 5 ] || fail "expected 5 logs in tiled.logs/"
[ "$(ls "$work"/turn.logs/*.log | wc -l)" = 3 ] || fail "expected 3 logs in turn.logs/"

"$same_bits" full.exr tiled.exr || fail "the merged tiles differ from the single-process render"
for f in 0 1 2; do
  "$same_bits" "turn-ref.$f.exr" "turn.000$f.exr" || fail "frame $f differs from the single-process render"
done
echo "test_slurm: 4 tiles merged and 3 frames through Slurm have the single-process bits"
