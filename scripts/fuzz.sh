#!/usr/bin/env bash
# libFuzzer on the glTF/GLB loader (tests/fuzz/gltf_fuzz.cpp): builds build-fuzz/ with clang (only core/ and
# the fuzz target, under AddressSanitizer and UBSan), then fuzzes from the seed corpus with the dictionary.
#
#   scripts/fuzz.sh                    build, then fuzz for 10 minutes
#   scripts/fuzz.sh --time 3600        ... for an hour (the test gltf_fuzz runs --time 45)
#   scripts/fuzz.sh --build            build only
#   scripts/fuzz.sh --time 600 -- -jobs=2 -workers=2    anything after -- goes to libFuzzer
#
# New inputs that reach new code go to build-fuzz/corpus (tests/fuzz/corpus, the seeds, is only read); a
# crash is saved under build-fuzz/crashes/ with the command that replays it. Exits with 77 (what ctest counts
# as skipped) when no clang with libFuzzer is installed: Debian 12's clang-14 and libclang-rt-14-dev.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=600
build_only=0
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --time) seconds="$2"; shift 2 ;;
    --build) build_only=1; shift ;;
    --) shift; extra=("$@"); break ;;
    *) echo "usage: scripts/fuzz.sh [--time SECONDS] [--build] [-- LIBFUZZER_ARGS...]" >&2; exit 2 ;;
  esac
done

if [ ! -f build-fuzz/CMakeCache.txt ]; then
  cc="" cxx=""
  for v in "" -14; do
    if command -v "clang++$v" >/dev/null 2>&1 && command -v "clang$v" >/dev/null 2>&1; then
      cc="clang$v" cxx="clang++$v"
      break
    fi
  done
  if [ -z "$cxx" ]; then
    echo "fuzz: clang is not installed (Debian: apt-get install clang-14 libclang-rt-14-dev); skipped" >&2
    exit 77
  fi
  # clang links -fsanitize=fuzzer from compiler-rt (libclang-rt-14-dev), which apt does not install with
  # clang-14 when recommends are off: try it before configuring.
  probe=$(mktemp -d)
  trap 'rm -rf "$probe"' EXIT
  echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' >"$probe/t.cpp"
  if ! "$cxx" -fsanitize=fuzzer "$probe/t.cpp" -o "$probe/t" 2>"$probe/err"; then
    cat "$probe/err" >&2
    echo "fuzz: $cxx cannot link -fsanitize=fuzzer (Debian: apt-get install libclang-rt-14-dev); skipped" >&2
    exit 77
  fi
  launcher=()
  command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # -O1 -g: what libFuzzer's documentation suggests (fast enough, stack traces that name lines).
  CC="$cc" CXX="$cxx" cmake -S . -B build-fuzz -G Ninja -DBOUNCE_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" "${launcher[@]}" >/dev/null
fi
cmake --build build-fuzz -j "$(nproc)"
[ "$build_only" -eq 1 ] && exit 0

mkdir -p build-fuzz/corpus build-fuzz/crashes
# -timeout: an input that takes more than 20 s is a finding (the loader checks sizes before any work);
# -rss_limit_mb: so is one that needs more than 2 GiB. Leak checking stays on: no GL driver here.
status=0
build-fuzz/tests/fuzz/gltf_fuzz -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
    -dict=tests/fuzz/gltf.dict -artifact_prefix=build-fuzz/crashes/ "${extra[@]}" \
    build-fuzz/corpus tests/fuzz/corpus || status=$?
if [ "$status" -ne 0 ]; then
  echo "fuzz: the loader failed on an input saved in build-fuzz/crashes/. Replay it with" >&2
  echo "  build-fuzz/tests/fuzz/gltf_fuzz build-fuzz/crashes/<file>" >&2
  echo "and once fixed, copy it into tests/fuzz/corpus/ so that gltf_fuzz_replay keeps checking it." >&2
fi
exit "$status"
