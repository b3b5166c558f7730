#!/usr/bin/env bash
# First command of the README: installs what is missing, builds, and shows what Bounce is for: the
# Cornell box (cornell-spot) with direct light only, with one diffuse bounce (hierarchical image-space
# radiosity, `hisr`: fast, but one bounce cannot converge to the full light transport) and with the
# full-GI technique the study (bench/study.json) finds best at a small cost (global ray-bundles, `grb`,
# 512 directions), each one's GPU time and its error against the path tracer's `full` reference
# (computed once at 64x64, then cached; under a minute on 2 cores the first time). Writes
# out/cornell-spot-{direct,hisr,grb}.{exr,png,json} and out/cornell-spot-full.exr.
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
scripts/build.sh

bounce=build/app/bounce
reference=out/cornell-spot-full.exr
# The render (512x512) is box-downsampled to the reference's 64x64 before the error is taken: the low
# frequencies indirect light lives in, at a fraction of a full-size reference's cost.
$bounce reference --scene cornell-spot --paths full --size 64x64 --noise 0.02 --spp 4096 --out "$reference"
$bounce render --scene cornell-spot --technique direct --size 512x512 --frames 5 --warmup 1 \
    --reference "$reference" --out out/cornell-spot-direct.exr
$bounce render --scene cornell-spot --technique hisr --size 512x512 --frames 3 --warmup 1 \
    --reference "$reference" --out out/cornell-spot-hisr.exr
# grb is progressive: 32 frames of 16 directions each, accumulated; its time is all of theirs.
$bounce render --scene cornell-spot --technique grb --size 256x256 --frames 32 --warmup 0 \
    --set directionsPerFrame=16 --reference "$reference" --out out/cornell-spot-grb.exr

python3 - out/cornell-spot-direct.json out/cornell-spot-hisr.json out/cornell-spot-grb.json <<'EOF'
import json, sys
print("\ncornell-spot against the path-traced full light transport (%s):" % "out/cornell-spot-full.exr")
for path in sys.argv[1:]:
    r = json.load(open(path))
    print("  %-7s %-18s %dx%d %8.1f ms per frame x %2d frames = %8.1f ms   relative RMSE %.3f   %s" % (
        r["technique"], "(" + r["lightPaths"] + ")", r["width"], r["height"], r["totalMs"], r["imageFrames"],
        r["imageMs"], r["relativeRmse"], path[:-5] + ".png"))
print("GL renderer: %s. Times are GPU milliseconds (median frame); on llvmpipe they measure the CPU." % r["renderer"])
print("Every technique side by side: build/app/bounce bench --config bench/study.json --out out/study (README).")
EOF
