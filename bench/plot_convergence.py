#!/usr/bin/python3
"""Convergence of progressive techniques beside the path tracer (the paper's Fig. 10 for ray-bundles).

Reads a `bounce bench` results.json and draws, one row per scene and image size: the relative RMSE against
`full` after every timed frame of each run recorded with "curve": true against the GPU time so far, with the
path tracer's rows ("pathTracerSpp": its render time against its error) as one more curve (left, log
scales); and the same errors against the accumulation steps (ray-bundle directions, point-projection
frames...) so far (right, log scales). Runs under Debian's python3 with python3-matplotlib.

usage: plot_convergence.py RESULTS.json OUT.png [--title TEXT]
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    records = json.load(open(argv[1]))
    title = argv[argv.index("--title") + 1] if "--title" in argv else "convergence against the path tracer"
    groups = []  # (scene, size) in order of appearance
    for r in records:
        key = (r.get("scene"), r.get("size"))
        if r.get("curve") and key not in groups:
            groups.append(key)
    if not groups:
        print("plot_convergence.py: no run in %s recorded a curve" % argv[1], file=sys.stderr)
        return 1
    fig, axes = plt.subplots(len(groups), 2, figsize=(11, 4 * len(groups)), squeeze=False)
    for row, (scene, size) in enumerate(groups):
        left, right = axes[row]
        for r in records:
            if (r.get("scene"), r.get("size")) != (scene, size) or not r.get("curve"):
                continue
            label = r["technique"] + ("" if r.get("settings") in (None, "", "defaults") else " " + r["settings"])
            points = [p for p in r["curve"] if p.get("relativeRmseFull", 0) > 0]
            left.plot([p["elapsedMs"] for p in points], [p["relativeRmseFull"] for p in points], label=label)
            right.plot([p["accumulated"] for p in points], [p["relativeRmseFull"] for p in points], label=label)
        tracer = sorted(
            (r["totalMs"], r["error"]["full"]["relativeRmse"])
            for r in records
            if (r.get("scene"), r.get("size")) == (scene, size) and r.get("technique") == "path-tracer"
            and r.get("error", {}).get("full", {}).get("relativeRmse", 0) > 0
        )
        if tracer:
            left.plot([t for t, _ in tracer], [e for _, e in tracer], "o-", color="black", label="path tracer")
        for ax, xlabel in ((left, "GPU time so far (ms); the path tracer: its render time"),
                           (right, "accumulation steps (grb: directions)")):
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(xlabel)
            ax.set_ylabel("relative RMSE vs full")
            ax.set_title("%s, %s" % (scene, size))
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(argv[2], dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
