#!/usr/bin/env bash
# SLURM for real (integration check, not part of tools/test.sh): starts a one-node SLURM cluster on this machine
# (munged, slurmctld, slurmd; loopback only, private config, state and sockets under a temporary folder), submits
# tools/slurm_array_example.sh on the `tiny` block exactly as its header says (one array task per tile, then
# `sacfuse merge` with --dependency=afterany), waits for both, and checks that the merged fused.las has the same
# points as `sacfuse run` of the same config in another output folder. Prints PASS or FAIL with the numbers and
# stops every daemon it started (also on error or Ctrl-C).
#
#   tools/bench/slurm_e2e.sh [WORKDIR]       # as root; WORKDIR defaults to a new folder under /tmp, kept on exit
#
# Installs Debian's slurm-wlm and munge with apt-get when missing (they are not in tools/install_deps.sh: only this
# script uses them). Runs as root: slurmd must, and the jobs run as the submitting user.
# Environment: SACFUSE_BIN (default: build/bin/sacfuse of this repository, else `sacfuse` on PATH);
#   SLURM_E2E_TIMEOUT_S (default 900) for the jobs; SLURM_E2E_TILE_M (default 20) the tile size;
#   SLURM_E2E_PORT (default 6817; slurmd uses the next port) when those ports are taken;
#   SLURM_E2E_BASELINE=1 first times an array of as many `true` tasks (SLURM's own per-task cost on this machine).
# Exit: 0 PASS, 1 FAIL (jobs failed, timed out, or the clouds differ), 2 setup error (cluster did not come up).
set -euo pipefail
REPO="$(cd "$(dirname "$0")/../.." && pwd)"
if [ "$(id -u)" -ne 0 ]; then echo "slurm_e2e: run as root (slurmd needs it)" >&2; exit 2; fi

BIN="${SACFUSE_BIN:-}"
if [ -z "$BIN" ]; then
  if [ -x "$REPO/build/bin/sacfuse" ]; then BIN="$REPO/build/bin/sacfuse"; else BIN="$(command -v sacfuse || true)"; fi
fi
if [ -z "$BIN" ] || [ ! -x "$BIN" ]; then
  echo "slurm_e2e: no sacfuse binary (build it with tools/build.sh --target sacfuse, or set SACFUSE_BIN)" >&2; exit 2
fi
BIN="$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN")"
export PATH="$(dirname "$BIN"):$PATH"   # the array script and the merge job call `sacfuse`; sbatch exports PATH

TIMEOUT_S="${SLURM_E2E_TIMEOUT_S:-900}"
TILE_M="${SLURM_E2E_TILE_M:-20}"
PORT="${SLURM_E2E_PORT:-6817}"
W="${1:-$(mktemp -d /tmp/sacfuse-slurm-e2e.XXXXXX)}"
mkdir -p "$W"
W="$(cd "$W" && pwd)"
log() { echo "[slurm_e2e] $*"; }

# --- packages ---------------------------------------------------------------------------------------------------
need=()
for p in slurm-wlm munge python3; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  log "installing ${need[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${need[@]}"
fi

# --- daemons: private munged + slurmctld + slurmd, stopped by the trap ------------------------------------------
C="$W/cluster"
rm -rf "$C"
mkdir -p "$C/state" "$C/spool" "$C/munge" "$C/log"
PIDFILES=("$C/slurmd.pid" "$C/slurmctld.pid" "$C/munge/munged.pid")
stop_daemons() {
  local f pid i
  for f in "${PIDFILES[@]}"; do
    [ -f "$f" ] || continue
    pid="$(cat "$f" 2>/dev/null || true)"
    [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null || continue
    kill -TERM "$pid" 2>/dev/null || true
    for i in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
    if kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid" 2>/dev/null || true; fi
  done
}
trap stop_daemons EXIT
trap 'exit 130' INT TERM

for port in "$PORT" "$((PORT + 1))"; do
  if ss -Hltn "sport = :$port" 2>/dev/null | grep -q .; then
    echo "slurm_e2e: port $port is in use (another SLURM?); set SLURM_E2E_PORT" >&2; exit 2
  fi
done

# munged refuses a key or folders others can write; its own key, readable by root only.
chmod 700 "$C/munge"
dd if=/dev/urandom of="$C/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$C/munge/munge.key"
SOCK="$C/munge/munge.socket"
/usr/sbin/munged --force --key-file="$C/munge/munge.key" --socket="$SOCK" --pid-file="$C/munge/munged.pid" \
  --log-file="$C/log/munged.log" --seed-file="$C/munge/munged.seed"
munge -n --socket="$SOCK" | unmunge --socket="$SOCK" >/dev/null || { echo "slurm_e2e: munged does not answer" >&2; exit 2; }

HOST="$(hostname -s)"
NCPU="$(nproc)"
MEM_MB=$(( $(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 1024 - 1024 ))   # what slurmd finds, less 1 GiB
export SLURM_CONF="$C/slurm.conf"
cat > "$SLURM_CONF" <<EOF
# Written by tools/bench/slurm_e2e.sh: one node on loopback, no accounting, no cgroups.
ClusterName=sacfuse-e2e
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SOCK
StateSaveLocation=$C/state
SlurmdSpoolDir=$C/spool
SlurmctldPidFile=$C/slurmctld.pid
SlurmdPidFile=$C/slurmd.pid
SlurmctldLogFile=$C/log/slurmctld.log
SlurmdLogFile=$C/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU_Memory
ReturnToService=2
MinJobAge=600
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$NCPU RealMemory=$MEM_MB State=UNKNOWN
PartitionName=e2e Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
log "cluster config $SLURM_CONF (node $HOST, $NCPU CPUs, $MEM_MB MB)"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
up=0
for i in $(seq 1 60); do
  state="$(sinfo -h -n "$HOST" -o '%t' 2>/dev/null | head -1 || true)"
  if [ "$state" = idle ]; then up=1; break; fi
  sleep 1
done
if [ "$up" != 1 ]; then
  echo "slurm_e2e: node $HOST not idle after 60 s (state: '${state:-none}'); logs in $C/log" >&2
  tail -n 20 "$C/log/slurmctld.log" "$C/log/slurmd.log" >&2 || true
  exit 2
fi
log "node $HOST idle: $(sinfo -h -o '%P %a %D %t %C')"

# --- block and configs ------------------------------------------------------------------------------------------
B="$W/block"
if [ ! -f "$B/metadata.json" ]; then
  log "simulating the tiny block into $B"
  sacfuse simulate --preset tiny --seed 7 --out "$B" >"$W/simulate.log" 2>&1
fi
rm -rf "$B/out_slurm" "$B/out_run"
for name in slurm run; do
  cat > "$B/$name.yaml" <<EOF
# tools/bench/slurm_e2e.sh: the tiny block, ${TILE_M} m tiles; slurm.yaml and run.yaml differ only in output.dir.
input: {path: "."}
output: {dir: "out_$name", format: las}  # LAS: las_same_points.py compares uncompressed records
tiling: {tile_size_m: $TILE_M}
EOF
done
CONFIG="$B/slurm.yaml"

# Waits until none of the jobs (comma-separated ids) is queued or running; after TIMEOUT_S cancels them and fails.
wait_jobs() {
  local deadline=$(( $(date +%s) + TIMEOUT_S ))
  while squeue -h -j "$1" -o '%i' 2>/dev/null | grep -q .; do
    if [ "$(date +%s)" -ge "$deadline" ]; then
      echo "FAIL: jobs still queued or running after ${TIMEOUT_S} s:" >&2
      squeue -j "$1" >&2 || true
      scancel ${1//,/ } 2>/dev/null || true
      exit 1
    fi
    sleep 1
  done
}
seconds_since() { python3 -c "import sys, time; print(f'{time.time() - float(sys.argv[1]):.1f}')" "$1"; }

# --- submit as tools/slurm_array_example.sh's header says (smaller per-task resources for this node) ------------
cd "$W"
mkdir -p logs
cd logs
N=$(sacfuse plan "$CONFIG" --list | wc -l)
if [ "$N" -lt 2 ]; then echo "slurm_e2e: the plan has $N tiles; expected several" >&2; exit 1; fi
if [ "${SLURM_E2E_BASELINE:-0}" = 1 ]; then
  tb=$(date +%s.%N)
  BASE=$(sbatch --parsable --array=0-$((N - 1)) --cpus-per-task=1 --mem=1G --output=/dev/null --wrap true)
  wait_jobs "${BASE%%;*}"
  log "baseline: an array of $N \`true\` tasks took $(seconds_since "$tb") s from submission to the last one's end"
fi
t0=$(date +%s.%N)
JOB=$(sbatch --parsable --array=0-$((N - 1)) --cpus-per-task=1 --mem=1G --export=ALL,CONFIG="$CONFIG" \
  "$REPO/tools/slurm_array_example.sh")
JOB="${JOB%%;*}"
MERGE=$(sbatch --parsable --dependency=afterany:"$JOB" --cpus-per-task=1 --mem=2G --output=sacfuse-merge-%j.log \
  --wrap "sacfuse merge $CONFIG")
MERGE="${MERGE%%;*}"
log "submitted array job $JOB (tasks 0-$((N - 1)), $N tiles) and merge job $MERGE (afterany:$JOB)"

wait_jobs "$JOB,$MERGE"
slurm_s=$(seconds_since "$t0")

# Final states from slurmctld (no accounting database; MinJobAge keeps ended jobs for 10 minutes).
states="$(scontrol -o show job "$JOB" | grep -o 'JobState=[A-Z_]*' | sort | uniq -c | tr -s ' ' | tr '\n' ' ')"
array_ok=$(scontrol -o show job "$JOB" | grep -c 'JobState=COMPLETED .*ExitCode=0:0' || true)
merge_line="$(scontrol -o show job "$MERGE")"
merge_state="$(grep -o 'JobState=[A-Z_]*' <<<"$merge_line")"
merge_exit="$(grep -o ' ExitCode=[0-9:]*' <<<"$merge_line" | tr -d ' ')"
log "array tasks: $states($array_ok of $N completed with exit 0); merge: $merge_state $merge_exit; wall ${slurm_s} s"

# --- the same config with `sacfuse run` ------------------------------------------------------------------------
t1=$(date +%s.%N)
sacfuse run "$B/run.yaml" >"$W/run.log" 2>&1 || { echo "FAIL: sacfuse run failed (log: $W/run.log)"; exit 1; }
run_s=$(seconds_since "$t1")

fail=0
if [ "$array_ok" != "$N" ] || [ "$merge_state" != JobState=COMPLETED ] || [ "$merge_exit" != ExitCode=0:0 ]; then
  echo "FAIL: SLURM jobs did not all complete (logs in $W/logs)"
  fail=1
fi
if [ ! -f "$B/out_slurm/fused.las" ]; then
  echo "FAIL: no $B/out_slurm/fused.las"
  exit 1
fi
python3 "$REPO/tools/bench/las_same_points.py" "$B/out_slurm/fused.las" "$B/out_run/fused.las" || fail=1
if [ "$fail" = 0 ]; then
  echo "PASS: $N tiles as a SLURM array on $HOST ($NCPU CPUs) in ${slurm_s} s (submit to merged);" \
       "sacfuse run ${run_s} s; the same points"
  exit 0
fi
echo "FAIL (work folder $W)"
exit 1
