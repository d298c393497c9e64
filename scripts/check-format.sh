#!/usr/bin/env bash
# Checks that the C++ lines changed since BASE (default: main's merge base with HEAD) follow .clang-format.
# Only changed lines are checked, so old code is reformatted when it is touched, not all at once.
#   scripts/check-format.sh [BASE]     exit 0: formatted; 1: the diff clang-format would apply is printed
#   scripts/check-format.sh --fix [BASE]   apply it to the working tree instead
set -euo pipefail
cd "$(dirname "$0")/.."
fix=0
if [[ "${1:-}" == "--fix" ]]; then fix=1; shift; fi
base=${1:-$(git merge-base HEAD main 2>/dev/null || echo HEAD~1)}
command -v clang-format >/dev/null || { echo "check-format: clang-format is not installed (apt-get install clang-format)" >&2; exit 1; }
if (( fix )); then
  git clang-format --extensions cpp,h,hpp "$base"
  exit 0
fi
out=$(git clang-format --diff --extensions cpp,h,hpp "$base" 2>&1 || true)
if [[ -z "$out" || "$out" == *"no modified files to format"* || "$out" == *"did not modify any files"* ]]; then
  echo "check-format: the C++ lines changed since $base follow .clang-format"
  exit 0
fi
echo "$out"
echo "check-format: the lines above differ from .clang-format; run scripts/check-format.sh --fix $base" >&2
exit 1
