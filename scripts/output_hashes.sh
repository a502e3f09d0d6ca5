#!/usr/bin/env bash
# Fingerprints of what a build produces, for refactors and speed work that must not change
# outputs: runs the default suite (default settings) and the motion suite (8 frames at
# 480x270), then writes to OUT_DIR/hashes.txt one line per image (sha256, path) and one line
# per report row (scene, spec, output hash, every metric at full precision). Timings are left
# out. Two builds produce the same bits when their hashes.txt are identical:
#   scripts/output_hashes.sh build/aalab /tmp/h-new && diff /tmp/h-old/hashes.txt /tmp/h-new/hashes.txt
set -euo pipefail
bin=${1:?usage: output_hashes.sh AALAB_BINARY OUT_DIR}
dir=${2:?usage: output_hashes.sh AALAB_BINARY OUT_DIR}
bin=$(realpath "$bin")
mkdir -p "$dir"
dir=$(realpath "$dir")
rm -rf "$dir/default" "$dir/motion"
"$bin" run --quiet --out "$dir/default"
"$bin" run --quiet --suite motion --frames 8 --size 480x270 --out "$dir/motion"
{
  for run in default motion; do
    (cd "$dir/$run" && find images -type f | LC_ALL=C sort | xargs sha256sum | sed "s|  |  $run/|")
    jq -c --arg run "$run" '.rows[] | [$run, .scene, .spec, .output_hash, .metrics, (.temporal // null)]' \
      "$dir/$run/report.json"
  done
} > "$dir/hashes.txt"
wc -l "$dir/hashes.txt"
