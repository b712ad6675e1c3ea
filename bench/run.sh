#!/usr/bin/env bash
# Prism benchmarks: scene load + BVH build times, and render time against POV-Ray 3.7 on the
# shared Whitted and knot scenes (same resolution, one sample per pixel, 2 threads).
# Runs are interleaved (Prism, POV-Ray, Prism, ...) and medians reported, so that the ratio
# comes from one session on a shared, noisy machine.
# Usage: bench/run.sh [RUNS]   (needs: build/prism, povray, python3 for gen_knot.py)
#        bench/run.sh --paths     (prints the prism binary and shared folder it would use)
# Paths resolve from the repository root (the folder above this script), whatever the current
# directory: the shared data is the folder `shared` beside the clone ($SHARED overrides it).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
cd "$ROOT"
PRISM="${PRISM:-$ROOT/build/prism}"
SHARED="${SHARED:-$ROOT/../shared}"
if [ ! -d "$SHARED/peers" ]; then
    echo "bench/run.sh: no peers folder in $SHARED (clone the repository beside shared/, or set SHARED)" >&2
    exit 2
fi
SHARED="$(cd "$SHARED" && pwd -P)"
if [ "${1:-}" = "--paths" ]; then
    echo "prism: $PRISM"
    echo "shared: $SHARED"
    exit 0
fi
RUNS="${1:-5}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
# Seconds of the given phase ("parse", "BVH build", "render") from prism's statistics line.
phase() { grep -o "$1 [0-9.]*s" | head -1 | sed 's/.* \([0-9.]*\)s/\1/'; }
wall() { local s e; s=$(date +%s.%N); "$@" >/dev/null 2>&1; e=$(date +%s.%N); awk "BEGIN {print $e - $s}"; }

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(date -u +%Y-%m-%d)"
echo

echo "## Load and BVH build (median of $RUNS)"
cp "$SHARED/peers/gen_knot.py" "$WORK/"
python3 "$WORK/gen_knot.py" 5000 100 >/dev/null   # 1,000,002 triangles: knot.ply/.obj/.pbrt
load_bench() {
    local name="$1" scene="$2" p=() b=()
    for _ in $(seq "$RUNS"); do
        out=$("$PRISM" render "$scene" -o "$WORK/x.png" --res 32x24 --spp 1 --no-progress 2>&1)
        p+=("$(awk "BEGIN {print $(echo "$out" | phase parse) + $(echo "$out" | phase setup)}")"); b+=("$(echo "$out" | phase 'BVH build')")
    done
    printf "| %s | %s | %s |\n" "$name" "$(printf '%s\n' "${p[@]}" | median)" "$(printf '%s\n' "${b[@]}" | median)"
}
echo "| scene | load: parse + setup (s) | BVH build (s) |"
echo "|---|---|---|"
load_bench "2CylinderEngine.glb (121,496 triangles)" "$SHARED/scenes/gltf-2cylinderengine/2CylinderEngine.glb"
load_bench "knot.pbrt + binary PLY (1,000,002 triangles)" "$WORK/knot.pbrt"
load_bench "knot.obj (1,000,002 triangles)" "$WORK/knot.obj"
echo

if command -v povray >/dev/null; then
    echo "## Render time against POV-Ray 3.7 (wall seconds, 800x600, 1 spp, 2 threads; median of $RUNS)"
    echo "| scene | Prism | POV-Ray | POV-Ray / Prism |"
    echo "|---|---|---|---|"
    cp "$SHARED/peers/whitted.pov" "$SHARED/peers/whitted.pbrt" "$WORK/"
    pov_bench() {
        local name="$1" pbrt="$2" pov="$3" a=() b=()
        for _ in $(seq "$RUNS"); do
            a+=("$(wall "$PRISM" render "$pbrt" -o "$WORK/p.png" --res 800x600 --spp 1 --threads 2 --quiet)")
            b+=("$(cd "$WORK" && wall povray +I"$pov" +O"$WORK/v.png" +W800 +H600 -D +FN -A +WT2)")
        done
        local ma mb
        ma=$(printf '%s\n' "${a[@]}" | median); mb=$(printf '%s\n' "${b[@]}" | median)
        printf "| %s | %.3f | %.3f | %.2f |\n" "$name" "$ma" "$mb" "$(awk "BEGIN {print $mb / $ma}")"
    }
    pov_bench "peers/whitted (quadrics, mirror, glass; maxdepth 5)" "$WORK/whitted.pbrt" "$WORK/whitted.pov"
    pov_bench "knot (1,000,002 triangles)" "$WORK/knot.pbrt" "$WORK/knot.pov"
fi

echo
echo "## What accuracy costs: analytic intersectors in float vs double (render seconds, 1 thread; median of $RUNS)"
echo "| scene | float | double | double / float |"
echo "|---|---|---|---|"
prec_bench() {
    local name="$1" scene="$2" f=() d=()
    for _ in $(seq "$RUNS"); do
        f+=("$("$PRISM" render "$scene" -o "$WORK/f.png" --res 400x250 --spp 4 --threads 1 --precision float --no-progress 2>&1 | phase render)")
        d+=("$("$PRISM" render "$scene" -o "$WORK/d.png" --res 400x250 --spp 4 --threads 1 --precision double --no-progress 2>&1 | phase render)")
    done
    local mf md
    mf=$(printf '%s\n' "${f[@]}" | median); md=$(printf '%s\n' "${d[@]}" | median)
    printf "| %s | %.3f | %.3f | %.3f |\n" "$name" "$mf" "$md" "$(awk "BEGIN {print $md / $mf}")"
}
prec_bench "scenes/quadrics.pbrt (12 analytic shapes)" scenes/quadrics.pbrt
prec_bench "scenes/whitted.pbrt" scenes/whitted.pbrt
