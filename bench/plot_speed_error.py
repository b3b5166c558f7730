#!/usr/bin/python3
"""Speed against error: the project's headline plot.

Reads a `bounce bench` results.csv and draws the GPU time of each image (x: its frames times the median
frame, the CSV's image_ms) against relative RMSE (y), log scales, one curve per technique (its parameter
sweep in order of time), one row of panels per scene and image size (times compare only at one size,
errors only on one scene), one column per error reference (the technique's own light paths, and `full`),
and marks each panel's Pareto front as the bench computed it (pareto_own, pareto_full: no other row both
faster and more accurate; app/bench_report.cpp), so that this plot, report.md and report.html name the
same front. Runs under Debian's python3 with python3-matplotlib.

usage: plot_speed_error.py RESULTS.csv OUT.png [--title TEXT]
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    # Camera-path rows (a "camera_path" file) measure moving frames, not an image: not on these axes.
    rows = [r for r in csv.DictReader(open(argv[1], newline="")) if not r.get("camera_path")]
    title = argv[argv.index("--title") + 1] if "--title" in argv else "speed against error"
    panels = [("rel_rmse_own", "relative RMSE vs own light paths", "pareto_own"),
              ("rel_rmse_full", "relative RMSE vs full", "pareto_full")]
    panels = [p for p in panels if any(r.get(p[0]) not in (None, "", "nan") for r in rows)]
    if not panels:
        print("plot_speed_error.py: no error figures in %s (were references computed?)" % argv[1], file=sys.stderr)
        return 1
    groups = sorted({(r["scene"], r["size"]) for r in rows},
                    key=lambda g: (g[0], -int(g[1].split("x")[0]) * int(g[1].split("x")[1])))
    techniques = sorted({r["technique"] for r in rows})
    colour = {t: "C%d" % (i % 10) for i, t in enumerate(techniques)}  # one colour per technique in every panel
    fig, axes = plt.subplots(len(groups), len(panels), figsize=(6.5 * len(panels), 4.5 * len(groups)), squeeze=False)
    for row, (scene, size) in zip(axes, groups):
        for ax, (column, label, marked) in zip(row, panels):
            points = []
            named = []  # the CSV row of each point
            for technique in sorted({r["technique"] for r in rows if r["scene"] == scene and r["size"] == size}):
                sel = [r for r in rows if r["scene"] == scene and r["size"] == size and r["technique"] == technique
                       and r.get(column) not in (None, "", "nan") and 0 < float(r[column]) < math.inf]
                sel.sort(key=lambda r: float(r["image_ms"]))
                if not sel:
                    continue
                xs = [float(r["image_ms"]) for r in sel]
                ys = [float(r[column]) for r in sel]
                ax.plot(xs, ys, "o-", label=technique, markersize=4, color=colour[technique])
                points += list(zip(xs, ys))
                named += sel
            front = sorted((i for i, r in enumerate(named) if r.get(marked) == "1"), key=lambda i: points[i][0])
            # The front in words too (tests check it against results.csv): technique, parameters, ms, error.
            print("pareto front, %s %s, %s: %s" % (scene, size, column, "; ".join(
                "%s (%s) %s %s" % (named[i]["technique"], named[i]["params"], named[i]["image_ms"], named[i][column])
                for i in front)))
            # A front per GL renderer (a merge of shards run on several machines): their times do not compare.
            renderers = sorted({named[i].get("renderer", "") for i in front})
            for k, renderer in enumerate(renderers):
                mine = [i for i in front if named[i].get("renderer", "") == renderer]
                ax.step([points[i][0] for i in mine], [points[i][1] for i in mine], "k--", where="post",
                        linewidth=1, label="Pareto front" + (" (%s)" % renderer if len(renderers) > 1 else ""),
                        dashes=(4 + 3 * k, 2 + k))
                ax.scatter([points[i][0] for i in mine], [points[i][1] for i in mine], s=80, facecolors="none",
                           edgecolors="k", zorder=3, marker="os^Dv"[k % 5])
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_title("%s, %s" % (scene, size), fontsize=10)
            ax.set_xlabel("GPU ms to the image (frames x median ms; path tracer: CPU ms)")
            ax.set_ylabel(label)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(argv[2] + ".tmp.png", dpi=120)
    import os
    os.replace(argv[2] + ".tmp.png", argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
