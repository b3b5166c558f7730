#!/usr/bin/python3
"""Roofline of a bench run: every pass with a bound (bounce bench --roofline) as a point, arithmetic
intensity (flops per byte) against achieved throughput (GFLOP/s), under this machine's measured
ceilings (fragment and compute: FMA throughput as the roof, bandwidth as the slope). Passes that do no
arithmetic are drawn at the bottom, on their bytes per second instead.

usage: plot_roofline.py roofline.csv roofline.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("roofline.csv has no passes with a bound")
    fig, (ax, eff) = plt.subplots(1, 2, figsize=(14, 6))
    c = rows[0]
    xs = [2.0 ** (k / 4.0) for k in range(-40, 49)]
    for stage, colour in (("fragment", "tab:blue"), ("compute", "tab:orange")):
        flops, gbps = float(c[stage + "_gflops"]), float(c[stage + "_gbps"])
        ax.plot(xs, [min(flops, gbps * x) for x in xs], color=colour, lw=1.5, label=f"{stage} ceiling")
    techniques = sorted({r["technique"] for r in rows})
    markers = "osD^v<>ph*"
    for i, t in enumerate(techniques):
        pts = [r for r in rows if r["technique"] == t and float(r["flops"]) > 0 and float(r["bytes"]) > 0]
        ax.scatter([float(r["flops"]) / float(r["bytes"]) for r in pts],
                   [float(r["flops"]) / float(r["ms"]) * 1e-6 for r in pts],
                   marker=markers[i % len(markers)], label=t, alpha=0.8)
        for r in pts:
            ax.annotate(r["pass"], (float(r["flops"]) / float(r["bytes"]), float(r["flops"]) / float(r["ms"]) * 1e-6),
                        fontsize=6, alpha=0.7)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("arithmetic intensity (flop / byte)")
    ax.set_ylabel("achieved GFLOP/s")
    ax.set_title("roofline: passes under the measured ceilings")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    labels = [f"{r['technique']}:{r['pass']}" for r in rows]
    effs = [float(r["efficiency"]) for r in rows]
    eff.barh(range(len(rows)), effs, color=["tab:green" if e >= 1 / 3 else "tab:red" for e in effs])
    eff.set_yticks(range(len(rows)))
    eff.set_yticklabels(labels, fontsize=6)
    eff.axvline(1 / 3, color="k", ls="--", lw=1, label="within 3x of the bound")
    eff.set_xscale("log")
    eff.set_xlabel("efficiency (bound / measured)")
    eff.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
