#!/usr/bin/env bash
# Builds Prism and runs the whole test suite through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
ctest --test-dir "${PRISM_BUILD_DIR:-build}" --output-on-failure -j "$(nproc)"
