#!/usr/bin/env python3
"""Aliasing of a render in a region against a reference (docs/MATERIALS.md).

Usage: tools/moire_metric.py REFERENCE.exr X0 Y0 W H IMAGE.exr [IMAGE.exr ...]

For each IMAGE, in the region (x0, y0, w, h) of linear RGB: the RMSE against REFERENCE, and
the high-frequency energy (mean square of the image minus its 3x3 box blur, i.e. the detail
at the scale of a pixel), printed as the ratio to the reference's. Aliasing (moire, crawling
checks) shows as excess high-frequency energy and as error; a ratio near 1 is the reference's
own detail. Pixels are read through oiiotool --dumpdata, so only the standard library
is needed.
"""
import os
import subprocess
import sys
import tempfile


def read(path, x0, y0, w, h):
    with tempfile.TemporaryDirectory() as d:
        cut = os.path.join(d, "cut.exr")
        subprocess.run(["oiiotool", path, "--ch", "R,G,B", "--cut", f"{w}x{h}+{x0}+{y0}",
                        "-d", "float", "-o", cut], check=True)
        out = subprocess.run(["oiiotool", "--dumpdata", cut], check=True, capture_output=True,
                             text=True).stdout
    img = [None] * (w * h)
    for line in out.splitlines():
        line = line.strip()
        if not line.startswith("Pixel ("):
            continue
        xy, values = line[len("Pixel ("):].split("):")
        x, y = map(int, xy.split(","))
        img[y * w + x] = list(map(float, values.split()))[:3]
    assert all(p is not None for p in img)
    return img


def high_freq(img, w, h):
    e, n = 0.0, 0
    for y in range(1, h - 1):
        for x in range(1, w - 1):
            for c in range(3):
                s = sum(img[(y + j) * w + x + i][c] for j in (-1, 0, 1) for i in (-1, 0, 1))
                d = img[y * w + x][c] - s / 9
                e += d * d
                n += 1
    return e / n


def main():
    ref_path, x0, y0, w, h = sys.argv[1], *map(int, sys.argv[2:6])
    ref = read(ref_path, x0, y0, w, h)
    ref_hf = high_freq(ref, w, h)
    print(f"region {w}x{h}+{x0}+{y0}; reference high-frequency energy {ref_hf:.3e}")
    for p in sys.argv[6:]:
        img = read(p, x0, y0, w, h)
        mse = sum((a[c] - b[c]) ** 2 for a, b in zip(img, ref) for c in range(3)) / (3 * w * h)
        hf = high_freq(img, w, h)
        print(f"{p}: RMSE {mse ** 0.5:.4f}, high-frequency energy {hf:.3e} "
              f"({hf / ref_hf:.2f}x the reference's)")


if __name__ == "__main__":
    main()
