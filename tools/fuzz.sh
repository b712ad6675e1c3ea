#!/usr/bin/env bash
# Runs each libFuzzer target for a bounded time, one after the other (one core), and prints the
# executions per target and in total. Crashing inputs are saved under
# $BUILD/fuzz-work/artifacts/<target>/; the run goes on past a crash until the time is used.
#   tools/fuzz.sh [SECONDS_PER_TARGET=60] [TARGET...]
#   (targets: pbrt ply stl obj gltf image gltf_json texture)
# Builds into $PRISM_FUZZ_BUILD_DIR (default build-fuzz) with clang++-14 and PRISM_FUZZ=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
SRC="$PWD"
SECONDS_PER_TARGET="${1:-60}"
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && TARGETS=(pbrt ply stl obj gltf image bsdf gltf_json texture)
BUILD="${PRISM_FUZZ_BUILD_DIR:-build-fuzz}"
CXX_FUZZ="${CXX_FUZZ:-clang++-14}"
CC_FUZZ="${CC_FUZZ:-clang-14}"

GEN=""
if command -v ninja >/dev/null 2>&1; then GEN="-G Ninja"; fi
CC="$CC_FUZZ" CXX="$CXX_FUZZ" cmake -S . -B "$BUILD" $GEN -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPRISM_FUZZ=ON -DPRISM_BUILD_TESTS=OFF >/dev/null
cmake --build "$BUILD" -j "${PRISM_FUZZ_JOBS:-2}" --target $(printf 'fuzz_%s ' "${TARGETS[@]}")

# Seeds: the checked-in corpus plus matching files from the shared scenes (not copied into the
# repository; the working corpus lives in the build directory and grows across runs).
# The structure-aware targets (gltf_json, texture) read generator choices, not files: no
# shared seeds.
declare -A EXTS=([pbrt]="pbrt" [ply]="ply" [stl]="stl" [obj]="obj" [gltf]="gltf glb" [image]="png jpg tga exr hdr pfm bmp" [gltf_json]="" [texture]="")
SHARED="$SRC/../shared/scenes"
WORK="$BUILD/fuzz-work"
export LSAN_OPTIONS="suppressions=$SRC/tools/lsan.supp:print_suppressions=0"
# Short allocation stacks and a smaller quarantine: ASan's bookkeeping of every malloc is most
# of the cost in these allocation-heavy readers. Reproduce a crash with the defaults.
export ASAN_OPTIONS="${ASAN_OPTIONS:-malloc_context_size=5:quarantine_size_mb=16}"
total=0
summary=""
for t in "${TARGETS[@]}"; do
  corpus="$WORK/corpus/$t"
  artifacts="$WORK/artifacts/$t"
  mkdir -p "$corpus" "$artifacts"
  cp -n "$SRC/tests/fuzz/corpus/$t/"* "$corpus/" 2>/dev/null || true
  if [ -d "$SHARED" ]; then
    for e in ${EXTS[$t]}; do
      find "$SHARED" -type f -name "*.$e" -size -256k -exec cp -n {} "$corpus/" \; 2>/dev/null || true
    done
  fi
  execs=0
  crashes=0
  start=$(date +%s)
  left=$SECONDS_PER_TARGET
  while [ "$left" -gt 0 ]; do
    log="$WORK/$t.log"
    set +e
    "$BUILD/tests/fuzz/fuzz_$t" "$corpus" -max_total_time="$left" -timeout=10 -rss_limit_mb=2560 \
      -max_len="${PRISM_FUZZ_MAX_LEN:-8192}" -print_final_stats=1 -close_fd_mask=1 -artifact_prefix="$artifacts/" \
      >"$log" 2>&1
    rc=$?
    set -e
    n=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
    if [ -z "$n" ]; then
      # A crash ends the run before the final statistics; take the last progress line.
      n=$(grep -o '^#[0-9]*' "$log" | tr -d '#' | tail -1)
    fi
    execs=$((execs + ${n:-0}))
    if [ $rc -ne 0 ]; then
      crashes=$((crashes + 1))
      echo "fuzz_$t: crash (exit $rc), see $log and $artifacts/" >&2
      grep -m3 -E 'ERROR|SUMMARY|Test unit written' "$log" >&2 || true
      [ $crashes -ge 20 ] && break
    fi
    left=$((SECONDS_PER_TARGET - ($(date +%s) - start)))
  done
  echo "fuzz_$t: $execs executions in $SECONDS_PER_TARGET s, $crashes crash(es)"
  summary+="$t $execs $crashes"$'\n'
  total=$((total + execs))
done
echo "total: $total executions"
printf '%s' "$summary" > "$WORK/last-summary.txt"
