#!/usr/bin/python3
"""Renders scenes small with prism and tiles them into one labelled contact sheet (PNG).

Usage: tools/contact_sheet.py OUT.png SCENE... [--prism build/prism] [--res 320x240] [--spp 4]
Scenes that fail are shown as a red tile with the error message.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--prism", default="build/prism")
    ap.add_argument("--res", default="320x240")
    ap.add_argument("--spp", default="4")
    ap.add_argument("--cols", type=int, default=3)
    a = ap.parse_args()
    w, h = (int(v) for v in a.res.split("x"))
    tiles = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, scene in enumerate(a.scenes):
            label = os.path.join(os.path.basename(os.path.dirname(scene)), os.path.basename(scene))
            img = os.path.join(tmp, f"{i}.png")
            r = subprocess.run([a.prism, "render", scene, "-o", img, "--res", a.res, "--spp", a.spp,
                                "--no-progress"], capture_output=True, text=True)
            warnings = sum(1 for l in r.stderr.splitlines() if "warning:" in l)
            if r.returncode == 0:
                tiles.append((label + (f"  ({warnings} warnings)" if warnings else ""), mpimg.imread(img)))
            else:
                err = [l for l in r.stderr.splitlines() if "error" in l]
                tiles.append((label + " FAILED: " + (err[0][-60:] if err else ""), None))
            print(f"{label}: exit {r.returncode}, {warnings} warnings", file=sys.stderr)
    rows = (len(tiles) + a.cols - 1) // a.cols
    fig, axes = plt.subplots(rows, a.cols, figsize=(a.cols * w / 100, rows * (h + 28) / 100), dpi=100)
    for ax in axes.flat if rows * a.cols > 1 else [axes]:
        ax.axis("off")
    for ax, (label, img) in zip(axes.flat, tiles):
        if img is not None:
            ax.imshow(img)
        else:
            ax.set_facecolor((0.4, 0.05, 0.05))
        ax.set_title(label, fontsize=8)
    fig.tight_layout(pad=0.3)
    fig.savefig(a.out)
    print(f"wrote {a.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
