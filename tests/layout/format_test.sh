#!/usr/bin/env bash
# Checks that every C++ and GLSL file is formatted as .clang-format says (clang-format 14, as
# Debian 12 ships it; scripts/setup.sh installs it). To fix: tests/layout/format_test.sh --fix
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
cd "$repo"
command -v clang-format >/dev/null || { echo "format: clang-format not found (scripts/setup.sh installs it)"; exit 1; }
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files -- 'src/*.h' 'src/*.cpp' 'tests/*.h' 'tests/*.cpp' 'bench/*.cpp' 'tools/*.cpp' \
    'shaders/*.h' 'shaders/*.glsl' 'shaders/*.comp')
else
  mapfile -t files < <(find src tests bench shaders tools -type f \( -name '*.h' -o -name '*.cpp' -o -name '*.glsl' -o -name '*.comp' \) | sort)
fi
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  echo "format: formatted ${#files[@]} files"
  exit 0
fi
bad=0
for f in "${files[@]}"; do
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "format: $f differs from .clang-format (tests/layout/format_test.sh --fix)"
    bad=$((bad + 1))
  fi
done
if [ $bad -gt 0 ]; then echo "1 failed: $bad of ${#files[@]} files not formatted"; exit 1; fi
echo "1 passed: ${#files[@]} files formatted"
