#!/usr/bin/python3
"""The plot of `prism bench compare --out DIR`: relative RMSE against CPU seconds, log-log, one
colour per renderer (its measured counts and its fitted curve: error e^a n^b at the time
t0 + c n), and the target error. Reads compare.csv and fit.csv, writes the PNG. Needs matplotlib
(Debian: python3-matplotlib)."""
import csv
import math
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 5:
        print("usage: plot_compare.py compare.csv fit.csv TARGET out.png", file=sys.stderr)
        return 2
    rows = list(csv.DictReader(open(sys.argv[1])))
    fits = {r["renderer"]: r for r in csv.DictReader(open(sys.argv[2]))}
    target = float(sys.argv[3])
    runs = {}
    for r in rows:
        runs.setdefault(r["renderer"], {}).setdefault(int(r["spp"]), []).append(r)
    fig, ax = plt.subplots(figsize=(7, 5))
    for name, by_spp in runs.items():
        pts = []
        for spp, rs in sorted(by_spp.items()):
            errs = [float(r["rel_rmse"]) for r in rs if r["rel_rmse"]]
            if errs:
                pts.append((statistics.median(float(r["cpu_seconds"]) for r in rs), errs[0], spp))
        if not pts:
            continue
        line, = ax.plot([p[0] for p in pts], [p[1] for p in pts], "o", label=name)
        for t, e, spp in pts:
            ax.annotate(str(spp), (t, e), textcoords="offset points", xytext=(4, 4),
                        fontsize=7)
        f = fits.get(name)
        if f and f["b"]:
            a, b, t0, c = (float(f[k]) for k in ("a", "b", "t0", "c"))
            ns = [min(by_spp), max(by_spp)]
            if f["spp_at_target"]:
                ns.append(float(f["spp_at_target"]))
            lo, hi = min(ns), max(ns)
            xs = [lo * (hi / lo) ** (i / 50) for i in range(51)]
            ax.plot([t0 + c * n for n in xs], [math.exp(a) * n ** b for n in xs], "-",
                    color=line.get_color(), alpha=0.6)
    ax.axhline(target, color="black", linestyle="--", label="target %.4g" % target)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU seconds (whole process, median)")
    ax.set_ylabel("relative RMSE against the reference")
    ax.set_title("Equal-error comparison (labels: spp)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(sys.argv[4], dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
