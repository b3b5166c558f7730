#!/usr/bin/env bash
# First command of the README: installs what is missing, builds, and renders the built-in default scene
# (the Cornell box) to out/cornell-spot.{exr,png,json}, printing the GL renderer and per-pass timings.
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
scripts/build.sh
build/app/bounce render --scene cornell-spot --technique direct --size 512x512 --out out/cornell-spot.exr
