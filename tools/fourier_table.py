#!/usr/bin/env python3
"""Writes a .bsdf file in the layout pbrt-v3's Material "fourier" reads (Prism:
src/render/fourier_bsdf.h): for zenith cosines mu_i, mu_o on a grid, the Fourier coefficients
in the azimuth difference of f*|mu_i|, and each row's CDF (the integral of its a_0 Catmull-Rom
spline). The BSDF is a made-up glossy, coloured one for comparing renderers, not a measured
material: a lobe about the mirror direction that widens with --roughness, a diffuse base of
albedo --diffuse, a little transmission, red and blue scaled by --tint.

Usage: tools/fourier_table.py OUT.bsdf [--n 33] [--order 12] [--roughness 0.15]
                                       [--diffuse 0.3] [--tint 1.2 0.6] [--eta 1.5]
"""
import argparse
import math
import struct


def table(n, order, roughness, diffuse, tint):
    mu = [math.sin(math.pi / 2 * (-1 + 2 * i / (n - 1))) for i in range(n)]

    def coeffs(mi, mo):
        reflect = mi * mo < 0
        a = [0.0] * (3 * order)
        lum = [0.0] * order
        if reflect:
            lum[0] += diffuse * abs(mi) / math.pi
            # The glossy lobe peaks where wi mirrors wo (the azimuth difference 0 in the
            # convention of -wi against wo) and is narrower near normal incidence.
            closeness = math.exp(-((abs(mi) - abs(mo)) ** 2) / (2 * roughness ** 2))
            for k in range(order):
                lum[k] += 0.3 * abs(mi) * closeness * math.exp(-0.5 * (k * roughness * 2) ** 2)
        else:
            lum[0] += 0.03 * abs(mi)
        for k in range(order):
            a[k] = lum[k]
            a[order + k] = tint[0] * lum[k]
            a[2 * order + k] = tint[1] * lum[k]
        return a

    return mu, coeffs


def write(path, mu, coeffs, order, eta):
    n = len(mu)
    data, offlen, avg = [], [], [0.0] * (n * n)
    for o in range(n):
        for i in range(n):
            a = coeffs(mu[i], mu[o])
            m = order
            while m > 0 and all(a[c * order + m - 1] == 0 for c in range(3)):
                m -= 1
            offlen += [len(data), m]
            for c in range(3):
                data += a[c * order:c * order + m]
            avg[o * n + i] = a[0] if m > 0 else 0.0
    cdf = [0.0] * (n * n)
    for o in range(n):
        f = avg[o * n:(o + 1) * n]
        s = 0.0
        for i in range(n - 1):
            w = mu[i + 1] - mu[i]
            d0 = w * (f[i + 1] - f[i - 1]) / (mu[i + 1] - mu[i - 1]) if i > 0 else f[i + 1] - f[i]
            d1 = (w * (f[i + 2] - f[i]) / (mu[i + 2] - mu[i]) if i + 2 < n
                  else f[i + 1] - f[i])
            s += w * ((f[i] + f[i + 1]) / 2 + (d0 - d1) / 12)
            cdf[o * n + i + 1] = s
    with open(path, "wb") as out:
        out.write(b"SCATFUN\x01")
        out.write(struct.pack("<6i", 1, n, len(data), order, 3, 1))
        out.write(struct.pack("<3i", 0, 0, 0))
        out.write(struct.pack("<f", eta))
        out.write(struct.pack("<4i", 0, 0, 0, 0))
        out.write(struct.pack("<%df" % n, *mu))
        out.write(struct.pack("<%df" % (n * n), *cdf))
        out.write(struct.pack("<%di" % len(offlen), *offlen))
        out.write(struct.pack("<%df" % len(data), *data))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out")
    p.add_argument("--n", type=int, default=33)
    p.add_argument("--order", type=int, default=12)
    p.add_argument("--roughness", type=float, default=0.15)
    p.add_argument("--diffuse", type=float, default=0.3)
    p.add_argument("--tint", type=float, nargs=2, default=[1.2, 0.6])
    p.add_argument("--eta", type=float, default=1.5)
    a = p.parse_args()
    mu, coeffs = table(a.n, a.order, a.roughness, a.diffuse, a.tint)
    write(a.out, mu, coeffs, a.order, a.eta)


if __name__ == "__main__":
    main()
