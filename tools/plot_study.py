#!/usr/bin/python3
"""Plots for `prism study`: reads results.csv and writes into OUTDIR one time_<knob>.png per
knob (cost against rmse, each point labelled with its value) and pareto.png (every setting,
coloured by knob, with the Pareto front of cost against rmse). Cost is BVH build + render
seconds, as in report.md. Each PNG is written to a temporary file and renamed. Needs matplotlib
(Debian: python3-matplotlib); `prism study` runs it when it is available."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# A costlier setting joins the front only if it lowers the rmse by more than this fraction
# (study_report.cpp ParetoRelativeTolerance).
PARETO_TOLERANCE = 0.005


def number(s):
    try:
        return float(s)
    except ValueError:
        return math.nan


def save(fig, path):
    tmp = os.path.join(os.path.dirname(path) or ".",
                       "." + os.path.basename(path) + ".tmp-%d" % os.getpid())
    try:
        fig.savefig(tmp, dpi=110, format="png")
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)


def pareto(rows):
    pts = [r for r in rows if not math.isnan(r["rmse"])]
    pts.sort(key=lambda r: (r["cost"], r["rmse"]))
    front, best = [], math.inf
    for r in pts:
        if r["rmse"] < best * (1 - PARETO_TOLERANCE):
            front.append(r)
            best = r["rmse"]
    return front


# Log axes: an exact match (rmse 0) is drawn at a floor below the other points.
def floor_for(rows):
    pos = [r["rmse"] for r in rows if r["rmse"] > 0 and math.isfinite(r["rmse"])]
    return min(pos) / 10 if pos else 1e-6


def main():
    if len(sys.argv) != 3:
        print("usage: plot_study.py results.csv OUTDIR", file=sys.stderr)
        return 2
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    out = sys.argv[2]
    for r in rows:
        r["time"] = number(r["time_s"])
        r["cost"] = number(r["build_s"]) + r["time"]
        r["rmse"] = number(r["rmse"])
    if not rows:
        return 0
    floor = floor_for(rows)
    knobs = []
    for r in rows:
        if r["knob"] not in knobs:
            knobs.append(r["knob"])

    for knob in knobs:
        rs = [r for r in rows if r["knob"] == knob]
        fig, ax = plt.subplots(figsize=(6.4, 4.6))
        xs = [r["rmse"] if r["rmse"] > 0 else floor for r in rs]
        ax.plot(xs, [r["time"] for r in rs], "o-", label="render")
        ax.plot(xs, [r["cost"] for r in rs], "s:", alpha=0.6, label="build + render")
        for x, r in zip(xs, rs):
            ax.annotate(r["value"], (x, r["cost"]), textcoords="offset points", xytext=(4, 4),
                        fontsize=8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("RMSE against the reference" + (" (0 drawn at the floor)"
                                                       if any(r["rmse"] == 0 for r in rs) else ""))
        ax.set_ylabel("seconds (median)")
        ax.set_title(f"{knob}: time against error")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        save(fig, os.path.join(out, f"time_{knob}.png"))

    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    for knob in knobs:
        rs = [r for r in rows if r["knob"] == knob]
        ax.plot([r["rmse"] if r["rmse"] > 0 else floor for r in rs], [r["cost"] for r in rs],
                "o", label=knob, alpha=0.75)
    front = pareto(rows)
    if front:
        ax.plot([r["rmse"] if r["rmse"] > 0 else floor for r in front], [r["cost"] for r in front],
                "k-", lw=1.2, label="Pareto front")
        for r in front:
            ax.annotate(f"{r['knob']} {r['value']}",
                        (r["rmse"] if r["rmse"] > 0 else floor, r["cost"]),
                        textcoords="offset points", xytext=(4, -10), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("RMSE against the reference")
    ax.set_ylabel("build + render seconds (median)")
    ax.set_title("Every setting and the Pareto front")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    save(fig, os.path.join(out, "pareto.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
