#!/usr/bin/env bash
# The CI gate of docs/ci.md on trial (issue #38): runs the recipe N times with one binary while
# busy processes load every core, comparing each run with one baseline (should exit 0), then N
# times with a planted quality regression (fxaa311-p39 with edge_threshold=1, compared
# through --map: should exit 1), and counts compare's exit codes.
#
#   scripts/ci_gate_trial.sh [N]          (default N=20)
#   AALAB=build/aalab SIZE=320x180 SCENES="--suite quick" LOAD=2 FAIL_ON=quality scripts/ci_gate_trial.sh 20
#
# The references are cached (--ref-cache) across the runs to save time: a cached reference
# is the same bits as a rendered one, and method times do not include the reference.
# Prints one line per run and a summary; exit 0 when every identical run exited 0 and every
# planted one exited 1.
set -u
N=${1:-20}
AALAB=${AALAB:-build/aalab}
SIZE=${SIZE:-320x180}
SCENES=${SCENES:---suite quick}
LOAD=${LOAD:-$(nproc)}
FAIL_ON=${FAIL_ON:-quality}
work=$(mktemp -d "${TMPDIR:-/tmp}/ci-gate-trial.XXXXXX")
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  wait 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT INT TERM

recipe() {  # recipe OUT [--methods LIST]: docs/ci.md's aalab run
  # shellcheck disable=SC2086
  "$AALAB" run $SCENES --size "$SIZE" --ref-spp 64 --repeat 5 --threads 2 --quiet --ref-cache "$work/refs" --out "$@" \
    >"$work/run.log" 2>&1 || { echo "aalab run failed:"; cat "$work/run.log"; exit 3; }
}

recipe "$work/base"
methods=$(python3 -c 'import json,sys
specs=[]
for r in json.load(open(sys.argv[1]))["rows"]:
    if r["spec"] not in specs: specs.append(r["spec"])
print(",".join(s + ":edge_threshold=1" if s == "fxaa311-p39" else s for s in specs))' "$work/base/report.json")

for ((i = 0; i < LOAD; i++)); do
  ( while :; do :; done ) &
  pids+=($!)
done
echo "load: $LOAD busy processes; loadavg at start $(cut -d' ' -f1-3 /proc/loadavg)"

declare -A same planted
for ((i = 1; i <= N; i++)); do
  recipe "$work/cur"
  "$AALAB" compare "$work/base/report.json" "$work/cur/report.json" --fail-on "$FAIL_ON" >"$work/cmp.log" 2>&1
  code=$?
  same[$code]=$(( ${same[$code]:-0} + 1 ))
  echo "identical $i/$N: exit $code ($(grep -o 'gating.*' "$work/cmp.log"))"
  [ "$code" = 0 ] || cat "$work/cmp.log"
done
for ((i = 1; i <= N; i++)); do
  recipe "$work/cur" --methods "$methods"
  "$AALAB" compare "$work/base/report.json" "$work/cur/report.json" --fail-on "$FAIL_ON" \
    --map fxaa311-p39=fxaa311-p39:edge_threshold=1 >"$work/cmp.log" 2>&1
  code=$?
  planted[$code]=$(( ${planted[$code]:-0} + 1 ))
  echo "planted $i/$N: exit $code ($(grep -o 'gating.*' "$work/cmp.log"))"
done
echo "loadavg at end $(cut -d' ' -f1-3 /proc/loadavg)"
summary() { local -n m=$1; local s=""; for k in "${!m[@]}"; do s+=" exit $k: ${m[$k]}"; done; echo "$s"; }
echo "summary (size $SIZE, $SCENES, --fail-on $FAIL_ON, $LOAD busy processes on $(nproc) cores):"
echo "  identical binary:$(summary same)"
echo "  planted regression:$(summary planted)"
[ "${same[0]:-0}" = "$N" ] && [ "${planted[1]:-0}" = "$N" ]
