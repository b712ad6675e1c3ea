#!/usr/bin/env bash
# Configures and builds Prism (Release) into build/ (or $PRISM_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${PRISM_BUILD_DIR:-build}"
GEN=""
if command -v ninja >/dev/null 2>&1; then GEN="-G Ninja"; fi
cmake -S . -B "$BUILD_DIR" $GEN -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$BUILD_DIR" -j "$(nproc)"
