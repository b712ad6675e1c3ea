#!/usr/bin/env bash
# An AOV contact sheet (docs/USAGE.md "AOVs"): renders SCENE with `prism render --aov all` and tiles
# the beauty and each layer, mapped to display values and labelled, into one PNG with oiiotool.
# Usage: tools/aov_contact_sheet.sh [SCENE] [OUT.png] [RES]
set -euo pipefail
cd "$(dirname "$0")/.."
SCENE="${1:-scenes/whitted.pbrt}"
OUT="${2:-docs/aov-contact-sheet.png}"
RES="${3:-320x240}"
FONT="${FONT:-/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf}"
PRISM="${PRISM:-$PWD/build/prism}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
"$PRISM" render "$SCENE" -o "$WORK/aov.exr" --aov all --res "$RES" -q
A="$WORK/aov.exr"
tile() {  # NAME OIIOTOOL-ARGS...: one labelled tile, channels mapped to [0,1]
    local name="$1"
    shift
    oiiotool "$A" "$@" --clamp:min=0,0,0:max=1,1,1 \
        --text:x=6:y=20:size=16:color=1,1,0:font="$FONT" "$name" -d uint8 -o "$WORK/tile-$name.png"
}
tile beauty --ch R,G,B
tile "depth Z" --ch Z,Z,Z --clamp:min=0,0,0:max=30,30,30 --mulc 0.0333 --subc 1 --abs
tile "P" --ch P.X,P.Y,P.Z --mulc 0.05 --addc 0.5
tile "N" --ch N.X,N.Y,N.Z --mulc 0.5 --addc 0.5
tile "Ng" --ch Ng.X,Ng.Y,Ng.Z --mulc 0.5 --addc 0.5
tile albedo --ch albedo.R,albedo.G,albedo.B
tile uv --ch uv.U,uv.V,=0
tile shape_id --ch shape_id,shape_id,shape_id --mulc 0.2
tile material_id --ch material_id,material_id,material_id --mulc 0.2
tile direct --ch direct.R,direct.G,direct.B
tile indirect --ch indirect.R,indirect.G,indirect.B
tile variance --ch variance.R,variance.G,variance.B --mulc 10
oiiotool "$WORK/tile-beauty.png" "$WORK/tile-depth Z.png" "$WORK/tile-P.png" "$WORK/tile-N.png" \
    "$WORK/tile-Ng.png" "$WORK/tile-albedo.png" "$WORK/tile-uv.png" "$WORK/tile-shape_id.png" \
    "$WORK/tile-material_id.png" "$WORK/tile-direct.png" "$WORK/tile-indirect.png" \
    "$WORK/tile-variance.png" --mosaic:pad=4 4x3 -d uint8 -o "$OUT"
echo "$OUT"
