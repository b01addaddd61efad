#!/usr/bin/env bash
# Quick start, step 1: installs the Debian 12 packages deepgi needs (skips what is present), builds it, and
# renders the default scene (the atrium) headless into out/atrium/. With a display, it also opens the viewer.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
tools/build.sh
build/app/deepgi render --out out/atrium --frames 24 --buffers all
echo "deepgi: the default scene is in out/atrium/ (final.png, final.exr, one EXR per buffer, timings.json, settings.json)"
if [ -n "${DISPLAY:-}" ] && build/app/deepgi --help 2>/dev/null | grep -q "^  view"; then
  build/app/deepgi view
fi
