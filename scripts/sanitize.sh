#!/usr/bin/env bash
# The test suite built with AddressSanitizer and UndefinedBehaviorSanitizer (gcc, -Og -g1, see below) into
# build-asan/ and run there; any report fails the test it comes from (halt_on_error, no recovery), so the
# run fails. .ci/run runs it after ./test.sh: every test; its build took 12 minutes on 2 cores from a clean clone.
#
#   scripts/sanitize.sh            build, then run the suite
#   scripts/sanitize.sh -R Cache   extra arguments go to ctest
#
# Leak checking is on for the suites that load no GL driver (labels core and ref, the fuzz corpus replay)
# and off for gl and app (detect_leaks=0): Mesa's llvmpipe keeps allocations to process exit (in
# libOSMesa and in its LLVM JIT's code, which has no module name a suppression could match), so
# LeakSanitizer reports the driver in every GL test. Nothing else is suppressed: neither sanitizer reports
# anything in Mesa (its libraries are not instrumented). The fuzz test (gltf_fuzz) is left out: it has
# its own clang build under the same sanitizers (scripts/fuzz.sh), and runs in ./test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

# abort_on_error: a report ends the test with SIGABRT, which ctest counts as a failure.
asan="halt_on_error=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The test binaries run while building (to list their tests): the options are needed from here on.
export ASAN_OPTIONS="$asan:detect_leaks=0"

# -Og -g1 rather than RelWithDebInfo's -O2 -g: the instrumented -O2 build took 32 minutes of CI's 90 (the
# test file tests/app/cli_test.cpp alone 186 s, 49 s at -Og -g1), and the tests' time is spent in Mesa's
# JIT-compiled shaders, which no flag here changes. -g1 keeps the line tables a report's stack needs.
opt="-Og -g1 -DNDEBUG"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="$opt" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$opt" >/dev/null
cmake --build build-asan -j "$(nproc)"

cd build-asan
status=0
ASAN_OPTIONS="$asan:detect_leaks=1" ctest --output-on-failure -j "$(nproc)" --timeout 900 -L '^(core|ref)$' \
    -E '^gltf_fuzz$' "$@" || status=1
# Conformance's scale-change and switch cases (two per technique, up to 42 s each here under the
# sanitizers) run the passes Conformance.Technique runs under them already; the coarse targets' allocation
# runs under them in JointUpsampleTest. They stay in the README's test command.
# Conformance keeps Mesa's shader cache here (tests/gl/conformance_test.cpp): the compiler warnings it turns it
# off to catch were checked in the README's test command, and what the sanitizers check is Bounce's code.
# With the cache off, LLVM's compiles through the sanitizer's allocator were most of these cases' time
# (Conformance.Technique/photon: 170 s alone; perf put 0.3% of it in Bounce's code, 37% in LLVM, 33% in the
# sanitizer's runtime).
export BOUNCE_CONFORMANCE_SHADER_CACHE=1
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j "$(nproc)" --timeout 900 -LE '^(core|ref)$' \
    -E '^gltf_fuzz$|Conformance[.](ScaleChangeLeavesNoTrace|SwitchShowsOnlyTheNewTechnique)/' "$@" || status=1
exit "$status"
