#!/usr/bin/env bash
# Renders each scene of scenes/pbrt4-reference (NAME.pbrt is the exact pbrt-v4 file that
# ../shared/tools/pbrt-v4/pbrt rendered into NAME.exr, and into NAME.quarter.exr at a quarter of
# its samples) with Prism and compares the box-filtered images as tools/compare_pbrt3.sh does:
# Prism is within pbrt-v4's own noise when its rel L1 is about the last column's.
# Usage: tools/compare_pbrt4.sh [OUTDIR] [FACTOR]   (default docs/pbrt4, 4)
set -euo pipefail
PBRT_VERSION=4 exec "$(dirname "$0")/compare_pbrt3.sh" "$@"
