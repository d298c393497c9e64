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
