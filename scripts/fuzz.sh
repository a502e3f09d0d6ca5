#!/usr/bin/env bash
# `make fuzz`: builds the libFuzzer targets of tests/fuzz with clang
# (-fsanitize=fuzzer,address,undefined) in build-fuzz/ and runs each for FUZZ_SECONDS seconds
# (default 60), seeded with the checked-in corpus tests/fuzz/corpus/{scene,image}/.
# New interesting inputs go to build-fuzz/corpus-<target>/ (the checked-in corpus is only
# read); crashes, leaks, timeouts and OOMs go to build-fuzz/findings-<target>/ and fail the
# target. To keep a finding as a regression case, minimise it
#   ./build-fuzz/scene_fuzz -minimize_crash=1 -runs=10000 build-fuzz/findings-scene/crash-...
# and copy it into tests/fuzz/corpus/<target>/ as bad-regress-NAME (refused with a clear error
# once fixed) or ok-regress-NAME (accepted): the replay test in `make test` runs it and checks
# the outcome its name states.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${FUZZ_BUILD:-build-fuzz}
SECS=${FUZZ_SECONDS:-60}
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}
CXX_FUZZ=${CXX_FUZZ:-clang++}
start=$(date +%s)

cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$CXX_FUZZ" -DAALAB_FUZZ=ON \
  > "$BUILD.configure.log" 2>&1 || { cat "$BUILD.configure.log"; exit 1; }
cmake --build "$BUILD" -j "$JOBS" --target scene_fuzz image_fuzz
built=$(date +%s)

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$PWD/tests/sanitizers/ubsan.supp"
# The same third-party-only suppressions as make test-asan (OpenImageIO's PNG error path leaks).
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
status=0
for t in scene image; do
  work="$BUILD/corpus-$t"
  findings="$BUILD/findings-$t"
  mkdir -p "$work" "$findings"
  dict=()
  [ -f "tests/fuzz/$t.dict" ] && dict=(-dict="tests/fuzz/$t.dict")
  max_len=8192
  [ "$t" = image ] && max_len=65536
  echo "fuzz: $t for ${SECS} s"
  "./$BUILD/${t}_fuzz" -max_total_time="$SECS" -timeout=10 -rss_limit_mb=2048 -max_len=$max_len \
    -print_final_stats=1 -artifact_prefix="$findings/" "${dict[@]}" "$work" "tests/fuzz/corpus/$t" \
    > "$BUILD/fuzz-$t.log" 2>&1 || { status=1; echo "fuzz: $t FOUND A PROBLEM (see $BUILD/fuzz-$t.log, $findings/)" >&2; }
  grep -E "^(stat::number_of_executed_units|stat::new_units_added|stat::peak_rss_mb)" "$BUILD/fuzz-$t.log" || true
done
echo "fuzz: build $((built - start)) s, fuzzing $(( $(date +%s) - built )) s: $([ $status -eq 0 ] && echo no findings || echo FINDINGS)"
exit $status
