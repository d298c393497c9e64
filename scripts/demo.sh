#!/usr/bin/env bash
# The main job on the bundled default (README command one, after the build).
# Runs what the project has: each stage is used when its command exists.
set -euo pipefail
build=${1:-build}
srp="$build/apps/srp"
out=${SRP_DEMO_OUT:-out/demo}
mkdir -p "$out"
db="$out/task.db"
rm -f "$db" "$db-wal" "$db-shm"

has() { "$srp" "$1" --help >/dev/null 2>&1; }

echo "== srp demo: the thesis scenario (SPEC.md §4), output in $out"
"$srp" db init "$db"
"$srp" db import datasets/examples/appendix_c_instruction1.json --db "$db"
"$srp" db show 1 --db "$db"
"$srp" db export 1 --db "$db" --format appendix-c --out "$out/appendix_c.tsv"
echo
echo "Task model stored in $db; Appendix C layout written to $out/appendix_c.tsv"
