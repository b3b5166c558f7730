#!/usr/bin/env bash
# Installs the Debian 12 packages Bounce builds and tests with (only those missing), and the npm
# packages of package.json (the Khronos glTF validator, and playwright-core, which drives Debian's chromium
# through the test of the benchmark's report.html: tests/app/report_browser.mjs). Needs root for apt-get.
# clang-14 builds the glTF fuzz target (scripts/fuzz.sh); libclang-rt-14-dev holds its libFuzzer and
# sanitizer runtimes, which apt does not install with clang-14 when recommends are off.
# glslang-tools: the Khronos reference GLSL compiler, which checks every shader stage the conformance
# tests compile (tests/gl/conformance_test.cpp), as a GPU driver's stricter front end would.
# munge, slurmctld, slurmd and slurm-client: the single-node Slurm that scripts/slurm/local-slurm-test.sh
# starts from a slurm.conf of its own (.ci/run), to run the bench as a job array for real.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake ninja-build g++ pkg-config clang-format
  libegl-dev libegl1-mesa-dev libgl-dev libosmesa6-dev libgl1-mesa-dri libglfw3-dev libglm-dev python3-glad
  libtinygltf-dev nlohmann-json3-dev libstb-dev libtinyexr-dev libimgui-dev libgtest-dev
  libembree-dev libtbb-dev
  xvfb xauth python3-matplotlib python3-numpy
  chromium glslang-tools
  clang-14 libclang-rt-14-dev
  munge slurmctld slurmd slurm-client
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node.js and npm run the Khronos glTF validator (tests/core/gltf_validator_test.cpp); a machine that
# already has an npm (from another source) keeps it.
command -v npm >/dev/null 2>&1 || missing+=(nodejs npm)
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The glTF validator and playwright-core (npm, from package-lock.json, so the versions are pinned).
if [ ! -d node_modules/gltf-validator ] || [ ! -d node_modules/playwright-core ]; then
  npm ci --no-audit --no-fund --silent
fi
