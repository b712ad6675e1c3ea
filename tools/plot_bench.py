#!/usr/bin/python3
"""Plots for `prism bench suite --out DIR`: reads results.csv, writes bench.png into DIR
(POV-Ray comparison times, start-up times and the issue-10 target ratios). Needs matplotlib
(Debian: python3-matplotlib)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        print("usage: plot_bench.py results.csv OUTDIR", file=sys.stderr)
        return 2
    rows = list(csv.DictReader(open(sys.argv[1])))
    val = {r["metric"]: float(r["value"]) for r in rows}
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))

    ax = axes[0]
    labels, prism, pov = [], [], []
    for aa in ("noaa", "aa"):
        for t in (1, 2):
            key = "whitted %s %dT" % (aa, t)
            if key + " prism whole" in val:
                labels.append("%s %dT" % ("AA" if aa == "aa" else "no AA", t))
                prism.append(val[key + " prism whole"])
                pov.append(val[key + " povray whole"])
    if labels:
        x = range(len(labels))
        ax.bar([i - 0.2 for i in x], prism, 0.4, label="Prism")
        ax.bar([i + 0.2 for i in x], pov, 0.4, label="POV-Ray 3.7")
        ax.set_xticks(list(x), labels)
        ax.legend()
    ax.set_title("Whitted scene, whole process (s)")

    ax = axes[1]
    names = [n for n in ("prism --help", "render whitted 8x6") if n in val]
    ax.bar(names, [val[n] for n in names], color="tab:green")
    ax.axhline(30, color="red", linestyle="--", label="target 30 ms")
    ax.set_title("Start-up, whole process (ms)")
    ax.legend()

    ax = axes[2]
    # Each target as a margin: measured/target for ">=" targets, target/measured for "<"
    # targets, so that 1 is the line to cross and larger is better.
    targets = [r for r in rows if r["target"]]
    names, margins, colors = [], [], []
    for r in targets:
        op, x = r["target"].split()
        v = float(r["value"])
        m = v / float(x) if op.startswith(">") else (float(x) / v if v > 0 else 0)
        names.append(r["metric"])
        margins.append(max(m, 1e-3))
        colors.append("tab:green" if r["status"] == "met" else "tab:red")
    ax.barh(names, margins, color=colors)
    ax.axvline(1, color="black", linestyle="--")
    ax.set_xscale("log")
    ax.set_title("Targets: measured vs target (>1 met)")
    fig.tight_layout()
    fig.savefig(sys.argv[2] + "/bench.png", dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
