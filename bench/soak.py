#!/usr/bin/env python3
"""Soak benchmark (issue 17): one `prism batch` run over many small scenes must keep its memory
and its time per scene flat: no leak in the batch process, no slowdown as the report grows.

The scenes (default 500) cycle through the readers a farm meets: pbrt with an Include, a
plymesh and an image texture, OBJ with an MTL and a map_Kd texture, and glTF with an external
buffer, each in its own folder and rendered under --confine. While the batch runs, the batch
process's resident memory (VmRSS) is sampled from /proc every 20 ms; report.json gives each
render's wall time and its process's peak RSS (wait4).

Writes OUT/soak.csv (one row per scene), OUT/soak_summary.txt and OUT/soak.png (needs
matplotlib; /usr/bin/python3 on Debian with python3-matplotlib).

Usage: bench/soak.py [--count 500] [--res 96] [--spp 4] [--prism build/prism] [--out docs/bench] [--jobs 1]
"""
import argparse
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time

HEAD = """LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "image" "integer xresolution" {res} "integer yresolution" {res}
Sampler "random" "integer pixelsamples" 1
WorldBegin
LightSource "point" "rgb I" [20 20 20] "point from" [1 2 5]
"""

PLY = ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
       "-1 -1 0\n1 -1 0\n0 1 0\n3 0 1 2\n")


def tiny_png(path, shade):
    """A 4x4 RGB PNG without dependencies (zlib + crc from the standard library)."""
    import zlib
    raw = b"".join(b"\x00" + bytes([shade, 255 - shade, 128] * 4) for _ in range(4))

    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 4, 4, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def write_scene(folder, i, res):
    os.makedirs(folder)
    kind = i % 4
    r = 0.3 + 0.5 * ((i * 37) % 100) / 100.0
    if kind == 0:  # pbrt: Include + image texture
        tiny_png(os.path.join(folder, "tex.png"), (i * 13) % 256)
        with open(os.path.join(folder, "part.pbrt"), "w") as f:
            f.write('Texture "t" "spectrum" "imagemap" "string filename" "tex.png"\n'
                    'Material "matte" "texture Kd" "t"\n'
                    f'Shape "sphere" "float radius" {r:.3f}\n')
        with open(os.path.join(folder, "scene.pbrt"), "w") as f:
            f.write(HEAD.format(res=res) + 'Include "part.pbrt"\n')
    elif kind == 1:  # pbrt: plymesh
        with open(os.path.join(folder, "tri.ply"), "w") as f:
            f.write(PLY)
        with open(os.path.join(folder, "scene.pbrt"), "w") as f:
            f.write(HEAD.format(res=res) + f'Scale {r:.3f} {r:.3f} 1\n'
                    'Shape "plymesh" "string filename" "tri.ply"\n')
    elif kind == 2:  # OBJ + MTL + map_Kd
        tiny_png(os.path.join(folder, "kd.png"), (i * 29) % 256)
        with open(os.path.join(folder, "m.mtl"), "w") as f:
            f.write("newmtl m\nKd 1 1 1\nmap_Kd kd.png\n")
        with open(os.path.join(folder, "scene.obj"), "w") as f:
            f.write(f"mtllib m.mtl\nv -{r} -{r} 0\nv {r} -{r} 0\nv 0 {r} 0\n"
                    "vt 0 0\nvt 1 0\nvt 0.5 1\nusemtl m\nf 1/1 2/2 3/3\n")
    else:  # glTF with an external buffer
        with open(os.path.join(folder, "b.bin"), "wb") as f:
            f.write(struct.pack("<9f", -r, -r, 0, r, -r, 0, 0, r, 0))
        gltf = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
                "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
                "buffers": [{"uri": "b.bin", "byteLength": 36}],
                "bufferViews": [{"buffer": 0, "byteLength": 36}],
                "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                               "min": [-r, -r, 0], "max": [r, r, 0]}]}
        with open(os.path.join(folder, "scene.gltf"), "w") as f:
            json.dump(gltf, f)


def rss_kib(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return None


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=500)
    ap.add_argument("--res", type=int, default=96)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--prism", default=os.path.join(root, "build", "prism"))
    ap.add_argument("--out", default=os.path.join(root, "docs", "bench"))
    ap.add_argument("--keep", action="store_true", help="keep the scratch folder")
    a = ap.parse_args()

    work = tempfile.mkdtemp(prefix="prism-soak-")
    scenes = os.path.join(work, "scenes")
    for i in range(a.count):
        write_scene(os.path.join(scenes, f"s{i:04d}"), i, a.res)
    outdir = os.path.join(work, "out")
    res = f"{a.res}x{a.res}"
    cmd = [a.prism, "batch", scenes, "-o", outdir, "--jobs", str(a.jobs), "--res", res,
           "--spp", str(a.spp), "--confine", "-q"]
    t0 = time.monotonic()
    proc = subprocess.Popen(cmd)
    samples = []  # (seconds since start, batch VmRSS KiB)

    def sample():
        while proc.poll() is None:
            v = rss_kib(proc.pid)
            if v is not None:
                samples.append((time.monotonic() - t0, v))
            time.sleep(0.02)
    th = threading.Thread(target=sample)
    th.start()
    rc = proc.wait()
    th.join()
    wall = time.monotonic() - t0
    with open(os.path.join(outdir, "report.json")) as f:
        report = json.load(f)
    jobs = report["scenes"]
    bad = [j for j in jobs if j["status"] != "ok"]
    if rc != 0 or bad:
        print(f"soak: batch exit {rc}; {len(bad)} scenes not ok, e.g. {bad[:1]}", file=sys.stderr)
        sys.exit(1)

    # Each scene's end time (jobs 1: one after another) and the batch's RSS at that moment.
    os.makedirs(a.out, exist_ok=True)
    rows = []
    # jobs 1: the scenes finish one after another; a scene's interval is the time from the
    # previous scene's end to its own (launch, render, reap, report rewrite: the batch's own
    # overhead included), and the batch's RSS is taken at its end.
    jobs.sort(key=lambda j: j["end_seconds"])
    k = 0
    last_rss = samples[0][1] if samples else 0
    prev_end = 0.0
    for i, j in enumerate(jobs):
        end = j["end_seconds"]
        while k < len(samples) and samples[k][0] <= end:
            last_rss = samples[k][1]
            k += 1
        rows.append((i, j["scene"][len(scenes) + 1:], end - prev_end, j["seconds"],
                     j.get("phases", {}).get("render", -1), j.get("peak_rss_kib", -1), last_rss))
        prev_end = end
    with open(os.path.join(a.out, "soak.csv"), "w") as f:
        f.write("index,scene,interval_seconds,process_seconds,render_seconds,"
                "render_peak_rss_kib,batch_rss_kib\n")
        for r in rows:
            f.write("%d,%s,%.4f,%.4f,%.4f,%d,%d\n" % r)

    def mean(v):
        return sum(v) / len(v)

    def slope(xs, ys):  # least squares, per scene
        mx, my = mean(xs), mean(ys)
        return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    n = len(rows)
    w = max(1, n // 10)
    secs = [r[2] for r in rows]
    child = [r[5] for r in rows]
    batch = [s[1] for s in samples]
    idx = [r[0] for r in rows]
    lines = [
        f"prism batch soak: {n} scenes ({a.res}x{a.res}, {a.spp} spp, --confine, --jobs {a.jobs}), "
        f"wall {wall:.1f} s, {n / wall:.1f} scenes/s",
        f"time per scene (end to end, the batch's overhead included): first {w} mean {mean(secs[:w]):.3f} s, last {w} mean "
        f"{mean(secs[-w:]):.3f} s; fitted slope {slope(idx, secs) * 100 * 1000:+.2f} ms per 100 "
        f"scenes; median {sorted(secs)[n // 2]:.3f} s, max {max(secs):.3f} s",
        f"render process peak RSS: first {w} mean {mean(child[:w]) / 1024:.1f} MiB, last {w} mean "
        f"{mean(child[-w:]) / 1024:.1f} MiB, max {max(child) / 1024:.1f} MiB",
        f"batch process RSS: at the first scene's end {rows[0][6] / 1024:.1f} MiB, at the last "
        f"{rows[-1][6] / 1024:.1f} MiB, peak {max(batch) / 1024:.1f} MiB "
        f"({len(samples)} samples); fitted slope "
        f"{slope(idx, [r[6] for r in rows]) * 100:+.1f} KiB per 100 scenes",
    ]
    with open(os.path.join(a.out, "soak_summary.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("soak: no matplotlib; skipped the plot (try /usr/bin/python3)", file=sys.stderr)
    else:
        fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
        ax1.plot(idx, secs, ".", ms=3, label="interval between scene ends")
        ax1.plot(idx, [r[3] for r in rows], ".", ms=3, label="render process wall time")
        ax1.plot(idx, [max(0, r[4]) for r in rows], ".", ms=3, label="its render phase")
        ax1.set_ylabel("seconds per scene")
        ax1.set_ylim(bottom=0)
        ax1.legend(loc="upper right")
        ax1.set_title(f"prism batch soak: {n} scenes in one run")
        ax2.plot(idx, [c / 1024 for c in child], ".", ms=3, label="render process peak RSS")
        ax2.plot(idx, [r[6] / 1024 for r in rows], "-", label="batch process RSS")
        ax2.set_ylabel("MiB")
        ax2.set_xlabel("scene (in render order)")
        ax2.set_ylim(bottom=0)
        ax2.legend(loc="center right")
        fig.tight_layout()
        fig.savefig(os.path.join(a.out, "soak.png"), dpi=100)
        print("wrote", os.path.join(a.out, "soak.png"))
    if a.keep:
        print("scratch:", work)
    else:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
