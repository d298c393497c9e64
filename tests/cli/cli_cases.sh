#!/usr/bin/env bash
# CLI checks of issue 21: each case runs srp on a bad input and passes only
# when the exit code AND the message are right (CTest's PASS_REGULAR_EXPRESSION
# alone ignores the exit code).
# Usage: cli_cases.sh <path to srp> <case>
set -u
SRP=$1
CASE=$2
TMP=$(mktemp -d "${TMPDIR:-/tmp}/srp_cli_${CASE}_XXXXXX")
trap 'rm -rf "$TMP"' EXIT
ROOT=$(cd "$(dirname "$0")/../.." && pwd)

# expect <exit: N or nonzero> <extended regex> -- command...
expect() {
  local want=$1 regex=$2
  shift 3
  local out rc
  out=$("$@" 2>&1)
  rc=$?
  if [[ $want == nonzero ]]; then
    [[ $rc -ne 0 ]] || { echo "FAIL: exit 0, expected non-zero: $*"; echo "$out"; exit 1; }
  else
    [[ $rc -eq $want ]] || { echo "FAIL: exit $rc, expected $want: $*"; echo "$out"; exit 1; }
  fi
  grep -Eq -- "$regex" <<<"$out" || { echo "FAIL: message does not match /$regex/: $*"; echo "$out"; exit 1; }
  # Messages are printable text (no heap garbage, no binary class names).
  if LC_ALL=C grep -q '[^[:print:][:space:]]' <<<"$out"; then echo "FAIL: non-printable bytes in: $out"; exit 1; fi
  echo "ok (exit $rc): $*"
}

# A small synthetic demonstration (srp's own rawlog, with its end marker).
small_demo() {
  "$SRP" synth-demo -o "$TMP/demo.rawlog" --width 64 --height 48 --max-frames 12 --clean -q > /dev/null || exit 1
}

# A failed `srp program` leaves no database file behind (nor its WAL files).
no_database_left() {
  for f in "$TMP/t.db" "$TMP/t.db-wal" "$TMP/t.db-shm"; do
    [[ ! -e $f ]] || { echo "FAIL: a failed run left $f behind"; exit 1; }
  done
  echo "ok: no database left behind"
}

case $CASE in
  parse_invalid_utf8)
    expect 1 'not valid UTF-8 \(byte 12 is 0xFF\)' -- "$SRP" parse $'Pick up the \xff cuboid.' --json ;;
  scene_number_overflow)
    sed 's/"seed": *[0-9]*/"seed": 1e999/' "$ROOT/sim/scenes/default.json" > "$TMP/scene.json"
    grep -q 1e999 "$TMP/scene.json" || { echo "FAIL: test scene has no seed to replace"; exit 1; }
    expect 1 "scene.json.*malformed JSON: number overflow parsing '1e999'" -- \
      "$SRP" synth-demo --scene "$TMP/scene.json" -o "$TMP/x.rawlog" --max-frames 1 ;;
  camera_width_1e12)
    echo '{"fx": 500, "fy": 500, "cx": 320, "cy": 240, "width": 1e12, "height": 480}' > "$TMP/cam.json"
    expect 1 "'width' must be a whole number of pixels in 1\.\.16384 \(got 1000000000000" -- \
      "$SRP" program -i "Pick up the cuboid and place it in the gray box." --demo "$TMP/none.rawlog" \
      --calib "$TMP/cam.json" --db "$TMP/t.db" ;;
  camera_px_inf|camera_px_abc)
    value=1e400; [[ $CASE == camera_px_abc ]] && value=abc
    sed "s#<px>607.178</px>#<px>$value</px>#" "$ROOT/calib/camera.xml" > "$TMP/camera.xml"
    expect 1 'camera.xml.*(focal lengths fx, fy \(ViSP px, py\) must be numbers in \(0, 1e\+06\] px|px, py, u0, v0 must be numbers)' -- \
      "$SRP" program -i "Pick up the cuboid and place it in the gray box." --demo "$TMP/none.rawlog" \
      --calib "$TMP/camera.xml" --db "$TMP/t.db" ;;
  board_dpi_0)
    expect nonzero '--dpi: Value 0 not in range 30 to 4800' -- \
      "$SRP" calibrate board --pattern chessboard:9x6:0.025 --out "$TMP/b.png" --dpi 0 ;;
  synth_width_negative)
    expect nonzero '--width: Value -5 not in range 16 to 16384' -- "$SRP" synth-demo -o "$TMP/x.rawlog" --width -5 ;;
  replay_fps_0)
    expect nonzero '--fps: Value 0 not in range' -- "$SRP" replay "$TMP/x.rawlog" --fps 0 ;;
  import_depth_scale_0)
    mkdir -p "$TMP/frames"
    expect nonzero '--depth-scale: Value 0 not in range' -- "$SRP" import "$TMP/frames" "$TMP/x.rawlog" --depth-scale 0 ;;
  db_show_hex_id)
    expect nonzero "'0x1' is not a TaskModelId" -- "$SRP" db show 0x1 --db "$TMP/t.db" ;;
  zero_quaternion)
    pose='{"translation": [0, 0, 0], "quaternion": [0, 0, 0, 0]}'
    echo "{\"pairs\": [{\"X_base_gripper\": $pose, \"X_camera_target\": $pose}]}" > "$TMP/pairs.json"
    expect 1 "'quaternion' \(w,x,y,z\) must be finite and not zero" -- \
      "$SRP" calibrate hand-eye --pairs "$TMP/pairs.json" --out "$TMP/e.json" ;;
  unknown_subcommand)
    expect nonzero "srp: error: unknown command 'frobnicate' \(commands: .*program.*\)" -- "$SRP" frobnicate
    expect nonzero "srp db: error: unknown command 'frobnicate' \(commands: init, list" -- "$SRP" db frobnicate ;;
  garbage_rawlog)
    head -c 100 /dev/urandom > "$TMP/garbage.rawlog"
    printf '\x85\x01\x02\xff\xfe\x07garbage' > "$TMP/binary.rawlog"
    expect nonzero 'garbage\.rawlog' -- "$SRP" replay "$TMP/garbage.rawlog"
    expect nonzero 'binary\.rawlog.*(no MRPT object header|damaged)' -- "$SRP" replay "$TMP/binary.rawlog" ;;
  program_damaged_demo)
    small_demo
    size=$(stat -c %s "$TMP/demo.rawlog")
    truncate -s $((size * 9 / 10)) "$TMP/demo.rawlog"
    expect 1 'damaged after frame [0-9]+ .*at byte [0-9]+.*nothing was stored' -- \
      "$SRP" program -i "Pick up the cuboid and place it in the gray box." --demo "$TMP/demo.rawlog" \
      --db "$TMP/t.db" -q
    no_database_left
    expect 3 'DAMAGED' -- "$SRP" replay "$TMP/demo.rawlog" ;;
  program_unwritable_report)
    small_demo
    touch "$TMP/file"
    expect 1 'cannot create the report folder.*nothing was stored' -- \
      "$SRP" program -i "Pick up the cuboid and place it in the gray box." --demo "$TMP/demo.rawlog" \
      --db "$TMP/t.db" --report "$TMP/file/report" -q
    no_database_left ;;
  *)
    echo "unknown case $CASE"; exit 1 ;;
esac
