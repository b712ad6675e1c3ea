#!/usr/bin/env python3
"""The cost of each effect and the speed-up of the specialized kernel (docs/EFFECTS.md).

1. Speed-up: each scene rendered with the kernel specialized for its effect set and with
   `--effects all` (the general kernel), interleaved (spec, all, all, spec, ...).
2. Cost of each effect: scenes/diffuse.pbrt (Lambertian spheres, two point lights) against a
   copy with one effect added (a mirror sphere, a glass sphere, a rough metal sphere, ...),
   interleaved with the base.

Every render is run REPEATS times in one session and the medians of prism's own "render"
time (no parse, BVH build or image writing) are reported, with their ratios: the machine is
shared and noisy, so only numbers from one run of this script are compared with each other.

Usage: bench/effects.py [--repeats N] [--threads T] [--spp S] [--prism PATH] [--shared DIR]
Prints a Markdown table (the one in docs/EFFECTS.md).
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def render(prism, scene, args, threads):
    cmd = [prism, "render", scene, "-o", os.path.join(TMP, "out.exr"), "--no-progress",
           "--threads", str(threads)] + args
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("bench/effects.py: failed: %s\n%s" % (" ".join(cmd), r.stderr))
    t = float(re.search(r"render ([0-9.]+)s", r.stderr).group(1))
    kernel = re.search(r"kernel: (.*)", r.stderr).group(1)
    rays = re.search(r"rays: (.*);", r.stderr).group(1)
    # The kinds of ray traced, in millions: "camera 1.2, shadow 1.7, glossy 0.4".
    rays = ", ".join("%s %.2f" % (k, int(n) / 1e6)
                     for k, n in re.findall(r"([a-z-]+) ([0-9]+)", rays) if int(n) > 0)
    return t, kernel, rays


def variants(base):
    """(name, scene text, extra args) for each effect added to scenes/diffuse.pbrt."""
    red = 'Material "matte" "rgb Kd" [ 0.7 0.2 0.15 ]'
    green = 'Material "matte" "rgb Kd" [ 0.3 0.7 0.3 ]'
    blue = 'Material "matte" "rgb Kd" [ 0.2 0.5 0.7 ]'
    floor = 'Material "matte" "rgb Kd" [ 0.6 0.6 0.55 ]'
    light1 = 'LightSource "point" "point3 from" [ -5 9 -6 ] "rgb I" [ 160 160 160 ]'
    camera = 'Camera "perspective" "float fov" [ 40 ]'
    green_sphere = ('Translate 2.5 1.2 1.5\n  Shape "sphere" "float radius" [ 1.2 ]')
    for old in (red, green, blue, floor, light1, camera, green_sphere):
        assert old in base, old
    dist = ["--integrator", "distribution"]
    return [
        ("specular reflection (a mirror sphere)", base.replace(red, 'Material "mirror"'), []),
        ("refraction (a glass sphere)", base.replace(green, 'Material "glass"'), []),
        ("glossy reflection (rough metal, distribution, 8 glossy samples)",
         base.replace(red, 'Material "metal" "float roughness" [ 0.05 ]'), dist),
        ("glossy transmission (rough glass, distribution, 8 glossy samples)",
         base.replace(green, 'Material "glass" "float roughness" [ 0.05 ]'), dist),
        ("textures (checkerboard floor)",
         base.replace(floor, 'Texture "c" "spectrum" "checkerboard" "float uscale" [ 4 ] '
                      '"float vscale" [ 4 ] "rgb tex1" [ 0.7 0.7 0.6 ] "rgb tex2" [ 0.5 0.5 0.45 ]\n'
                      '  Material "matte" "texture Kd" "c"'), []),
        ("BSDF generality (one Oren-Nayar sphere)",
         base.replace(blue, blue + ' "float sigma" [ 20 ]'), []),
        ("soft shadows (a sphere light, 4 samples, for one point light)",
         base.replace(light1, 'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 50 50 50 ] '
                      '"integer nsamples" [ 4 ]\nTranslate -5 9 -6\nShape "sphere" "float radius" '
                      '[ 0.5 ]\nAttributeEnd'), []),
        ("environment (an infinite light, 4 samples)",
         base.replace(light1, light1 + '\nLightSource "infinite" "rgb L" [ 0.1 0.15 0.3 ] '
                      '"integer nsamples" [ 4 ]'), []),
        ("depth of field (lens radius 0.1)",
         base.replace(camera, camera + ' "float lensradius" [ 0.1 ] "float focaldistance" [ 9 ]'),
         []),
        ("CSG (the green sphere as a union of two spheres)",
         base.replace(green_sphere, 'Translate 2.5 1.2 1.5\n  CSGBegin "union"\n'
                      '  Shape "sphere" "float radius" [ 1.2 ]\n  AttributeBegin Translate 0.5 0 0 '
                      'Shape "sphere" "float radius" [ 1 ] AttributeEnd\n  CSGEnd'), []),
        ("motion blur (the green sphere moves 0.5 while the shutter is open)",
         base.replace(green_sphere, 'Translate 2.5 1.2 1.5\n  ActiveTransform EndTime\n'
                      '  Translate 0.5 0 0\n  ActiveTransform All\n'
                      '  Shape "sphere" "float radius" [ 1.2 ]'), []),
        ("instancing (the green sphere as an ObjectInstance)",
         base.replace(green_sphere, 'ObjectBegin "ball"\n  Shape "sphere" "float radius" [ 1.2 ]\n'
                      '  ObjectEnd\n  Translate 2.5 1.2 1.5\n  ObjectInstance "ball"'), []),
    ]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--spp", type=int, default=16, help="for the scenes of this repository")
    ap.add_argument("--prism", default=os.path.join(ROOT, "build", "prism"))
    ap.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"))
    a = ap.parse_args()

    diffuse = os.path.join(ROOT, "scenes", "diffuse.pbrt")
    speedups = [
        ("scenes/diffuse.pbrt", diffuse, ["--spp", str(a.spp)]),
        ("scenes/whitted.pbrt", os.path.join(ROOT, "scenes", "whitted.pbrt"),
         ["--spp", str(a.spp)]),
    ]
    cornell = os.path.join(a.shared, "scenes", "pbrt-cornell-box-bitterli", "scene.pbrt")
    if os.path.exists(cornell):
        # The scene asks for path; its Whitted render runs the kernel (light samples).
        speedups.append(("pbrt-cornell-box-bitterli (whitted, 512x512, 16 spp)", cornell,
                         ["--integrator", "whitted", "--res", "512x512", "--spp", "16"]))

    base = open(diffuse).read()
    costs = []
    for i, (name, text, args) in enumerate(variants(base)):
        path = os.path.join(TMP, "effect%d.pbrt" % i)
        open(path, "w").write(text)
        costs.append((name, path, args + ["--spp", str(a.spp)]))
    base_args = ["--spp", str(a.spp)]

    times = {}
    info = {}

    def run(key, scene, args):
        t, kernel, rays = render(a.prism, scene, args, a.threads)
        times.setdefault(key, []).append(t)
        info[key] = (kernel, rays)

    for r in range(a.repeats):
        for name, scene, args in speedups:
            order = [False, True] if r % 2 == 0 else [True, False]
            for general in order:
                run((name, general), scene, args + (["--effects", "all"] if general else []))
        for name, scene, args in costs:
            run(("base", False), diffuse, base_args)
            run((name, False), scene, args)
        print("repeat %d/%d done" % (r + 1, a.repeats), file=sys.stderr)

    med = {k: statistics.median(v) for k, v in times.items()}
    print("Specialized kernel against `--effects all` (median render seconds of %d runs, "
          "%d threads):\n" % (a.repeats, a.threads))
    print("| scene | kernel | specialized (s) | --effects all (s) | speed-up |")
    print("|---|---|---:|---:|---:|")
    for name, _, _ in speedups:
        s, g = med[(name, False)], med[(name, True)]
        print("| %s | %s | %.3f | %.3f | %.2fx |" % (name, info[(name, False)][0], s, g, g / s))
    b = med[("base", False)]
    print("\nCost of each effect: scenes/diffuse.pbrt (%d spp, %.3f s, kernel %s) with one "
          "effect added (median render seconds of %d runs):\n" %
          (a.spp, b, info[("base", False)][0], a.repeats))
    print("| effect added | kernel | render (s) | × diffuse | rays (millions) |")
    print("|---|---|---:|---:|---|")
    for name, _, _ in costs:
        t = med[(name, False)]
        print("| %s | %s | %.3f | %.2f | %s |" % (name, info[(name, False)][0], t, t / b,
                                                  info[(name, False)][1]))


if __name__ == "__main__":
    with tempfile.TemporaryDirectory(prefix="prism_effects_bench_") as TMP:
        main()
