#!/usr/bin/env bash
# The GPU check (issue 30) in one command: on a machine with a GPU, the GL and app test suites on the EGL
# backend, `bounce probe`, and every technique timed on the Cornell variants and Crytek Sponza at 512x512
# (bench/device.json) and 1024x768 (bench/device-1024x768.json), into one folder with one report
# (report.md and report.json: the GL renderer, the tests that failed, the probe's ceilings, per-pass
# times, errors against the cached references, frames per second against the issue's targets).
#
# On a GPU machine with only a driver: build here with scripts/device-pack.sh, copy the checkout with its
# .device/ folder there and run this script from the checkout; it unpacks the binaries and libraries of
# .device/ and, where the machine has no libEGL.so.1, Debian's libglvnd (the NVIDIA driver brings only
# libEGL_nvidia.so.0 and its glvnd vendor file). On a machine that builds Bounce itself it uses build/.
# Without a GPU it runs the same steps on Mesa's llvmpipe (--quick: small sizes, for trying the script).
#
# Usage: scripts/device-check.sh [--out DIR] [--steps tests,probe,bench] [--bench CONFIGS] [--quick]
#                                [--budget SECONDS]
#   --out     the report folder                                        [out/device-check]
#   --steps   which steps, comma-separated                             [tests,probe,bench]
#   --bench   bench configs, comma-separated, run in this order; e.g. with bench/device-sweeps.json
#             added, the parameters that trade speed for error
#                                          [bench/device-1024x768.json,bench/device.json]
#   --quick   the benchmarks at 64x64 and 64x48 on the Cornell variants, 1 warm-up and 2 timed frames,
#             and only the context, frame and conformance tests (llvmpipe: a few minutes)
#   --budget  seconds the whole script may take; each step gets its share and is cut off (the report
#             says so) rather than overrunning a lease                [450]
# Exit status: 0 when every step ran, every test passed and every figure asked for is in the report (a bench
# cut off by the budget fails the check), 1 otherwise, 2 for bad arguments.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

out=out/device-check
steps=tests,probe,bench
quick=0
budget=450
benches=bench/device-1024x768.json,bench/device.json # the targets' size first
while [ $# -gt 0 ]; do
    case "$1" in
        --out) out=${2:?--out needs a folder}; shift 2 ;;
        --steps) steps=${2:?--steps needs a list}; shift 2 ;;
        --bench) benches=${2:?--bench needs configs}; shift 2 ;;
        --quick) quick=1; shift ;;
        --budget) budget=${2:?--budget needs seconds}; shift 2 ;;
        -h | --help)
            sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'
            exit 0
            ;;
        *)
            echo "device-check: unknown argument '$1' (see --help)" >&2
            exit 2
            ;;
    esac
done
for s in ${steps//,/ }; do
    case "$s" in tests | probe | bench) ;; *)
        echo "device-check: unknown step '$s' (tests, probe, bench)" >&2
        exit 2
        ;;
    esac
done
case "$budget" in '' | *[!0-9]*) echo "device-check: --budget takes whole seconds" >&2; exit 2 ;; esac
IFS=, read -r -a configs <<<"$benches"
for c in "${configs[@]}"; do
    [ -f "$c" ] || { echo "device-check: no bench config '$c'" >&2; exit 2; }
done
has() { [[ ",$steps," == *",$1,"* ]]; }
start=$(date +%s)
left() { echo $((budget - ($(date +%s) - start))); }

rm -rf "$out"
mkdir -p "$out/logs"
out=$(cd "$out" && pwd)
log() { echo "[device-check $(($(date +%s) - start))s] $*" | tee -a "$out/logs/steps.log"; }

# ---- the machine: carried binaries, GL dispatch, compiled-in paths --------------------------------------
# The carried binaries replace build/ only on another machine than the one that packed them.
if [ -f .device/bin.tar.xz ] && { [ ! -x build/app/bounce ] || [ "$(cat .device/ROOT 2>/dev/null)" != "$root" ]; }; then
    log "unpacking .device/bin.tar.xz"
    mkdir -p .device/unpacked
    tar -C .device/unpacked -xJf .device/bin.tar.xz
    mkdir -p build/app build/tests
    cp .device/unpacked/build/app/bounce build/app/
    cp .device/unpacked/build/tests/*_tests build/tests/
fi
[ -d .device/unpacked/lib ] && export LD_LIBRARY_PATH="$root/.device/unpacked/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# Debian's libglvnd goes into .device/glvnd, never into the system's root: the loader finds it through
# LD_LIBRARY_PATH, and the machine is left as it was lent.
if ! ldconfig -p 2>/dev/null | grep -q 'libEGL\.so\.1 ' && [ -d .device/gl ]; then
    log "no libEGL.so.1: unpacking Debian's libglvnd from .device/gl into .device/glvnd"
    mkdir -p .device/glvnd
    for f in .device/gl/*.deb; do dpkg -x "$f" .device/glvnd || log "could not unpack $f"; done
    for d in .device/glvnd/usr/lib/*-linux-gnu .device/glvnd/usr/lib; do
        [ -d "$d" ] && export LD_LIBRARY_PATH="$root/$d${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    done
fi
nvidia_vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
if [ -f "$nvidia_vendor" ] && ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
    export __EGL_VENDOR_LIBRARY_FILENAMES="$nvidia_vendor"
fi
# The test binaries name the checkout they were built in (BOUNCE_BINARY, BOUNCE_TEST_OUT): a link from
# there to here lets them run from another path.
if [ -f .device/ROOT ]; then
    built=$(cat .device/ROOT)
    if [ "$built" != "$root" ] && [ ! -e "$built" ]; then
        mkdir -p "$(dirname "$built")" && ln -s "$root" "$built" && log "linked $built -> $root"
    fi
fi
# Scene setups name ../shared/assets beside the checkout.
if [ -d .device/assets/sponza ] && [ ! -f ../shared/assets/sponza/Sponza.gltf ]; then
    mkdir -p ../shared/assets && ln -sfn "$root/.device/assets/sponza" ../shared/assets/sponza &&
        log "linked ../shared/assets/sponza -> .device/assets/sponza"
fi
# The bench's plots need matplotlib: Debian's /usr/bin/python3 has it with python3-matplotlib, a GPU image
# often only in another Python.
for python in /usr/bin/python3 python3; do
    if "$python" -c 'import matplotlib' >/dev/null 2>&1; then
        export BOUNCE_PYTHON="$python"
        break
    fi
done
export BOUNCE_ROOT="$root"
export BOUNCE_PROGRESS=0
export BOUNCE_TEST_BACKEND=egl
bounce="$root/build/app/bounce"
if [ ! -x "$bounce" ]; then
    echo "device-check: no $bounce: build with scripts/build.sh, or bring .device/ from scripts/device-pack.sh" >&2
    exit 2
fi

{
    echo "date: $(date -u +%FT%TZ)"
    # The binaries' commit: device-pack.sh's record of it where they were carried.
    if [ -f .device/COMMIT ]; then
        echo "commit: $(cat .device/COMMIT) (built by scripts/device-pack.sh)"
    else
        echo "commit: $(git describe --always --dirty 2>/dev/null || echo unknown)"
    fi
    echo "host: $(uname -srm), $(nproc) cores"
    command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm \
        --format=csv,noheader 2>&1 | sed 's/^/gpu: /'
    ldd "$bounce" | grep 'not found' | sed 's/^/missing library: /'
} >"$out/machine.txt" 2>&1
cat "$out/machine.txt"
"$bounce" render --scene cornell-spot --technique direct --size 64x64 --frames 1 --warmup 0 \
    --out "$out/logs/hello.exr" --json "$out/logs/hello.json" >"$out/logs/hello.log" 2>&1 ||
    log "a first render failed: $(tail -3 "$out/logs/hello.log")"

# ---- tests ------------------------------------------------------------------------------------------------
# Each suite split into shards run side by side (GoogleTest sharding); JSON results per shard.
if has tests; then
    share=$(($(left) * 2 / 5))
    [ "$quick" = 1 ] && filter='ContextTest.*:ContextGlTest.*:FrameTest.*:Cli.Bench*' || filter='*'
    shards=$(($(nproc) / 2))
    [ "$shards" -lt 1 ] && shards=1
    [ "$shards" -gt 8 ] && shards=8
    log "tests: gl_tests and app_tests, $shards shards each, at most ${share}s"
    mkdir -p "$out/tests"
    for suite in gl_tests app_tests; do
        for ((i = 0; i < shards; ++i)); do
            GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$i timeout -k 5 "$share" "build/tests/$suite" \
                --gtest_filter="$filter" --gtest_output="json:$out/tests/$suite-$i.json" \
                >"$out/logs/$suite-$i.log" 2>&1 &
        done
    done
    wait
    log "tests done"
fi

# ---- probe ------------------------------------------------------------------------------------------------
if has probe; then
    log "probe"
    timeout -k 5 $(($(left) / 6 + 20)) "$bounce" probe --force --json "$out/probe.json" >"$out/logs/probe.log" 2>&1 ||
        log "probe failed or was cut off: $(tail -2 "$out/logs/probe.log")"
fi

# ---- benchmarks -------------------------------------------------------------------------------------------
if has bench; then
    if [ "$quick" = 1 ]; then
        # The same runs, small: for trying the script on llvmpipe. Its references are computed here.
        small=()
        for c in "${configs[@]}"; do
            python3 - "$c" "$out/logs/$(basename "$c")" <<'EOF'
import json, sys
c = json.load(open(sys.argv[1]))
wide = c["size"] != "512x512"
c.update(size="64x48" if wide else "64x64", warmup=1, frames=2,
         reference={"size": "16x12" if wide else "16x16", "spp": 64},
         scenes=[s for s in c["scenes"] if not s.endswith(".json")][:2])
c["runs"] = [r for r in c["runs"] if "scenes" not in r or any(s in c["scenes"] for s in r["scenes"])]
for r in c["runs"]:
    if "scenes" in r: r["scenes"] = [s for s in r["scenes"] if s in c["scenes"]]
    if r["technique"] == "rsm" and r.get("set", {}).get("vpls") == 4096: r["set"]["vpls"] = 1024
json.dump(c, open(sys.argv[2], "w"), indent=1)
EOF
            small+=("$out/logs/$(basename "$c")")
        done
        configs=("${small[@]}")
    fi
    n=${#configs[@]}
    for c in "${configs[@]}"; do
        name=$(basename "$c" .json)
        share=$(($(left) / n))
        n=$((n - 1))
        log "bench $name: at most ${share}s"
        cache=()
        [ -d .device/cache ] && [ "$quick" = 0 ] && cache=(--cache "$root/.device/cache")
        timeout -k 5 "$share" "$bounce" bench --config "$c" --out "$out/$name" "${cache[@]}" --roofline \
            >"$out/logs/$name.log" 2>&1
        status=$?
        echo "$name	$c" >>"$out/logs/benches-asked.txt"
        if [ "$status" = 124 ] || [ "$status" = 137 ]; then
            # The figures it did not reach are missing: the check fails, and the report names them.
            echo "$name: cut off at its share of the budget (${share}s)" >>"$out/logs/bench-failed.txt"
            log "bench $name was cut off at its share; the renders it finished are kept, the rest are missing"
        elif [ "$status" != 0 ]; then
            # A bench that stops on its own (a refused config, a crash) fails the check.
            echo "$name (status $status): $(tail -1 "$out/logs/$name.log")" >>"$out/logs/bench-failed.txt"
            log "bench $name failed (status $status): $(tail -2 "$out/logs/$name.log")"
        fi
    done
fi

# ---- the report ---------------------------------------------------------------------------------------------
log "report"
python3 scripts/device_report.py "$out" && cat "$out/report.md"
status=$?
[ "$(python3 -c 'import json,sys; print(int(json.load(open(sys.argv[1]))["ok"]))' "$out/report.json" 2>/dev/null)" = 1 ] || status=1
log "done: $out/report.md (status $status)"
exit $status
