#!/usr/bin/env bash
# Quick start, step 2: the whole test suite (installs packages and builds first if needed).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
tools/build.sh
cd "${DEEPGI_BUILD_DIR:-build}"
ctest --output-on-failure -j"$(nproc)" --timeout 900
