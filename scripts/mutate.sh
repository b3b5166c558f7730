#!/usr/bin/env bash
# Mutation check: applies each named mutation of scripts/mutations.ini (GLSL and C++) to a copy of the
# tree, builds it, runs the tests the mutation names and reports whether they caught it (failed). Every
# mutation must be caught; the script exits 1 when one is missed or does not apply. Run by hand, not by
# the test suite (a C++ mutation rebuilds what depends on it: minutes each on 2 cores; GLSL ones need no
# build, shaders are read at run time).
#
#   scripts/mutate.sh                      every mutation
#   scripts/mutate.sh eq8-constant ...     only these
#   MUTATE_DIR=/tmp/x scripts/mutate.sh    where the copy and its build live (default /tmp/bounce-mutate)
#
# The copy is refreshed from the working tree (build outputs left out) and built once with
# ccache; each mutation then edits one file, rebuilds incrementally, runs `ctest -R <tests>` and restores
# the file.
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
dir="${MUTATE_DIR:-/tmp/bounce-mutate}"
list="$src/scripts/mutations.ini"

# A fresh copy with the files' own times (tar keeps them), its build/ kept: ninja rebuilds only what changed
# since the last run. The build sits where the working tree's does (tree/build), so that ccache, with
# CCACHE_BASEDIR making paths relative, reuses what scripts/build.sh compiled.
mkdir -p "$dir/tree"
find "$dir/tree" -mindepth 1 -maxdepth 1 ! -name build -exec rm -rf {} +
tar -C "$src" --exclude='./build*' --exclude=./node_modules --exclude=./out --exclude=./.git -cf - . | tar -C "$dir/tree" -xf -
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="$dir/tree"
build="$dir/tree/build"
cmake -S "$dir/tree" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
echo "mutate: building the unmutated copy in $build"
cmake --build "$build" -j "$(nproc)" >/dev/null

# name<TAB>file<TAB>tests for every mutation, in file order (or those named on the command line).
names=$(/usr/bin/python3 - "$list" "$@" <<'PY'
import configparser, sys
c = configparser.ConfigParser(interpolation=None)
c.optionxform = str
c.read(sys.argv[1])
wanted = sys.argv[2:]
for w in wanted:
    if w not in c.sections():
        sys.exit("mutate: no mutation named '%s' (see scripts/mutations.ini)" % w)
for s in c.sections():
    if not wanted or s in wanted:
        print("%s\t%s\t%s" % (s, c[s]["file"], c[s]["tests"]))
PY
)

caught=0
missed=0
results=""
while IFS=$'\t' read -r name file tests; do
    [ -n "$name" ] || continue
    target="$dir/tree/$file"
    cp "$target" "$dir/original"
    if ! /usr/bin/python3 - "$list" "$name" "$target" <<'PY'
import configparser, sys
c = configparser.ConfigParser(interpolation=None)
c.optionxform = str
c.read(sys.argv[1])
m = c[sys.argv[2]]
text = open(sys.argv[3]).read()
if text.count(m["from"]) != 1:
    sys.exit("mutate: %s: 'from' occurs %d times in %s (must be once)" % (sys.argv[2], text.count(m["from"]), m["file"]))
open(sys.argv[3], "w").write(text.replace(m["from"], m["to"]))
PY
    then
        results+="$name: DOES NOT APPLY\n"
        missed=$((missed + 1))
        continue
    fi
    echo "mutate: $name ($file), tests '$tests'"
    if ! cmake --build "$build" -j "$(nproc)" >"$dir/$name.build.log" 2>&1; then
        results+="$name: caught (does not build)\n"
        caught=$((caught + 1))
    elif (cd "$build" && xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest -R "$tests" --timeout 900 \
              >"$dir/$name.log" 2>&1); then
        ran=$(grep -c "Test *#" "$dir/$name.log" || true)
        if [ "$ran" -eq 0 ]; then
            results+="$name: NO TEST MATCHES '$tests'\n"
        else
            results+="$name: MISSED ($ran tests passed; $dir/$name.log)\n"
        fi
        missed=$((missed + 1))
    else
        failed=$(grep -E "^\s+[0-9]+ - " "$dir/$name.log" | sed 's/^ *[0-9]* - //; s/ *#.*//; s/ (.*//' | tr -s ' \n' ' ')
        results+="$name: caught by $failed\n"
        caught=$((caught + 1))
    fi
    cp "$dir/original" "$target"
done <<<"$names"
# Leave the copy's build matching the unmutated tree.
cmake --build "$build" -j "$(nproc)" >/dev/null 2>&1 || true

printf "\n%b" "$results"
echo "mutate: $caught caught, $missed missed or not applied"
[ "$missed" -eq 0 ]
