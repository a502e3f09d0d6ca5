#!/usr/bin/env bash
# `make test-slurm`: starts a real one-node Slurm cluster from the Debian packages (munge,
# slurmctld, slurmd; scripts/debian-packages-slurm.txt), runs the shipped recipe
# (scripts/slurm/submit.sh: a job array of shards and a merge job that depends on it) and checks
# that every merged report equals a single-process run (`aalab same-results`), then stops what
# it started. Cases:
#   run    the quick suite in SHARDS shards with a shared reference cache
#   motion moving scenes over several frames, references rendered by a first job array
#          (`submit.sh --references-first`), so the split by frame is exercised
#   sweep  a grid sweep in SHARDS shards of one CPU each (--cpus-per-task=1 through
#          AALAB_SBATCH_ARGS: the shards run --threads 1, the single sweep all threads)
#   rerun  the recipe for a failed shard: shard 1 fails once (a wrapper around the binary), the
#          merge job waits, `submit.sh --rerun 1` reruns shard 1 and the merge job runs
# Not part of `make test`: it installs and starts daemons and needs root (docs/cluster.md).
#
# Everything lives in a private temp folder: slurm.conf (SLURM_CONF points every Slurm command
# at it; no Slurm or munge configuration under /etc is read or changed), a munge key made for the test with munged on a
# private socket, state, spool, logs, and the runs. Ports are picked free. The daemons run in the
# foreground as children of this script, each in its own session (setsid: a Ctrl-C reaches this
# script, not them); on exit (also on failure or Ctrl-C) the jobs are cancelled, the daemons
# stopped and the folder removed (KEEP=1 keeps it).
#
# Environment: BUILD (build folder, default build), JOBS, SHARDS (default 3), KEEP=1,
# WAIT_S (longest wait for the cluster or for one case's jobs, default 300).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD=${BUILD:-build}
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}
SHARDS=${SHARDS:-3}
WAIT_S=${WAIT_S:-300}
KEEP=${KEEP:-0}

say() { echo "test-slurm: $*"; }
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }
test_start=$(now)
failures=0

if ! [[ "$SHARDS" =~ ^[1-9][0-9]*$ ]] || [ "$SHARDS" -lt 2 ]; then
  say "SHARDS must be an integer of at least 2 (the rerun case reruns shard 1), got '$SHARDS'" >&2
  exit 2
fi
if [ "$(id -u)" -ne 0 ]; then
  say "needs root: it installs the Slurm and munge packages and starts munged, slurmctld and slurmd (as root) for one test" >&2
  exit 2
fi

# --- dependencies and the binary -------------------------------------------------------------
t=$(now)
bash scripts/install-deps.sh scripts/debian-packages-slurm.txt
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release > "$BUILD.configure.log" 2>&1 || { cat "$BUILD.configure.log"; exit 1; }
fi
cmake --build "$BUILD" -j "$JOBS" --target aalab
AALAB_BIN="$ROOT/$BUILD/aalab"
say "phase deps+build: $(since "$t") s"

# --- a private one-node cluster --------------------------------------------------------------
# Slurm settings from the caller's shell (a Slurm job, SBATCH_PARTITION, ...) must not leak in.
while read -r v; do unset "$v"; done < <(compgen -e | grep -E '^(SLURM|SBATCH|SALLOC|SRUN|SQUEUE|SINFO|SCONTROL|SCANCEL)_' || true)
T=$(mktemp -d "${TMPDIR:-/tmp}/aalab-slurm.XXXXXX")
chmod 711 "$T"  # munged wants every folder above its socket searchable and none writable by others
munged_pid="" ctld_pid="" slurmd_pid=""

stop_pid() {  # stop_pid PID NAME: SIGTERM, then SIGKILL after 20 s
  local pid=$1 name=$2 i
  [ -n "$pid" ] || return 0
  kill -0 "$pid" 2>/dev/null || { wait "$pid" 2>/dev/null; return 0; }
  kill -TERM "$pid" 2>/dev/null
  for ((i = 0; i < 200; ++i)); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  if kill -0 "$pid" 2>/dev/null; then
    say "$name (pid $pid) did not stop in 20 s; killing it" >&2
    kill -KILL "$pid" 2>/dev/null
  fi
  wait "$pid" 2>/dev/null || true
}

cleanup() {
  local rc=$? i
  set +e
  trap - EXIT INT TERM
  if [ -n "$ctld_pid" ] && kill -0 "$ctld_pid" 2>/dev/null; then
    mapfile -t left < <(squeue -h -o %A 2>/dev/null)
    if [ ${#left[@]} -gt 0 ]; then
      scancel "${left[@]}" 2>/dev/null
      for ((i = 0; i < 300; ++i)); do [ -z "$(squeue -h -o %A 2>/dev/null)" ] && break; sleep 0.1; done
    fi
  fi
  stop_pid "$slurmd_pid" slurmd
  stop_pid "$ctld_pid" slurmctld
  stop_pid "$munged_pid" munged
  if [ "$KEEP" = 1 ]; then
    say "kept $T (slurm.conf, logs, runs)"
  else
    rm -rf "$T"
  fi
  say "total $(since "$test_start") s: $([ $rc -eq 0 ] && echo PASS || echo FAIL)"
  exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

show_logs() {
  local f
  for f in "$T"/log/*; do
    [ -f "$f" ] || continue
    echo "==== $f (last 40 lines)" >&2
    tail -n 40 "$f" >&2
  done
}

port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
pick_port() {  # a port nothing listens on, from 20000-39999, other than $1
  local p i
  for ((i = 0; i < 200; ++i)); do
    p=$((20000 + (RANDOM * 32768 + RANDOM) % 20000))
    [ "$p" != "${1:-}" ] && port_free "$p" && { echo "$p"; return 0; }
  done
  say "found no free TCP port in 20000-39999" >&2
  return 1
}

wait_until() {  # wait_until SECONDS WHAT COMMAND...: polls COMMAND every 0.2 s
  local limit=$1 what=$2 start
  shift 2
  start=$(date +%s)
  until "$@" > /dev/null 2>&1; do
    if [ $(($(date +%s) - start)) -ge "$limit" ]; then
      say "FAIL: $what not within $limit s" >&2
      show_logs
      return 1
    fi
    sleep 0.2
  done
}

t=$(now)
host=$(hostname -s)
mkdir -p "$T/munge" "$T/state" "$T/spool" "$T/log" "$T/run"
chmod 700 "$T/state" "$T/spool"
chmod 711 "$T/munge"
dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 status=none
chmod 600 "$T/munge/munge.key"
munge_socket="$T/munge/munge.socket"
setsid munged --foreground --socket="$munge_socket" --key-file="$T/munge/munge.key" \
  --pid-file="$T/munge/munged.pid" --seed-file="$T/munge/munged.seed" \
  --log-file="$T/log/munged.log" > "$T/log/munged.out" 2>&1 &
munged_pid=$!
wait_until 30 "munged answering on $munge_socket" bash -c "munge -S '$munge_socket' -n | unmunge -S '$munge_socket'"

ctld_port=$(pick_port)
slurmd_port=$(pick_port "$ctld_port")
mem=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' | head -n 1)
[ -n "$mem" ] || { say "FAIL: slurmd -C reported no RealMemory" >&2; exit 1; }
mem=$((mem * 9 / 10))  # a node that reports less memory than configured is drained
touch "$T/plugstack.conf"
cat > "$T/slurm.conf" <<EOF
# One-node test cluster of scripts/test-slurm.sh (removed when the test ends).
ClusterName=aalabtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$munge_socket
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
PlugStackConfig=$T/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
# Keep finished jobs' records (JobState, ExitCode) for an hour: there is no accounting database.
MinJobAge=3600
# Schedule at each event: with the defaults (batch_sched_delay 3 s, sched_min_interval 2 s) the
# jobs started in 3 s steps (slurmctld.log) and the test took 50 s instead of 23 s here.
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$mem State=UNKNOWN
PartitionName=aalab Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$T/slurm.conf"
setsid slurmctld -D -f "$SLURM_CONF" > "$T/log/slurmctld.out" 2>&1 &
ctld_pid=$!
wait_until 60 "slurmctld answering (scontrol ping)" bash -c 'scontrol ping | grep -q UP'
setsid slurmd -D -f "$SLURM_CONF" -N "$host" > "$T/log/slurmd.out" 2>&1 &
slurmd_pid=$!
wait_until 60 "node $host idle in sinfo" bash -c "sinfo -h -n '$host' -o %t | grep -qx idle"
say "phase cluster start: $(since "$t") s (ports $ctld_port/$slurmd_port, $(nproc) CPUs, node $host idle)"

# --- helpers for the cases -------------------------------------------------------------------
show_jobs() {  # show_jobs JOBID...: one line per job record (scontrol takes one id at a time)
  local id
  for id in "$@"; do scontrol -o show job "$id" || return 1; done
}
terminal() {  # every record of the jobs has ended, or waits on a dependency that failed
  local out waiting
  out=$(show_jobs "$@" 2>&1) || return 1
  # (no `grep -q` at the end of a pipe: with pipefail, the first grep's SIGPIPE would count)
  waiting=$(grep -E 'JobState=(PENDING|RUNNING|CONFIGURING|COMPLETING|REQUEUED|RESIZING|SUSPENDED)' <<< "$out" |
    grep -v 'Reason=DependencyNeverSatisfied' || true)
  [ -z "$waiting" ]
}
wait_jobs() {  # wait_jobs JOBID...: until every job is finished (WAIT_S at most)
  wait_until "$WAIT_S" "jobs $* finished" terminal "$@"
}
check_jobs() {  # check_jobs WORK JOBID...: every record COMPLETED with exit 0:0, else the logs
  local work=$1 out bad
  shift
  out=$(show_jobs "$@")
  bad=$(grep -vE 'JobState=COMPLETED .*ExitCode=0:0' <<< "$out" || true)
  [ -z "$bad" ] && return 0
  say "jobs that did not complete with exit 0:" >&2
  sed -E 's/^(JobId=[^ ]+).*(JobName=[^ ]+).*(JobState=[^ ]+ Reason=[^ ]+).*(ExitCode=[^ ]+).*/  \1 \2 \3 \4/' <<< "$bad" >&2
  for f in "$work"/logs/*; do [ -f "$f" ] && { echo "==== $f" >&2; tail -n 20 "$f" >&2; }; done
  return 1
}
job_of() { sed -n "s/^$1=//p" "$2/jobs.txt"; }
fail() { say "FAIL: $*" >&2; failures=$((failures + 1)); }

export AALAB="$AALAB_BIN"
submit=("$ROOT/scripts/slurm/submit.sh" -n "$SHARDS")
run_opts=(--suite quick --size 160x90 --ref-spp 16 --repeat 1 --quiet)
# shellcheck disable=SC2054  # the commas are aalab's list syntax, not array separators
motion_opts=(--scenes motion-pan,motion-orbit,wedges --frames 4 --size 160x90 --ref-spp 16 --repeat 1 --quiet)
# shellcheck disable=SC2054
sweep_opts=(--scenes wedges,circle,thin-wires --method fxaa311-p39 --grid subpix=0,0.5,1
  --grid edge_threshold=0.125,0.25 --size 160x90 --ref-spp 16 --repeat 1 --quiet)

# case NAME KIND SINGLE_OPTS... -- SUBMIT_FLAGS...: the single-process run, the recipe, the check
run_case() {
  local name=$1 kind=$2 t work
  shift 2
  local -a opts=() flags=()
  while [ $# -gt 0 ] && [ "$1" != -- ]; do opts+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  flags=("$@")
  work="$T/run/$name"
  t=$(now)
  if ! "$AALAB_BIN" "$kind" "${opts[@]}" --out "$work-single" > "$T/log/$name-single.out" 2>&1; then
    cat "$T/log/$name-single.out" >&2
    fail "$name: the single-process $kind failed"
    return
  fi
  local t_single
  t_single=$(since "$t")
  t=$(now)
  "${submit[@]}" "${flags[@]}" "$work" "$kind" "${opts[@]}" > "$T/log/$name-submit.out" 2>&1 ||
    { cat "$T/log/$name-submit.out" >&2; fail "$name: submit.sh failed"; return; }
  local ids=()
  mapfile -t ids < <(sed 's/^.*=//' "$work/jobs.txt")
  wait_jobs "${ids[@]}" || { fail "$name: jobs ${ids[*]} did not finish"; return; }
  check_jobs "$work" "${ids[@]}" || { fail "$name: a job failed"; return; }
  local t_slurm
  t_slurm=$(since "$t")
  if "$AALAB_BIN" same-results "$work-single" "$work/merged"; then
    say "PASS $name: $SHARDS shards merged through Slurm == single $kind (single $t_single s; submit to merged $t_slurm s; jobs ${ids[*]}; $(find "$work/cache" -name '*.ref' | wc -l) cached references)"
  else
    fail "$name: the merged $kind differs from the single-process $kind"
  fi
}

# The failed-shard recipe of docs/cluster.md: shard 1 fails once, the merge job waits forever
# (DependencyNeverSatisfied: Slurm's default), `submit.sh --rerun 1` submits shard 1 again and
# points the pending merge job at it, and the merge equals the single run.
rerun_case() {
  local name=rerun work="$T/run/rerun" t flaky="$T/flaky-aalab"
  t=$(now)
  cat > "$flaky" <<EOF
#!/usr/bin/env bash
# Shard 1 fails the first time (a stand-in for a node failure), every other call is aalab.
if [ "\${SLURM_ARRAY_TASK_ID:-}" = 1 ] && [ ! -e "$T/flaky-failed-once" ]; then
  touch "$T/flaky-failed-once"; echo "flaky-aalab: simulated failure of shard 1" >&2; exit 3
fi
exec "$AALAB_BIN" "\$@"
EOF
  chmod +x "$flaky"
  AALAB="$flaky" "${submit[@]}" "$work" run "${run_opts[@]}" > "$T/log/$name-submit.out" 2>&1 ||
    { cat "$T/log/$name-submit.out" >&2; fail "$name: submit.sh failed"; return; }
  local array merge
  array=$(job_of array_job "$work") merge=$(job_of merge_job "$work")
  wait_jobs "$array" "$merge" || { fail "$name: jobs did not finish"; return; }
  if ! grep -q 'ArrayTaskId=1 .*JobState=FAILED .*ExitCode=3:0' <<< "$(show_jobs "$array")"; then
    fail "$name: shard 1 was expected to fail with exit 3"; show_jobs "$array" >&2; return
  fi
  if ! grep -q 'JobState=PENDING Reason=DependencyNeverSatisfied' <<< "$(show_jobs "$merge")"; then
    fail "$name: the merge job should wait (DependencyNeverSatisfied) after a failed shard"; show_jobs "$merge" >&2; return
  fi
  "$ROOT/scripts/slurm/submit.sh" --rerun 1 "$work" >> "$T/log/$name-submit.out" 2>&1 ||
    { cat "$T/log/$name-submit.out" >&2; fail "$name: submit.sh --rerun 1 failed"; return; }
  local again
  again=$(job_of rerun_job "$work")
  [ "$(job_of merge_job "$work")" = "$merge" ] || { fail "$name: --rerun should have kept the pending merge job $merge"; return; }
  wait_jobs "$again" "$merge" || { fail "$name: rerun jobs did not finish"; return; }
  check_jobs "$work" "$again" "$merge" || { fail "$name: the rerun or its merge failed"; return; }
  if "$AALAB_BIN" same-results "$T/run/run-single" "$work/merged"; then
    say "PASS $name: shard 1 failed, the merge job waited, submit.sh --rerun 1 reran it and released job $merge; merged == single run ($(since "$t") s)"
  else
    fail "$name: the merged run after the rerun differs from the single-process run"
  fi
}

t=$(now); run_case run run "${run_opts[@]}"; say "phase run: $(since "$t") s"
t=$(now); run_case motion run "${motion_opts[@]}" -- --references-first; say "phase motion: $(since "$t") s"
t=$(now)
AALAB_SBATCH_ARGS=--cpus-per-task=1 run_case sweep sweep "${sweep_opts[@]}"
if ! grep -q -- "--threads 1 --shard" "$T/run/sweep/logs/aalab-shard-"*_0.out; then
  fail "sweep: with --cpus-per-task=1 the shard should have run --threads 1"
fi
say "phase sweep: $(since "$t") s"
t=$(now); rerun_case; say "phase rerun: $(since "$t") s"

if [ $failures -ne 0 ]; then
  say "$failures case(s) failed"
  [ "$KEEP" = 1 ] || say "(KEEP=1 keeps the cluster's logs and runs for a look)"
  exit 1
fi
