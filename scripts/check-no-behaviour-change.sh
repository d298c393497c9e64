#!/usr/bin/env bash
# Issue 22's acceptance "no behaviour change": the outputs of `srp perceive --csv` and
# `srp program` on the default demo and two seeds, written by one build, so that two builds
# (e.g. fec2a15 and the merged main) can be compared file by file.
#
#   scripts/check-no-behaviour-change.sh BUILD_DIR OUT_DIR [DEMO_DIR]
#   scripts/check-no-behaviour-change.sh --compare OUT_A OUT_B
#
# Per case (default: `srp synth-demo` with the scene's seed; seed7; seed3; instruction 1 of
# Appendix A, the thesis scene, 640x480) it writes to OUT_DIR:
#   <case>.rawlog            the synthesised demo (skipped when DEMO_DIR holds <case>.rawlog:
#                            give the other build's OUT_DIR to compare perception and programming
#                            on the very same frames even if the renderer changed); its header holds
#                            the wall-clock time, so it is not compared, its ground truth is:
#   <case>.gt.json           the demo's ground truth (`srp synth-demo`)
#   <case>.perceive.csv      `srp perceive --csv` (the per-frame table `srp segment` reads)
#   <case>.perceive.json     `srp perceive --json`
#   <case>.program.json      `srp program --json` without the run's wall times and peak memory
#   <case>.taskmodel.json    `srp db export --format json` of the stored task model, without its
#                            creation time
#   sha256sums.txt           one line per compared file
# --compare prints the files that differ between two such folders and exits 1 if a perception
# or programming output does (a differing ground truth is printed, not counted).
# Each build uses its own datasets/ (knowledge base, language model) as it ships.
# About 1-2 minutes per case on 2 cores.
set -euo pipefail

if [ "${1:-}" = "--compare" ]; then
  [ $# -eq 3 ] || { echo "usage: $0 --compare OUT_A OUT_B" >&2; exit 64; }
  a=$2 b=$3 differ=0
  for f in "$a"/*.csv "$a"/*.json; do  # *.gt.json: the demos; the others: perception and programming
    name=$(basename "$f")
    if [ ! -f "$b/$name" ] && [ "${name%.gt.json}" != "$name" ]; then echo "no demo: $name (DEMO_DIR reused)"
    elif [ ! -f "$b/$name" ]; then echo "missing in $b: $name"; differ=1
    elif ! cmp -s "$f" "$b/$name" && [ "${name%.gt.json}" != "$name" ]; then echo "differs: $name (the demo's ground truth: not a perception or programming output)"
    elif ! cmp -s "$f" "$b/$name"; then echo "differs: $name"; differ=1
    else echo "same:    $name"; fi
  done
  exit $differ
fi

[ $# -ge 2 ] && [ $# -le 3 ] || { echo "usage: $0 BUILD_DIR OUT_DIR [DEMO_DIR] | --compare OUT_A OUT_B" >&2; exit 64; }
build=$1 out=$2 demos=${3:-}
srp="$build/apps/srp"
[ -x "$srp" ] || { echo "$srp is missing: build the srp target of $build first" >&2; exit 66; }
mkdir -p "$out"

instruction="Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, carefully lift \
the star and position it next to the cuboid in the gray box. Then, move the parallelogram, placing it beside the \
star in the gray box. Finally, pick up the octagon and place it adjacent to the parallelogram in the gray box."

run_case() {  # name, synth-demo args...
  local name=$1; shift
  local demo="$out/$name.rawlog"
  if [ -n "$demos" ] && [ -f "$demos/$name.rawlog" ]; then
    demo="$demos/$name.rawlog"
  else
    "$srp" synth-demo -q -w -o "$demo" "$@" > /dev/null
  fi
  echo "== $name ($demo)"
  "$srp" perceive --demo "$demo" --csv "$out/$name.perceive.csv" -w --json > "$out/$name.perceive.json" 2> /dev/null
  local db="$out/$name.db"
  rm -f "$db" "$db-wal" "$db-shm"
  # wall times and peak memory change from run to run: left out
  "$srp" program -q --json -i "$instruction" --demo "$demo" --db "$db" --name "$name" |
    sed '/"timings_s": {/,/}/d; /"peak_memory_MB"/d' > "$out/$name.program.json"
  "$srp" db export 1 --db "$db" --format json | sed '/"created_utc"/d' > "$out/$name.taskmodel.json"
}

run_case default
run_case seed7 --seed 7
run_case seed3 --seed 3
(cd "$out" && sha256sum ./*.perceive.csv ./*.perceive.json ./*.program.json ./*.taskmodel.json $(ls ./*.gt.json 2> /dev/null) > sha256sums.txt)
cat "$out/sha256sums.txt"
echo "compare with another build's folder: $0 --compare $out OTHER_OUT"
