#!/usr/bin/env bash
# Submits an aalab run or sweep to Slurm as a job array of N shards plus a merge job that runs
# once every shard has succeeded (docs/cluster.md):
#
#   submit.sh [-n N] [--references-first] WORK run   [aalab run options...]
#   submit.sh [-n N] [--references-first] WORK sweep [aalab sweep options...]
#   submit.sh --rerun K WORK
#
#   -n N                number of shards (array tasks), default 4
#   --references-first  first a job array that renders the references into the cache
#                       (`aalab run|sweep --references-only`: a run splits them by scene and by
#                       frame of a moving scene), then the shard array after it
#   --rerun K           after shard K failed: submits shard K again (K may be a Slurm index
#                       list, e.g. 1,4) with the options of the first submission (kept in
#                       WORK/submit.state) and makes the merge job wait for it: the pending
#                       merge job is updated (scontrol update), or a new one is submitted when
#                       it is gone (cancelled, e.g. by DependencyParameters=kill_invalid_depend)
#   WORK                a fresh folder on a filesystem every node sees: the shards go to
#                       WORK/shards/K, the merged report to WORK/merged, job logs to WORK/logs
#
# Environment: AALAB (the binary, default `aalab` on PATH of the nodes), AALAB_REF_CACHE (the
# reference cache, default WORK/cache; share it between runs), AALAB_SBATCH_ARGS (extra sbatch
# options for every job, e.g. "--partition=cpu --time=02:00:00 --cpus-per-task=16"); sbatch's
# own SBATCH_* variables apply too; --rerun uses the values of the first submission. Prints
# the job ids as NAME=ID lines (also appended to WORK/jobs.txt).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
die() { echo "submit.sh: $*" >&2; exit 2; }
usage="usage: submit.sh [-n N] [--references-first] WORK run|sweep [aalab options...] | submit.sh --rerun K WORK"
record() { echo "$1=$2" | tee -a "$work/jobs.txt"; }
job_ids() { sed -n "s/^$1=//p" "$work/jobs.txt"; }

in_list() {  # in_list I LIST: I is in the Slurm index list LIST (1,3-5)
  local r
  for r in ${2//,/ }; do
    [ "$1" -ge "${r%-*}" ] && [ "$1" -le "${r#*-}" ] && return 0
  done
  return 1
}

# --rerun K WORK: shard K again, and the merge after it.
rerun() {
  local list=$1 i
  work=$2
  [[ "$list" =~ ^[0-9]+(-[0-9]+)?(,[0-9]+(-[0-9]+)?)*$ ]] || die "--rerun needs array indices such as 1 or 1,4-5, got '$list'"
  if [ ! -f "$work/submit.state" ] || [ ! -f "$work/jobs.txt" ]; then
    die "'$work' holds no submit.state and jobs.txt: --rerun needs the WORK folder of an earlier submit.sh"
  fi
  work=$(cd "$work" && pwd)
  local shards mode saved_aalab saved_cache saved_sbatch
  local -a args
  # shellcheck source=/dev/null
  source "$work/submit.state"
  local part job line ids
  for part in ${list//,/ }; do
    for i in $(seq "${part%-*}" "${part#*-}"); do
      [ "$i" -lt "$shards" ] || die "--rerun: index $i is outside 0..$((shards - 1)) (this run has $shards shards)"
      # Two jobs writing WORK/shards/K at once would collide: refuse while K is still queued or
      # running (a record's ArrayTaskId is an index, or a list of ranges such as 0,2-4%2).
      for job in $(job_ids array_job) $(job_ids rerun_job); do
        while read -r line; do
          [[ "$line" =~ JobState=(PENDING|RUNNING|CONFIGURING|COMPLETING|REQUEUED|SUSPENDED) ]] || continue
          [[ "$line" =~ ArrayTaskId=([0-9,%-]+) ]] || continue
          ids=${BASH_REMATCH[1]%%%*}
          if in_list "$i" "$ids"; then
            die "--rerun: shard $i of job $job is still queued or running (squeue -j $job); wait for it or scancel it first"
          fi
        done < <(scontrol -o show job "$job" 2>/dev/null || true)
      done
    done
  done
  if [ -n "$saved_aalab" ]; then export AALAB="$saved_aalab"; fi
  if [ -n "$saved_cache" ]; then export AALAB_REF_CACHE="$saved_cache"; fi
  # shellcheck disable=SC2206
  local -a extra=($saved_sbatch)
  local again merge state deps=""
  again=$(sbatch --parsable "${extra[@]}" --array="$list" --output="$work/logs/%x-%A_%a.out" \
    "$here/aalab-array.sbatch" "$shards" "$work" "$mode" "${args[@]}")
  again=${again%%;*}
  # The merge waits for every earlier shard job to end (any state) and for this one to succeed;
  # aalab merge then names any shard that is still missing.
  for i in $(job_ids array_job) $(job_ids rerun_job); do deps+="afterany:$i,"; done
  deps+="afterok:$again"
  record rerun_job "$again"
  merge=$(job_ids merge_job | tail -n 1)
  state=$(scontrol -o show job "$merge" 2>/dev/null | grep -o 'JobState=[A-Z]*' | head -n 1 || true)
  if [ "$state" = JobState=PENDING ]; then
    scontrol update jobid="$merge" dependency="$deps" || die "scontrol could not update the dependency of merge job $merge"
    echo "submit.sh: merge job $merge now waits for $deps" >&2
  else
    merge=$(sbatch --parsable "${extra[@]}" --dependency="$deps" --output="$work/logs/%x-%j.out" \
      "$here/aalab-merge.sbatch" "$shards" "$work")
    merge=${merge%%;*}
    record merge_job "$merge"
  fi
}

shards=4 refs_first=0
while [ $# -gt 0 ]; do
  case "$1" in
    --rerun)
      [ $# -eq 3 ] || die "usage: submit.sh --rerun K WORK"
      command -v sbatch >/dev/null 2>&1 || die "sbatch not found: run this on a Slurm login node"
      rerun "$2" "$3"
      exit 0 ;;
    -n) [ $# -ge 2 ] || die "-n needs a value"; shards=$2; shift 2 ;;
    --references-first) refs_first=1; shift ;;
    -h | --help) echo "$usage"; exit 0 ;;
    -*) die "unknown option '$1' ($usage)" ;;
    *) break ;;
  esac
done
[ $# -ge 2 ] || die "$usage"
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "-n must be a positive integer, got '$shards'"
work=$1 mode=$2
shift 2
case "$mode" in run | sweep) ;; *) die "the mode must be run or sweep, got '$mode' ($usage)" ;; esac
command -v sbatch >/dev/null 2>&1 || die "sbatch not found: run this on a Slurm login node"
mkdir -p "$work"
work=$(cd "$work" && pwd)
for d in shards merged; do
  [ ! -e "$work/$d" ] || die "'$work/$d' exists: use a fresh WORK folder (share the reference cache between runs with AALAB_REF_CACHE)"
done
mkdir -p "$work/logs" "${AALAB_REF_CACHE:-$work/cache}"

# shellcheck disable=SC2206  # AALAB_SBATCH_ARGS is a list of options, split on spaces
extra=(${AALAB_SBATCH_ARGS:-})
last=$((shards - 1))
dep=()
: > "$work/jobs.txt"
args=("$@") saved_aalab=${AALAB:-} saved_cache=${AALAB_REF_CACHE:-} saved_sbatch=${AALAB_SBATCH_ARGS:-}
declare -p shards mode args saved_aalab saved_cache saved_sbatch > "$work/submit.state"

if [ $refs_first -eq 1 ]; then
  refs=$(sbatch --parsable "${extra[@]}" --array="0-$last" --job-name=aalab-refs \
    --output="$work/logs/%x-%A_%a.out" "$here/aalab-array.sbatch" "$shards" "$work" "$mode" --references-only "$@")
  refs=${refs%%;*}
  record references_job "$refs"
  dep=(--dependency="afterok:$refs")
fi
array=$(sbatch --parsable "${extra[@]}" "${dep[@]}" --array="0-$last" \
  --output="$work/logs/%x-%A_%a.out" "$here/aalab-array.sbatch" "$shards" "$work" "$mode" "$@")
array=${array%%;*}
record array_job "$array"
merge=$(sbatch --parsable "${extra[@]}" --dependency="afterok:$array" \
  --output="$work/logs/%x-%j.out" "$here/aalab-merge.sbatch" "$shards" "$work")
merge=${merge%%;*}
record merge_job "$merge"
echo "submit.sh: $shards shards -> $work/shards, merged report -> $work/merged (logs: $work/logs)" >&2
