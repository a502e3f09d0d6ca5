#!/usr/bin/env bash
# `make test-asan`: builds aalab and every test with AddressSanitizer + UndefinedBehaviorSanitizer
# (AALAB_SANITIZE=ON, RelWithDebInfo, in build-asan/), runs the whole ctest suite, then runs the
# `hard` suite through the CLI. Every sanitizer report is fatal, including reports from the
# aalab processes the CLI tests start (whose exit codes those tests may expect to be non-zero):
# reports are also written to build-asan/sanitizer-logs/ and any file there fails the target.
#
# Embree, TBB and OpenImageIO come from Debian and are not instrumented. Suppressions, each
# documented in its file, are for third-party code only: tests/sanitizers/{lsan,ubsan}.supp.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD=${ASAN_BUILD:-build-asan}
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}
start=$(date +%s)

cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAALAB_SANITIZE=ON > "$BUILD.configure.log" 2>&1 ||
  { cat "$BUILD.configure.log"; exit 1; }
cmake --build "$BUILD" -j "$JOBS"
built=$(date +%s)

LOGS="$ROOT/$BUILD/sanitizer-logs"
rm -rf "$LOGS"
mkdir -p "$LOGS"
# halt_on_error: the first report ends the process; log_path: reports also land in files, so a
# report inside a process whose failure a test expects is still seen. fast_unwind_on_malloc=0:
# the frame-pointer unwinder stops at the first uninstrumented library (libstdc++, OIIO), and
# the leak suppressions need the OIIO frames (about 30% slower).
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:fast_unwind_on_malloc=0:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:log_path=$LOGS/asan"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$ROOT/tests/sanitizers/ubsan.supp:log_path=$LOGS/ubsan"
export LSAN_OPTIONS="suppressions=$ROOT/tests/sanitizers/lsan.supp:print_suppressions=0"

status=0
(cd "$BUILD" && ctest --output-on-failure -j "$JOBS") || status=1
tested=$(date +%s)

OUT="$ROOT/$BUILD/hard-run"
rm -rf "$OUT" "$OUT.partial"
"./$BUILD/aalab" run --suite hard --size 96x54 --ref-spp 16 --repeat 1 --quiet --out "$OUT" || status=1
[ -f "$OUT/report.json" ] || { echo "test-asan: the hard-suite run wrote no report" >&2; status=1; }
done_at=$(date +%s)

if compgen -G "$LOGS/*" > /dev/null; then
  echo "test-asan: sanitizer reports:" >&2
  for f in "$LOGS"/*; do echo "== $f" >&2; cat "$f" >&2; done
  status=1
fi
echo "test-asan: build $((built - start)) s, ctest $((tested - built)) s, hard suite $((done_at - tested)) s," \
     "total $((done_at - start)) s: $([ $status -eq 0 ] && echo passed || echo FAILED)"
exit $status
