#!/usr/bin/env bash
# Second command of the README: the whole test suite (installs and builds first when needed). GL tests
# run on Mesa's llvmpipe (OSMesa and EGL); the demo test opens a window under Xvfb.
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
scripts/build.sh
cd build
xvfb-run -a -s "-screen 0 1280x1024x24" ctest --output-on-failure -j "$(nproc)" --timeout 900
