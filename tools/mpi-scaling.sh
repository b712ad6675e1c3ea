#!/usr/bin/env bash
# Measures prism-mpi against prism render on this machine (docs/DISTRIBUTED.md): ROUNDS rounds,
# each running every configuration once (interleaved, so load changes hit them alike), and
# prints the medians of each one's render phase, wall time and CPU time (user + system of every
# process: on a shared machine the wall time depends on what else runs, the CPU time less).
# Needs /usr/bin/time. Usage:
#   tools/mpi-scaling.sh [SCENE] [ROUNDS] [prism render options...]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${PRISM_BUILD_DIR:-build}"
SCENE="${1:-scenes/quadrics.pbrt}"
ROUNDS="${2:-5}"
shift 2 || true
OPTS=("$@")
[ ${#OPTS[@]} -eq 0 ] && OPTS=(--res 400x240 --spp 16)
MPIRUN=(mpirun --oversubscribe --bind-to none)
[ "$(id -u)" -eq 0 ] && MPIRUN+=(--allow-run-as-root)
export OMPI_MCA_btl_tcp_if_include=lo OMPI_MCA_oob_tcp_if_include=lo
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
declare -A CONFIGS=(
  ["1 process x 2 threads (prism render)"]="$BUILD/prism render"
  ["1 rendering rank x 2 threads (-np 2)"]="${MPIRUN[*]} -np 2 $BUILD/prism-mpi render"
  ["2 rendering ranks x 1 thread (-np 3)"]="${MPIRUN[*]} -np 3 $BUILD/prism-mpi render"
  ["1 process x 1 thread (prism render)"]="$BUILD/prism render"
)
declare -A THREADS=(
  ["1 process x 2 threads (prism render)"]=2
  ["1 rendering rank x 2 threads (-np 2)"]=2
  ["2 rendering ranks x 1 thread (-np 3)"]=1
  ["1 process x 1 thread (prism render)"]=1
)
for ((r = 0; r < ROUNDS; r++)); do
  for name in "${!CONFIGS[@]}"; do
    key="$(echo "$name" | tr -c 'a-z0-9' _)"
    /usr/bin/time -f "%e %U %S" -o "$TMP/time" ${CONFIGS[$name]} "$SCENE" -o "$TMP/out.exr" \
      --no-progress --threads "${THREADS[$name]}" "${OPTS[@]}" 2>"$TMP/err"
    render=$(sed -n 's/.*render \([0-9.]*\)s$/\1/p' "$TMP/err" | head -1)
    echo "$render $(awk '{ printf "%.3f %.3f", $1, $2 + $3 }' "$TMP/time")" >>"$TMP/$key"
  done
done
printf '%-40s %12s %12s %12s\n' configuration "render (s)" "wall (s)" "CPU (s)"
for name in "${!CONFIGS[@]}"; do
  key="$(echo "$name" | tr -c 'a-z0-9' _)"
  med() { sort -n | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
  printf '%-40s %12s %12s %12s\n' "$name" "$(cut -d' ' -f1 "$TMP/$key" | med)" \
    "$(cut -d' ' -f2 "$TMP/$key" | med)" "$(cut -d' ' -f3 "$TMP/$key" | med)"
done
