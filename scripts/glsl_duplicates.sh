#!/usr/bin/env bash
# Copied GLSL check (STYLE.md: "Shaders share code through glsl/common/ includes, never by copy"). Reads
# every file under glsl/ (every extension), drops comments and blank lines, folds whitespace, and reports
# each run of 6 or more identical consecutive lines found in two places (two files, or two places in one
# file) as `file:first-last ~ file:first-last (N lines)`, the line numbers those of the files as written.
# Run by the test suite (Glsl.NoDuplicateRuns).
#
#   scripts/glsl_duplicates.sh                  glsl/ of this tree, runs of 6 lines or more
#   scripts/glsl_duplicates.sh --min-lines 4    shorter runs too
#   scripts/glsl_duplicates.sh path/to/glsl     another folder
#
# Exit status: 0 when no run is found, 1 when one is, 2 for bad arguments.
set -euo pipefail

usage() {
  sed -n '2,12s/^# \{0,1\}//p' "$0"
}

min=6
root=""
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help)
      usage
      exit 0
      ;;
    --min-lines)
      [ $# -ge 2 ] || { echo "--min-lines needs a number (2 or more)" >&2; exit 2; }
      min="$2"
      shift 2
      ;;
    --min-lines=*)
      min="${1#--min-lines=}"
      shift
      ;;
    -*)
      echo "unknown option: $1 (allowed: --min-lines N, --help, a folder)" >&2
      exit 2
      ;;
    *)
      [ -z "$root" ] || { echo "one folder at most (got $root and $1)" >&2; exit 2; }
      root="$1"
      shift
      ;;
  esac
done
if ! [[ "$min" =~ ^[0-9]+$ ]] || [ "$min" -lt 2 ]; then
  echo "--min-lines takes a whole number of 2 or more (got '$min')" >&2
  exit 2
fi
if [ -z "$root" ]; then
  cd "$(dirname "$0")/.."
  root=glsl
fi
if [ ! -d "$root" ]; then
  echo "not a folder: $root" >&2
  exit 2
fi

exec /usr/bin/python3 - "$root" "$min" <<'PY'
import collections
import os
import sys

root, min_lines = sys.argv[1], int(sys.argv[2])


def code_lines(text):
    """(line number, line) for each line left once comments are dropped and whitespace folded."""
    kept = []
    line, number, i, n = [], 1, 0, len(text)

    def end_line():
        folded = " ".join("".join(line).split())
        if folded:
            kept.append((number, folded))
        line.clear()

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
            continue
        if text.startswith("/*", i):
            close = text.find("*/", i + 2)
            close = n if close < 0 else close + 2
            # A block comment separates what stands either side of it, like a space.
            line.append(" ")
            for _ in range(text.count("\n", i, close)):
                end_line()
                number += 1
            i = close
            continue
        if c == "\n":
            end_line()
            number += 1
        else:
            line.append(c)
        i += 1
    end_line()
    return kept


paths = []
for folder, dirs, files in os.walk(root):
    dirs.sort()
    paths += [os.path.join(folder, f) for f in sorted(files)]
paths.sort()
lines = {}
for path in paths:
    with open(path, encoding="utf-8", errors="replace") as f:
        lines[path] = code_lines(f.read())

# Every window of min_lines code lines, by its text; each text seen twice or more is shared.
windows = collections.defaultdict(list)
for path in paths:
    text = [t for _, t in lines[path]]
    for k in range(len(text) - min_lines + 1):
        windows[tuple(text[k:k + min_lines])].append((path, k))

# Shared windows, by pair of places and the offset between them: consecutive windows of one pair and
# offset make one run. Places are listed in path order, then line order, so each pair comes once.
starts = collections.defaultdict(set)
for places in windows.values():
    for a in range(len(places)):
        for b in range(a + 1, len(places)):
            (pa, ka), (pb, kb) = places[a], places[b]
            starts[(pa, pb, kb - ka)].add(ka)

runs = []
for (pa, pb, offset), ks in starts.items():
    ks = sorted(ks)
    first = last = ks[0]
    for k in ks[1:] + [None]:
        if k == last + 1:
            last = k
            continue
        la, lb = lines[pa], lines[pb]
        runs.append((pa, la[first][0], la[last + min_lines - 1][0],
                     pb, lb[first + offset][0], lb[last + offset + min_lines - 1][0],
                     last - first + min_lines))
        first = last = k

for r in sorted(runs):
    print("%s:%d-%d ~ %s:%d-%d (%d lines)" % r)
total = sum(len(v) for v in lines.values())
sys.stdout.flush()
if runs:
    print("%d run%s of %d or more identical lines under %s: give the code one home (an #include) "
          "instead" % (len(runs), "" if len(runs) == 1 else "s", min_lines, root), file=sys.stderr)
    sys.exit(1)
print("no duplicates: %d files, %d code lines under %s share no run of %d or more lines"
      % (len(paths), total, root, min_lines))
PY
