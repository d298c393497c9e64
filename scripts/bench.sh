#!/usr/bin/env bash
# Runs every benchmark built from bench/ and writes its JSON next to the build.
set -euo pipefail
build=${1:-build}
mkdir -p "$build/bench-results"
for b in "$build"/bench/*_bench; do
  [ -x "$b" ] || continue
  name=$(basename "$b")
  echo "== $name"
  "$b" --benchmark_out="$build/bench-results/$name.json" --benchmark_out_format=json
done
# Issue 8: srp program on a 60 s demo, wall time and peak memory.
if [ -x "$build/apps/srp" ]; then
  echo "== srp program (scripts/bench-program.sh)"
  "$(dirname "$0")/bench-program.sh" "$build" "$build/bench-results/program"
fi
