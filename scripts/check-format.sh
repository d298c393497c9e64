#!/usr/bin/env bash
# The C++ layout of .clang-format, checked two ways:
#   scripts/check-format.sh --listed        every file named in scripts/format-checked.txt is formatted
#                                           (CTest's style.format runs this: no git needed, so a clean
#                                           clone or a source tarball checks the same files)
#   scripts/check-format.sh --list-clean    prints the C++ files of libs/ and apps/ that are formatted
#                                           (to grow the list: append them to scripts/format-checked.txt)
#   scripts/check-format.sh [BASE]          the lines changed since BASE (default: main's merge base with
#                                           HEAD) are formatted, for a local check before a commit
#   scripts/check-format.sh --fix [BASE]    formats the lines changed since BASE in the working tree
# Exit 0: formatted; 1: what clang-format would change is printed.
# The list grows rather than the tree being reformatted at once: a file joins it when it is formatted
# (a new file, or an old one whose module is reformatted in its own commit), and stays formatted.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "check-format: clang-format is not installed (apt-get install clang-format)" >&2; exit 1; }
list=scripts/format-checked.txt

if [[ "${1:-}" == "--listed" ]]; then
  mapfile -t files < <(grep -v '^\s*#' "$list" | grep -v '^\s*$')
  bad=0
  for f in "${files[@]}"; do
    if [[ ! -f "$f" ]]; then echo "check-format: $list names $f, which is not there (remove the line)" >&2; bad=1; continue; fi
    if ! out=$(clang-format --style=file "$f" | diff -u --label "$f" --label "$f (clang-format)" "$f" -); then
      echo "$out"
      bad=1
    fi
  done
  if (( bad )); then
    echo "check-format: the files above differ from .clang-format; run clang-format -i on them" >&2
    exit 1
  fi
  echo "check-format: the ${#files[@]} files of $list follow .clang-format"
  exit 0
fi

if [[ "${1:-}" == "--list-clean" ]]; then
  git ls-files 'libs/*.cpp' 'libs/*.h' 'apps/*.cpp' 'apps/*.h' | while read -r f; do
    clang-format --style=file "$f" | cmp -s - "$f" && echo "$f"
  done
  exit 0
fi

fix=0
if [[ "${1:-}" == "--fix" ]]; then fix=1; shift; fi
base=${1:-$(git merge-base HEAD main 2>/dev/null || echo HEAD~1)}
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
