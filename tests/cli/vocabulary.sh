#!/usr/bin/env bash
# One CLI vocabulary (srp --help, apps/srp/CommonOptions.h), checked over every command srp lists:
#   - every command and subcommand takes -q/--quiet, -v/--verbose, --log-level and --data-dir;
#   - each command is classified below: the ones that write a main output take -o,--out, the ones
#     whose result is data take --json (a command srp lists but this file does not classify fails);
#   - every old spelling still works and prints one deprecation line naming the new one;
#   - -q silences the notes, -v turns the debug categories on, a bad --log-level is a usage error (2).
# Usage: vocabulary.sh SRP SOURCE_DIR
set -uo pipefail
SRP=$1 SRC=$2
TMP=$(mktemp -d /tmp/srp_cli_vocabulary_XXXXXX)
trap 'rm -rf "$TMP"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Leaf commands ("cmd" or "cmd sub"): the main output option and --json.
declare -A OUT JSON
for c in calibrate "calibrate extrinsics" "calibrate hand-eye" "calibrate board" "db export" execute experiment \
         import "kb build" motion perceive program record replay synth-demo train-language; do OUT[$c]=1; done
for c in calibrate "calibrate extrinsics" "calibrate hand-eye" "db list" "db show" eval-language execute experiment \
         import "kb add" "kb build" "kb list" motion parse perceive program record replay segment synth-demo \
         train-language; do JSON[$c]=1; done
# Commands whose result is not data: a confirmation line (db init/import/delete), a picture (calibrate board),
# the exported document itself (db export --format json).
NOT_DATA=("calibrate board" "db init" "db import" "db delete" "db export")

subcommands() {  # the subcommands srp <path> --help lists
  "$SRP" "$@" --help | awk '/^Subcommands:/ { s = 1; next } /^[^ ]/ { s = 0 } s && /^  [a-z]/ { print $1 }'
}
leaves=()
for c in $(subcommands); do
  subs=$(subcommands "$c")
  # calibrate is a command with options of its own and subcommands
  if [ -z "$subs" ] || [ "$c" = calibrate ]; then leaves+=("$c"); fi
  for s in $subs; do leaves+=("$c $s"); done
done
[ ${#leaves[@]} -ge 20 ] || fail "srp --help lists only ${#leaves[@]} commands"

for c in "${leaves[@]}"; do
  # shellcheck disable=SC2086
  help=$("$SRP" $c --help 2>&1) || { fail "srp $c --help exits non-zero"; continue; }
  for opt in "-q,--quiet" "-v,--verbose" "--log-level" "--data-dir"; do
    grep -q -- "^ *$opt" <<<"$help" || fail "srp $c: no $opt"
  done
  classified=0
  if [ -n "${OUT[$c]:-}" ]; then classified=1; grep -q -- "^ *-o,--out" <<<"$help" || fail "srp $c: no -o,--out"; fi
  if [ -n "${JSON[$c]:-}" ]; then classified=1; grep -q -- "^ *--json" <<<"$help" || fail "srp $c: no --json"; fi
  for n in "${NOT_DATA[@]}"; do [ "$n" = "$c" ] && classified=1; done
  [ $classified = 1 ] || fail "srp $c is not classified in $0 (main output? data?)"
  echo "ok: srp $c"
done

# Old spellings: each still parses and prints exactly one deprecation line naming the new spelling
# (the command may then fail on the made-up input; the line comes first).
deprecated() {  # old new -- command...
  local old=$1 new=$2; shift 3
  local out
  out=$("$@" 2>&1 >/dev/null)
  local n
  n=$(grep -c "srp: warning: '$old' is deprecated and will be removed; use '$new'" <<<"$out")
  [ "$n" = 1 ] || fail "'$old' -> '$new': expected one deprecation line, got $n: $*"$'\n'"$out"
  echo "ok: $old warns"
}
cat="$SRC/datasets/kb/catalogue.json"
deprecated --catalogue --kb -- "$SRP" kb list --catalogue "$cat"
deprecated --catalogue --kb -- "$SRP" kb build --catalogue "$cat" -o "$TMP/kb" -w
deprecated --catalogue --kb -- "$SRP" kb add --catalogue "$TMP/parts.json" --name box1 --shape box --size 0.1 0.1 0.1
deprecated --report --out -- "$SRP" program -i "Pick up the cuboid." --demo "$TMP/none.rawlog" --report "$TMP/r"
deprecated --calib --intrinsics -- "$SRP" program -i "Pick up the cuboid." --demo "$TMP/none.rawlog" --calib "$TMP/c.xml"
deprecated --export --out -- "$SRP" replay "$TMP/none.rawlog" --export "$TMP/frames"
deprecated --task-id --task -- "$SRP" replay "$TMP/none.rawlog" --task-id 1
deprecated --csv --out -- "$SRP" perceive --demo "$TMP/none.rawlog" --csv "$TMP/t.csv"
deprecated --out-dir --out -- "$SRP" motion --task 1 --db "$TMP/none.db" --out-dir "$TMP/m"
deprecated "the positional id" --task -- "$SRP" motion 1 --db "$TMP/none.db"
deprecated "the positional out" --out -- "$SRP" import "$TMP/nofolder" "$TMP/x.rawlog"
deprecated "the positional out" --out -- "$SRP" record "$TMP/x.rawlog" --frames 1
deprecated "the positional id" --task -- "$SRP" db show 1 --db "$TMP/none.db"
deprecated "the positional id" --task -- "$SRP" db export 1 --db "$TMP/none.db"
deprecated "the positional id" --task -- "$SRP" db delete 1 --db "$TMP/none.db"
deprecated "the positional file" --db -- "$SRP" db init "$TMP/init.db"
[ -f "$TMP/init.db" ] || fail "db init FILE (the old spelling) created no database"
# The new spellings: no warning.
out=$("$SRP" db init --db "$TMP/new.db" 2>&1) || fail "db init --db: $out"
grep -q warning <<<"$out" && fail "db init --db warns: $out"
"$SRP" db show --db "$TMP/new.db" > "$TMP/show.txt" 2>&1
[ $? = 2 ] && grep -q -- "--task is required" "$TMP/show.txt" || fail "db show without --task: $(cat "$TMP/show.txt")"

# --json prints JSON (only JSON on stdout).
isjson() { python3 -c 'import json, sys; json.load(sys.stdin)' || fail "not JSON: $*"; }
"$SRP" kb list --json | isjson kb list --json
"$SRP" kb build --json -o "$TMP/kb2" | isjson kb build --json
"$SRP" parse --json "Put the cuboid in the gray box." | isjson parse --json
"$SRP" db list --json --db "$TMP/new.db" | isjson db list --json

# -q, -v, --log-level on a tiny rendered demo.
"$SRP" synth-demo -o "$TMP/demo.rawlog" --width 64 --height 48 --max-frames 8 --clean -q > /dev/null 2>&1 \
  || fail "synth-demo for the -q/-v checks"
verbose=$("$SRP" perceive --demo "$TMP/demo.rawlog" -v 2>&1 >/dev/null)
grep -q "^perception: debug: frame" <<<"$verbose" || fail "perceive -v wrote no 'perception: debug:' line: $verbose"
one=$("$SRP" perceive --demo "$TMP/demo.rawlog" --log-level hand=debug 2>&1 >/dev/null)
grep -q "^perception: debug:" <<<"$one" && fail "--log-level hand=debug also wrote perception's debug lines"
quiet=$("$SRP" perceive --demo "$TMP/demo.rawlog" --hand none -q --draw "$TMP/drawn" 2>&1 >/dev/null)
[ -z "$quiet" ] || fail "perceive -q wrote on stderr: $quiet"
noisy=$("$SRP" perceive --demo "$TMP/demo.rawlog" --hand none --draw "$TMP/drawn" -w 2>&1 >/dev/null)
grep -q "drew .* frames" <<<"$noisy" || fail "perceive --draw without -q wrote no note: $noisy"
legacy=$(SRP_PERCEPTION_DEBUG=1 "$SRP" perceive --demo "$TMP/demo.rawlog" --hand none 2>&1 >/dev/null)
grep -q "SRP_PERCEPTION_DEBUG is deprecated; use --log-level perception=debug" <<<"$legacy" \
  && grep -q "^perception: debug:" <<<"$legacy" || fail "SRP_PERCEPTION_DEBUG: no deprecation line or no debug lines: $legacy"
"$SRP" kb list --log-level loud > "$TMP/ll.txt" 2>&1
rc=$?
[ $rc = 2 ] && grep -q "log level 'loud': not a level" "$TMP/ll.txt" || fail "--log-level loud: exit $rc: $(cat "$TMP/ll.txt")"

[ $failures = 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "vocabulary: all checks passed"
