#!/usr/bin/env bash
# Issue 8's speed figure: wall time and peak memory of `srp program` on a 60 s,
# 30 FPS, 640x480 demonstration (instruction 1 demonstrated slowly), against the
# demo's own duration (target: faster than real time; stretch: < 25 %).
#   scripts/bench-program.sh [build] [out]
set -euo pipefail
build=${1:-build}
out=${2:-$build/bench-results/program}
srp="$build/apps/srp"
mkdir -p "$out"
instruction="Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, carefully lift \
the star and position it next to the cuboid in the gray box. Then, move the parallelogram, placing it beside the \
star in the gray box. Finally, pick up the octagon and place it adjacent to the parallelogram in the gray box."

if [ ! -f "$out/demo60.rawlog" ]; then
  echo "== synthesising a ~60 s demo (instruction 1, slow demonstrator)"
  "$srp" synth-demo -o "$out/demo60.rawlog" --speed 0.36 -q
fi
rm -f "$out/task.db" "$out/task.db-wal" "$out/task.db-shm"
echo "== srp program"
/usr/bin/time -v -o "$out/time.txt" "$srp" program --instruction "$instruction" --demo "$out/demo60.rawlog" \
  --db "$out/task.db" --name bench --json > "$out/program.json"
wall=$(grep "Elapsed (wall clock)" "$out/time.txt" | awk '{print $NF}')
rss_kb=$(grep "Maximum resident set size" "$out/time.txt" | awk '{print $NF}')
cpu_user=$(grep "User time" "$out/time.txt" | awk '{print $NF}')
frames=$(grep -m1 '"frames"' "$out/program.json" | tr -dc '0-9')
echo "frames: $frames, demo duration $(awk "BEGIN{printf \"%.1f\", $frames/30}") s"
echo "srp program wall: $wall (m:ss), user CPU: ${cpu_user} s, peak RSS: $((rss_kb / 1024)) MB"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
