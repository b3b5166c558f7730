#!/usr/bin/env bash
# Prepares, on a Debian 12 build machine, everything scripts/device-check.sh needs on a GPU machine that
# has a driver and nothing else (no compiler toolchain for Bounce, no Debian libraries, no network, no
# ../shared): one folder, .device/ (git-ignored, under 64 MiB), to copy beside the checkout there.
#
#   .device/bin.tar.xz   build/app/bounce, build/tests/{gl,app}_tests and the shared libraries they load
#                        that a plain Linux lacks (Embree, TBB, tinygltf, tinyexr, GLFW, stb, X11's client
#                        libraries); the C and C++ runtimes are the machine's own
#   .device/gl/*.deb     Debian's GL vendor-neutral dispatch (libglvnd: libEGL.so.1, libOpenGL.so.0, ...):
#                        the NVIDIA driver brings only its vendor libraries (libEGL_nvidia.so.0)
#   .device/cache/       the references of bench/device.json and bench/device-1024x768.json (Embree, here)
#   .device/assets/sponza  Crytek Sponza from ../shared/assets with the images Bounce reads (base colours,
#                        metallic-roughness, normal maps); any other is replaced by one small JPEG so that
#                        the folder fits; the scene, and so the reference cache key, is the same
#   .device/ROOT         the checkout's path here: the test binaries have it compiled in
#   .device/COMMIT       the commit the binaries were built from (-dirty: with uncommitted changes)
#
# Usage: scripts/device-pack.sh [--no-references]   (references: about 20 minutes on 2 cores the first
# time, then cached in .device/cache)
set -euo pipefail
cd "$(dirname "$0")/.."

references=1
for arg in "$@"; do
    case "$arg" in
        --no-references) references=0 ;;
        -h | --help)
            sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
            exit 0
            ;;
        *)
            echo "device-pack: unknown argument '$arg' (see --help)" >&2
            exit 2
            ;;
    esac
done

root=$(pwd)
assets="$root/../shared/assets"
if [ ! -f "$assets/sponza/Sponza.gltf" ]; then
    echo "device-pack: $assets/sponza/Sponza.gltf is missing: the benchmark assets live in ../shared/assets" >&2
    exit 2
fi

scripts/build.sh
mkdir -p .device/gl .device/cache
printf '%s\n' "$root" >.device/ROOT
git describe --always --dirty >.device/COMMIT

# The binaries and the libraries they need beyond glibc, libstdc++ and libgcc (newer on any GPU image).
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/build/app" "$stage/build/tests" "$stage/lib"
cp build/app/bounce "$stage/build/app/"
cp build/tests/gl_tests build/tests/app_tests "$stage/build/tests/"
strip --strip-unneeded "$stage"/build/app/bounce "$stage"/build/tests/*_tests
ldd build/app/bounce build/tests/gl_tests build/tests/app_tests | awk '/=> \//{print $3}' | sort -u |
    grep -Ev '/(libc|libm|libstdc\+\+|libgcc_s|libpthread|libdl|librt|ld-linux[^/]*)\.so' |
    while read -r lib; do cp -L "$lib" "$stage/lib/"; done
tar -C "$stage" -cJf .device/bin.tar.xz build lib

# libglvnd from Debian, unpacked on the GPU machine only where it has no libEGL.so.1 of its own.
(cd .device/gl && rm -f ./*.deb && apt-get download libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 >/dev/null)

# Sponza with the images Bounce reads.
python3 - "$assets/sponza" .device/assets/sponza <<'EOF'
import json, os, shutil, sys
src, dst = sys.argv[1], sys.argv[2]
gltf = json.load(open(os.path.join(src, "Sponza.gltf")))
source = lambda t: gltf["textures"][t["index"]]["source"]
kept = set()
for m in gltf["materials"]:
    pbr = m.get("pbrMetallicRoughness", {})
    for key in ("baseColorTexture", "metallicRoughnessTexture"):
        if key in pbr: kept.add(source(pbr[key]))
    if "normalTexture" in m: kept.add(source(m["normalTexture"]))
stand_in = min((os.path.join(src, i["uri"]) for n, i in enumerate(gltf["images"]) if n in kept), key=os.path.getsize)
os.makedirs(dst, exist_ok=True)
for name in os.listdir(src):
    if name.endswith((".gltf", ".bin", ".md")): shutil.copyfile(os.path.join(src, name), os.path.join(dst, name))
for n, image in enumerate(gltf["images"]):
    shutil.copyfile(os.path.join(src, image["uri"]) if n in kept else stand_in, os.path.join(dst, image["uri"]))
EOF

if [ "$references" = 1 ]; then
    # Every light path the techniques of the two configs compare against, at each config's reference
    # size, with its noise and spp: the keys `bounce bench` looks up.
    for config in bench/device.json bench/device-1024x768.json; do
        python3 - "$config" <<'EOF' | while read -r size noise spp scene; do
import json, sys
c = json.load(open(sys.argv[1]))
r = c["reference"]
for scene in c["scenes"]:
    print(r["size"], r["noise"], r["spp"], scene)
EOF
            for paths in direct onebounce-novis onebounce full; do
                build/app/bounce reference --scene "$scene" --paths "$paths" --size "$size" --noise "$noise" \
                    --spp "$spp" --cache-dir .device/cache --out "$stage/reference.exr" >/dev/null
                echo "reference $scene $paths $size: cached"
            done
        done
    done
fi

du -sh .device
total=$(du -sb .device | cut -f1)
if [ "$total" -gt $((56 * 1024 * 1024)) ]; then
    echo "device-pack: .device is $((total / 1048576)) MiB: with the checkout it may not fit a 64 MiB transfer" >&2
    exit 1
fi
echo "ready: copy the checkout with .device/ to the GPU machine and run scripts/device-check.sh there"
