#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer (DEEPGI_SANITIZE=ON).
#   tools/sanitize.sh [ctest args...]
# Configures and builds in its own folder (build-sanitize, or $DEEPGI_SANITIZE_BUILD) with -j$DEEPGI_SANITIZE_JOBS
# (default 2), then runs ctest with the suppressions in tools/sanitizers/ (third-party frames only: Mesa/llvmpipe,
# LLVM, OSMesa). Prints the time each stage took; exits non-zero on any failure or sanitizer report.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${DEEPGI_SANITIZE_BUILD:-$ROOT/build-sanitize}"
JOBS="${DEEPGI_SANITIZE_JOBS:-2}"
SUPP="$ROOT/tools/sanitizers"

t0=$(date +%s)
cmake -S "$ROOT" -B "$BUILD" -DDEEPGI_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$BUILD" -j"$JOBS"
t1=$(date +%s)

# detect_leaks: LeakSanitizer on, with suppressions for leaks inside Mesa/LLVM (never our frames).
# abort_on_error/halt_on_error: a report fails the test. UBSan: print a stack, stop on the first error.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:halt_on_error=1:detect_odr_violation=0:strict_string_checks=1:${ASAN_OPTIONS:-}"
export LSAN_OPTIONS="suppressions=$SUPP/lsan.supp:print_suppressions=0:${LSAN_OPTIONS:-}"
export UBSAN_OPTIONS="suppressions=$SUPP/ubsan.supp:print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
# The viewer (GLX) and EGL tests load Mesa's DRI driver with dlopen; it is unloaded before LeakSanitizer runs, so
# the driver's own allocations show up as "<unknown module>" with no deepgi frame and no suppression can name them.
# Those tests run with ASan and UBSan but without leak detection; every other test keeps it.
NO_LEAK_CHECK='^(Viewer\.|ViewerRound2\.|ViewerEdit\.|OffscreenContext\.Egl)'
set +e
(cd "$BUILD" && ctest --output-on-failure -j"$JOBS" --timeout 1200 -E "$NO_LEAK_CHECK" "$@")
rc=$?
(cd "$BUILD" && ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" ctest --output-on-failure -j"$JOBS" --timeout 1200 -R "$NO_LEAK_CHECK" "$@")
rc2=$?
[ $rc -ne 0 ] || rc=$rc2
set -e
t2=$(date +%s)
echo "sanitize.sh: build $((t1 - t0)) s, tests $((t2 - t1)) s, total $((t2 - t0)) s; ctest exit code $rc"
exit $rc
