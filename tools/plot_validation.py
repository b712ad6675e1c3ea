#!/usr/bin/python3
"""Convergence plots for `prism validate`: reads results.csv, writes convergence.png (all
shapes: mean |dt| against n_phi on log-log axes with an O(n^-2) reference slope, and time per
ray against n_phi) into the output directory. Run with Debian's /usr/bin/python3
(python3-matplotlib)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        print("usage: plot_validation.py results.csv OUTDIR", file=sys.stderr)
        return 2
    rows = list(csv.DictReader(open(sys.argv[1])))
    shapes = {}
    for r in rows:
        shapes.setdefault(r["shape"], []).append(r)
    fig, (ax0, axs, ax1) = plt.subplots(1, 3, figsize=(19, 5.2))
    ref_drawn = False
    for name, rs in shapes.items():
        n = [int(r["level"]) for r in rs]
        dt = [float(r["dt_mean"]) for r in rs]
        h = [float(r["h"]) for r in rs]
        ns_mesh = [float(r["ns_per_ray_mesh"]) for r in rs]
        ns_an = float(rs[0]["ns_per_ray_analytic"])
        pts = [(a, b) for a, b in zip(n, dt) if b > 0]
        slope = rs[0].get("slope", "")
        label = name + (f" (slope {float(slope):.2f})" if slope else " (exact in plane)")
        if pts:
            line, = ax0.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=label)
            ax0.loglog(n, h, ":", color=line.get_color(), alpha=0.5)
            color = line.get_color()
        else:
            color = None
        if not ref_drawn and pts and slope:
            n0, d0 = pts[0]
            ax0.loglog([n0, n[-1]], [d0 * 1.5, d0 * 1.5 * (n[-1] / n0) ** -2], "k--",
                       label="O(n^-2) reference")
            ref_drawn = True
        # Shading-normal error (mean, degrees); the disk's sits at float rounding.
        sh = [(a, float(r["shading_err_deg_mean"])) for a, r in zip(n, rs)]
        sh = [p for p in sh if p[1] > 0]
        sslope = rs[0].get("shading_slope", "")
        if sh:
            axs.loglog([p[0] for p in sh], [p[1] for p in sh], "o-", color=color,
                       label=name + (f" (slope {float(sslope):.2f})" if sslope else ""))
        l2, = ax1.loglog(n, ns_mesh, "o-", color=color, label=name + " triangles")
        ax1.axhline(ns_an, color=l2.get_color(), ls="--", alpha=0.6)
    ax0.set_xlabel("n_phi (segments around the axis)")
    ax0.set_ylabel("mean |t_mesh - t_analytic|  (dotted: band h)")
    ax0.set_title("Tessellation error against n")
    ax0.grid(True, which="both", alpha=0.3)
    ax0.legend(fontsize=7)
    axs.set_xlabel("n_phi")
    axs.set_ylabel("mean shading-normal error (degrees)")
    axs.set_title("Interpolated vertex normals against n")
    axs.grid(True, which="both", alpha=0.3)
    axs.legend(fontsize=7)
    ax1.set_xlabel("n_phi")
    ax1.set_ylabel("ns per ray (dashed: analytic)")
    ax1.set_title("Time per ray (1 thread, rtcIntersect1)")
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend(fontsize=7)
    fig.tight_layout()
    out = sys.argv[2] + "/convergence.png"
    fig.savefig(out, dpi=110)
    print("wrote " + out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
