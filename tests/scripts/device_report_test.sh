#!/usr/bin/env bash
# scripts/device_report.py fails the device check when a figure it was asked for is missing: a bench
# config of two scenes, `direct` and a two-value sweep of `rsm`, with one of the six runs absent from
# results.json (as a bench cut off by its budget leaves it) gives "ok": false and names the run; with
# every run present, "ok": true. Run by ctest (tests/CMakeLists.txt) from the project's root.
set -euo pipefail
report="$(pwd)/scripts/device_report.py"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir -p "$dir/logs" "$dir/tiny"
echo '{"renderer": "test", "platform": "test", "glVersion": "4.5"}' >"$dir/logs/hello.json"
cat >"$dir/tiny.json" <<'JSON'
{"size": "16x16", "scenes": ["cornell-area", "assets/setups/sponza-sun.json"],
 "runs": [{"technique": "direct"}, {"technique": "rsm", "sweep": {"vpls": [4, 64]}}]}
JSON
printf 'tiny\t%s\n' "$dir/tiny.json" >"$dir/logs/benches-asked.txt"
rows() { # the scene/technique pairs given, as results.json rows
    python3 -c 'import json, sys; print(json.dumps([{"scene": a.split(":")[0], "technique": a.split(":")[1],
        "size": "16x16", "totalMs": 1.0} for a in sys.argv[1:]]))' "$@"
}
ok() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["ok"])' "$dir/report.json"; }

rows cornell-area:direct cornell-area:rsm cornell-area:rsm assets/setups/sponza-sun.json:direct \
    assets/setups/sponza-sun.json:rsm >"$dir/tiny/results.json"
python3 "$report" "$dir"
[ "$(ok)" = False ] || { echo "FAIL: a missing run was not noticed"; exit 1; }
grep -q 'figure missing: tiny: rsm on assets/setups/sponza-sun.json: 1 of 2 runs' "$dir/report.md" ||
    { echo "FAIL: the report does not name the missing run"; cat "$dir/report.md"; exit 1; }

rows cornell-area:direct cornell-area:rsm cornell-area:rsm assets/setups/sponza-sun.json:direct \
    assets/setups/sponza-sun.json:rsm assets/setups/sponza-sun.json:rsm >"$dir/tiny/results.json"
python3 "$report" "$dir"
[ "$(ok)" = True ] || { echo "FAIL: every run is there and the check still fails"; cat "$dir/report.md"; exit 1; }

rm "$dir/tiny/results.json"
python3 "$report" "$dir"
[ "$(ok)" = False ] || { echo "FAIL: a bench that wrote no results.json was not noticed"; exit 1; }
echo "device_report: missing figures fail the check"
