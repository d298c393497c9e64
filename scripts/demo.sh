#!/usr/bin/env bash
# README command one, after the build: the thesis scenario end to end on the
# bundled default (SPEC.md §4). Synthesise the demonstration of instruction 1,
# program the task from it, execute it and two adaptations in simulation, and
# the task once more in the scene its own demonstration showed.
# A second run replaces the first run's outputs (-w).
set -euo pipefail
build=${1:-build}
srp="$build/apps/srp"
out=${SRP_DEMO_OUT:-out/demo}
scene=sim/scenes/default.json
mkdir -p "$out"
db="$out/task.db"
rm -f "$db" "$db-wal" "$db-shm"

instruction="Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, carefully lift \
the star and position it next to the cuboid in the gray box. Then, move the parallelogram, placing it beside the \
star in the gray box. Finally, pick up the octagon and place it adjacent to the parallelogram in the gray box."
subset="Pick up the cuboid from the blue box and place it in the gray box."
reversal="Move the cuboid from the gray box back to the blue box."

step() { printf '\n== %s\n' "$*"; }
started=$(date +%s)

step "1/6 synthesise the demonstration of instruction 1 ($scene)"
"$srp" synth-demo --scene "$scene" -o "$out/demo.rawlog" --contact-sheet "$out/contact_sheet.png" -w

step "2/6 program the task: instruction + demonstration -> task model"
"$srp" program --instruction "$instruction" --demo "$out/demo.rawlog" --db "$db" --name thesis \
  -o "$out/report" -w

run_execute() {  # name, extra args...: every step must be done (exit 0)
  local name=$1; shift
  set +e
  "$srp" execute --db "$db" --task 1 --out "$out/$name" -w "$@"
  local rc=$?
  set -e
  if [ $rc -ne 0 ]; then  # 3: steps skipped or refused, 1: a step failed (the report says which)
    echo "demo: 'srp execute' ($name) exited $rc; expected 0, every step done: see $out/$name/report.txt" >&2
    exit $rc
  fi
}
step "3/6 execute the learned task on the simulated UR5 (and export it for the real cell)"
run_execute execute --scene "$scene" --urscript "$out/task.script" --trajectory-yaml "$out/trajectory.yaml"
step "4/6 adaptation without a new demonstration: subset"
run_execute subset --scene "$scene" --instruction "$subset"
step "5/6 adaptation without a new demonstration: reversal (from the scene the first run left)"
run_execute reversal --scene "$out/execute/final_scene.json" --instruction "$reversal"
step "6/6 the learned task in the scene of its own demonstration (no --scene: the scene srp program perceived; robot base from calib/extrinsics.json)"
run_execute own_scene --extrinsics calib/extrinsics.json

step "summary ($(( $(date +%s) - started )) s)"
"$srp" db list --db "$db"
for run in execute subset reversal own_scene; do
  if [ -f "$out/$run/report.txt" ]; then echo "-- $run"; tail -n 4 "$out/$run/report.txt"; fi
done
echo
echo "Report of the programming run: $out/report/summary.md"
echo "Execution reports and frames: $out/execute/ $out/subset/ $out/reversal/ $out/own_scene/"
for f in "$out/task.script" "$out/trajectory.yaml"; do
  if [ -f "$f" ]; then echo "For the real cell: $f"; else echo "not written (see the execute step's message): $f"; fi
done
