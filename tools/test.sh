#!/usr/bin/env bash
# Quick start, step 2: the whole test suite. Installs packages and builds first if needed, then:
#   1. the GoogleTest suite under CTest (headless: OSMesa, Xvfb for the viewer);
#   2. the same suite built with AddressSanitizer + UndefinedBehaviorSanitizer (tools/sanitize.sh);
#   3. a bounded libFuzzer run of the glTF loader (tools/fuzz.sh, 60 s).
# DEEPGI_QUICK=1 runs step 1 only (for local iteration).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
tools/build.sh
t0=$(date +%s)
(cd "${DEEPGI_BUILD_DIR:-build}" && ctest --output-on-failure -j"$(nproc)" --timeout 900)
echo "test.sh: suite passed in $(( $(date +%s) - t0 )) s"
if [ "${DEEPGI_QUICK:-0}" = 1 ]; then exit 0; fi
tools/sanitize.sh
tools/fuzz.sh "${DEEPGI_FUZZ_SECONDS:-60}"
echo "test.sh: suite, sanitizer suite and fuzzing all passed"
