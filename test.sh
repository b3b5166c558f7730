#!/usr/bin/env bash
# Second command of the README: the whole test suite (installs and builds first when needed). GL tests
# run on Mesa's llvmpipe (OSMesa and EGL); the demo test opens a window under Xvfb. -noreset: by default Xvfb
# resets when its last client disconnects and drops a client that connects meanwhile ("X11: Failed to open
# display"; 4 processes opening and closing the display 1000 times each lost 13-23 connections, none with it).
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
scripts/build.sh
cd build
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j "$(nproc)" --timeout 900
