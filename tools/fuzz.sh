#!/usr/bin/env bash
# Fuzz the glTF loader with libFuzzer for SECONDS (default 60).
#   tools/fuzz.sh [SECONDS]
# Builds tests/fuzz/fuzz_gltf_loader with clang (-fsanitize=fuzzer,address,undefined) in its own build folder
# (build-fuzz, or $DEEPGI_FUZZ_BUILD), runs it on a copy of tests/fuzz/corpus, and leaves crashing inputs in
# <build>/fuzz-run/artifacts/. Turn each into a regression file in tests/data/gltf/regress/.
set -euo pipefail
SECS="${1:-60}"
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${DEEPGI_FUZZ_BUILD:-$ROOT/build-fuzz}"
JOBS="${DEEPGI_FUZZ_BUILD_JOBS:-2}"

CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DDEEPGI_FUZZ=ON -DDEEPGI_BUILD_TESTS=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$BUILD" --target fuzz_gltf_loader -j"$JOBS"

RUN="$BUILD/fuzz-run"
rm -rf "$RUN/corpus"
mkdir -p "$RUN/corpus" "$RUN/artifacts"
cp "$ROOT"/tests/fuzz/corpus/* "$RUN/corpus/"
cp "$ROOT"/tests/data/gltf/regress/* "$RUN/corpus/"  # the shapes that once crashed or were refused unclearly

set +e
"$BUILD/tests/fuzz/fuzz_gltf_loader" "$RUN/corpus" \
  -dict="$ROOT/tests/fuzz/gltf.dict" \
  -max_total_time="$SECS" -max_len=16384 -rss_limit_mb=2048 -timeout=10 \
  -artifact_prefix="$RUN/artifacts/" -print_final_stats=1
rc=$?
set -e
echo "fuzz.sh: fuzzer exit code $rc; artifacts in $RUN/artifacts/:"
ls -la "$RUN/artifacts/"
exit $rc
