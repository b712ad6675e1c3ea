#!/usr/bin/env bash
# Error against samples per pixel of Prism's path integrator on the shared Cornell box
# (../shared/pbrt3-reference/cornell-path.pbrt) for each sampler Prism draws (`--sampler`:
# stratified, pbrt-v3's 02sequence, pbrt-v4's paddedsobol and zsobol, halton, random). Prism renders at
# 64x64 (its box filter averages each pixel's area); the reference is pbrt-v3's own 1024-spp
# 256x256 render box-filtered down by 4 (16384 samples per 64x64 pixel), so its own noise is
# well below the errors measured. Prints a Markdown table of the relative L1 error
# (mean |a - b| / mean |b|) and one of the RMSE.
# Usage: tools/path_convergence.sh [SPP...]   (default: 4 16 64 256 1024)
#        SAMPLERS="zsobol stratified" SCENE=cornell-direct tools/path_convergence.sh 16 64
set -euo pipefail
cd "$(dirname "$0")/.."
PRISM="${PRISM:-$PWD/build/prism}"
REF="${SHARED:-$PWD/../shared}/pbrt3-reference"
SPPS="${*:-4 16 64 256 1024}"
SCENE="${SCENE:-cornell-path}"
SAMPLERS="${SAMPLERS:-stratified 02sequence paddedsobol zsobol halton random}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
oiiotool "$REF/$SCENE.exr" --resize:filter=box 64x64 -d float -o "$WORK/ref.exr"
avg3() {
    sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p' |
        awk '{printf "%.6g", ($1+$2+$3)/3}'
}
meanb=$(oiiotool "$WORK/ref.exr" --printstats 2>&1 | avg3)
header="| spp"
rule="|---"
for s in $SAMPLERS; do
    header="$header | $s"
    rule="$rule|---"
done
l1table="$header |
$rule|"
rmsetable="$l1table"
for spp in $SPPS; do
    l1row="| $spp"
    rmserow="| $spp"
    for s in $SAMPLERS; do
        "$PRISM" render "$REF/$SCENE.pbrt" --sampler "$s" --res 64x64 --spp "$spp" \
            -o "$WORK/$s.exr" --no-progress --quiet >/dev/null 2>&1
        l1=$(oiiotool "$WORK/$s.exr" "$WORK/ref.exr" --absdiff --printstats 2>&1 | avg3)
        l1row="$l1row | $(awk -v d="$l1" -v m="$meanb" 'BEGIN{printf "%.2f%%", 100 * d / m}')"
        rmse=$(oiiotool "$WORK/$s.exr" "$WORK/ref.exr" --diff 2>&1 |
            sed -n 's/.*RMS error = \([0-9.e+-]*\).*/\1/p' || true)
        rmserow="$rmserow | $rmse"
    done
    l1table="$l1table
$l1row |"
    rmsetable="$rmsetable
$rmserow |"
done
echo "Relative L1 error:"
echo "$l1table"
echo
echo "RMSE:"
echo "$rmsetable"
