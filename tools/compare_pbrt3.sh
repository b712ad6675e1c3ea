#!/usr/bin/env bash
# Renders the scenes of ../shared/pbrt3-reference and of the project's own
# scenes/pbrt3-reference (each NAME.pbrt is the exact scene file pbrt-v3 rendered into NAME.exr
# beside it; the project's folder also holds the images and files its scenes read) with Prism
# and compares box-filtered images: both are downsampled by FACTOR (default 4) and
# compared with oiiotool --diff (RMSE, PSNR, max error) and by their relative L1 error
# (mean |a - b| / mean |b| over the RGB channels, from oiiotool --absdiff and --printstats).
# Side-by-side PNGs go to OUTDIR. ONLY="cornell-path cornell-direct" renders just those scenes.
# A scene with NAME.quarter.exr beside its reference (pbrt-v3 at a quarter of the scene's
# samples, or of its sppm iterations: e.g. bdpt-gap, sppm-caustic) is rendered by Prism at
# that quarter too, and the last column gives pbrt-v3's own quarter-vs-full relative L1: Prism
# is within pbrt-v3's noise when its rel L1 is about that.
# PBRT_VERSION=4 (tools/compare_pbrt4.sh) compares the pbrt-v4 renders of scenes/pbrt4-reference
# the same way (there is no shared pbrt-v4 folder).
# Usage: tools/compare_pbrt3.sh [OUTDIR] [FACTOR]
set -euo pipefail
cd "$(dirname "$0")/.."
V="${PBRT_VERSION:-3}"
OUT="${1:-docs/pbrt$V}"
FACTOR="${2:-4}"
PRISM="${PRISM:-$PWD/build/prism}"
SHARED_REF="${SHARED:-$PWD/../shared}/pbrt3-reference"
[ "$V" = 3 ] || SHARED_REF=""
OWN_REF="$PWD/scenes/pbrt$V-reference"
SCENES="${SHARED:-$PWD/../shared}/scenes"
mkdir -p "$OUT"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
[ -z "$SHARED_REF" ] || cp "$SHARED_REF"/*.pbrt "$WORK/"
cp -r "$OWN_REF"/. "$WORK/"
# The texture the spheres scene needs sits with the original scene.
cp -r "$SCENES/pbrt-spheres-differentials-texfilt/textures" "$WORK/"
echo "| scene | Prism render (s) | RMSE | PSNR (dB) | max abs error | mean of reference | rel L1 | pbrt-v$V at Prism's spp: rel L1 |"
echo "|---|---|---|---|---|---|---|---|"
# The mean over R, G and B of oiiotool --printstats' "Stats Avg".
avg3() {
    sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p' |
        awk '{printf "%.6g", ($1+$2+$3)/3}'
}
for f in "$WORK"/*.pbrt; do
    name="$(basename "$f" .pbrt)"
    REF="$SHARED_REF"
    [ -z "$REF" ] || [ -f "$OWN_REF/$name.pbrt" ] && REF="$OWN_REF"
    ref="$REF/$name.exr"
    [ -f "$ref" ] || continue
    if [ -n "${ONLY:-}" ] && [[ " $ONLY " != *" $name "* ]]; then continue; fi
    quarter="$REF/$name.quarter.exr"
    sppArgs=()
    if [ -f "$quarter" ]; then
        iters=$(grep -o 'numiterations" *\[\? *[0-9]*' "$f" | grep -o '[0-9]*$' || true)
        muts=$(grep -o 'mutationsperpixel" *\[\? *[0-9]*' "$f" | grep -o '[0-9]*$' || true)
        if [ -n "$muts" ]; then
            # mlt: a quarter of the mutations per pixel.
            sed -i -E "s/mutationsperpixel\" *(\[ *$muts *\]|$muts)/mutationsperpixel\" [$((muts / 4))]/" "$f"
        elif [ -n "$iters" ]; then
            # sppm: a quarter of the iterations (its --spp is not the iteration count).
            sed -i -E "s/numiterations\" *(\[ *$iters *\]|$iters)/numiterations\" [$((iters / 4))]/" "$f"
        else
            spp=$(grep -o 'pixelsamples" *\[\? *[0-9]*' "$f" | grep -o '[0-9]*$')
            sppArgs=(--spp $((spp / 4)))
        fi
    fi
    out=$("$PRISM" render "$f" -o "$WORK/$name.exr" --no-progress "${sppArgs[@]}" 2>&1)
    secs=$(echo "$out" | grep -o 'render [0-9.]*s' | head -1 | sed 's/render \(.*\)s/\1/')
    w=$(oiiotool --info "$ref" | sed -n 's/.* \([0-9]*\) x *\([0-9]*\),.*/\1/p')
    h=$(oiiotool --info "$ref" | sed -n 's/.* \([0-9]*\) x *\([0-9]*\),.*/\2/p')
    sw=$((w / FACTOR)); sh=$((h / FACTOR))
    oiiotool "$WORK/$name.exr" --resize:filter=box "${sw}x${sh}" -d float -o "$WORK/a.exr"
    oiiotool "$ref" --resize:filter=box "${sw}x${sh}" -d float -o "$WORK/b.exr"
    diff=$(oiiotool "$WORK/a.exr" "$WORK/b.exr" --diff 2>&1 || true)
    rmse=$(echo "$diff" | sed -n 's/.*RMS error = \([0-9.e+-]*\).*/\1/p')
    psnr=$(echo "$diff" | sed -n 's/.*Peak SNR = \([0-9.e+-]*\).*/\1/p')
    maxe=$(echo "$diff" | sed -n 's/.*Max error *= \([0-9.e+-]*\).*/\1/p')
    meanb=$(oiiotool "$WORK/b.exr" --printstats 2>&1 | avg3)
    mean=$(awk -v m="$meanb" 'BEGIN{printf "%.4f", m}')
    l1=$(oiiotool "$WORK/a.exr" --ch R,G,B "$WORK/b.exr" --ch R,G,B --absdiff --printstats 2>&1 |
        avg3)
    rel=$(awk -v d="$l1" -v m="$meanb" 'BEGIN{printf "%.2f%%", 100 * d / m}')
    own="-"
    if [ -f "$quarter" ]; then
        oiiotool "$quarter" --resize:filter=box "${sw}x${sh}" -d float -o "$WORK/q.exr"
        ql1=$(oiiotool "$WORK/q.exr" --ch R,G,B "$WORK/b.exr" --ch R,G,B --absdiff --printstats \
            2>&1 | avg3)
        own=$(awk -v d="$ql1" -v m="$meanb" 'BEGIN{printf "%.2f%%", 100 * d / m}')
    fi
    echo "| $name | $secs | $rmse | $psnr | $maxe | $mean | $rel | $own |"
    oiiotool "$WORK/$name.exr" --colorconvert linear sRGB -d uint8 -o "$WORK/p.png"
    oiiotool "$ref" --colorconvert linear sRGB -d uint8 -o "$WORK/r.png"
    oiiotool "$WORK/p.png" "$WORK/r.png" --mosaic 2x1 --resize 50% -o "$OUT/$name-prism-vs-pbrt$V.png"
done
