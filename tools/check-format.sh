#!/usr/bin/env bash
# Checks that every C++ source under src/ and tests/ is formatted as .clang-format says
# (clang-format 14, Debian 12's). With --fix, reformats them in place instead.
set -euo pipefail
cd "$(dirname "$0")/.."
CLANG_FORMAT="${CLANG_FORMAT:-clang-format}"
mapfile -t files < <(git ls-files 'src/*.h' 'src/*.cpp' 'src/*.inc' 'tests/*.h' 'tests/*.cpp')
if [ "${1:-}" = "--fix" ]; then
    "$CLANG_FORMAT" -i "${files[@]}"
    echo "formatted ${#files[@]} files"
    exit 0
fi
bad=()
for f in "${files[@]}"; do
    if ! "$CLANG_FORMAT" --dry-run -Werror "$f" >/dev/null 2>&1; then bad+=("$f"); fi
done
if [ "${#bad[@]}" -gt 0 ]; then
    echo "error: ${#bad[@]} of ${#files[@]} files differ from .clang-format (run tools/check-format.sh --fix):" >&2
    printf '  %s\n' "${bad[@]}" >&2
    exit 1
fi
echo "format: ${#files[@]} files match .clang-format"
