#!/usr/bin/env bash
# Error against samples per pixel of Prism's path integrator on the shared Cornell box
# (../shared/pbrt3-reference/cornell-path.pbrt), for the sampler that stands in for pbrt's
# "sobol" (per-dimension correlated multi-jittered patterns), for "02sequence" (pbrt-v3's own
# ZeroTwoSequenceSampler algorithm) and for "random" (independent samples). Prism renders at 64x64 (its box filter averages each pixel's area); the reference
# is pbrt-v3's own 1024-spp 256x256 render box-filtered down by 4 (16384 samples per 64x64
# pixel), so its own noise is well below the errors measured. Prints a Markdown table of the
# relative L1 error (mean |a - b| / mean |b|) and the RMSE.
# Usage: tools/path_convergence.sh [SPP...]   (default: 4 16 64 256 1024)
set -euo pipefail
cd "$(dirname "$0")/.."
PRISM="${PRISM:-$PWD/build/prism}"
REF="${SHARED:-$PWD/../shared}/pbrt3-reference"
SPPS="${*:-4 16 64 256 1024}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
oiiotool "$REF/cornell-path.exr" --resize:filter=box 64x64 -d float -o "$WORK/ref.exr"
avg3() {
    sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p' |
        awk '{printf "%.6g", ($1+$2+$3)/3}'
}
meanb=$(oiiotool "$WORK/ref.exr" --printstats 2>&1 | avg3)
sed 's/^Sampler .*/Sampler "sobol" "integer pixelsamples" [16]/' "$REF/cornell-path.pbrt" \
    >"$WORK/sobol.pbrt"
sed 's/^Sampler .*/Sampler "random" "integer pixelsamples" [16]/' "$REF/cornell-path.pbrt" \
    >"$WORK/random.pbrt"
sed 's/^Sampler .*/Sampler "02sequence" "integer pixelsamples" [16]/' "$REF/cornell-path.pbrt" \
    >"$WORK/02sequence.pbrt"
echo "| spp | rel L1: sobol (stand-in) | 02sequence | random | RMSE: sobol (stand-in) | 02sequence | random |"
echo "|---|---|---|---|---|---|---|"
for spp in $SPPS; do
    row="| $spp"
    rmses=""
    for s in sobol 02sequence random; do
        "$PRISM" render "$WORK/$s.pbrt" --res 64x64 --spp "$spp" -o "$WORK/$s.exr" \
            --no-progress --quiet >/dev/null 2>&1
        l1=$(oiiotool "$WORK/$s.exr" "$WORK/ref.exr" --absdiff --printstats 2>&1 | avg3)
        row="$row | $(awk -v d="$l1" -v m="$meanb" 'BEGIN{printf "%.2f%%", 100 * d / m}')"
        rmse=$(oiiotool "$WORK/$s.exr" "$WORK/ref.exr" --diff 2>&1 |
            sed -n 's/.*RMS error = \([0-9.e+-]*\).*/\1/p' || true)
        rmses="$rmses | $rmse"
    done
    echo "$row$rmses |"
done
