#!/usr/bin/env bash
# Runs one srp command line and checks BOTH its exit code and its output, so a
# command that prints the right words and then fails (or the reverse) fails the test.
# CTest's PASS_REGULAR_EXPRESSION alone ignores the exit code; this script is why.
#
#   check_cli.sh [--exit N] [--expect REGEX]... [--reject REGEX]... -- command args...
#
# --exit N      the exit code the command must return (default 0)
# --expect R    a Perl regex the combined stdout+stderr must match ('.' matches newlines)
# --reject R    a Perl regex the output must not match
# --skip N      an exit code that means "skipped" (CTest's SKIP_RETURN_CODE): passed on as is
set -u
exit_expected=0
skip_code=
expects=()
rejects=()
while [ $# -gt 0 ]; do
  case "$1" in
    --exit) exit_expected=$2; shift 2 ;;
    --expect) expects+=("$2"); shift 2 ;;
    --reject) rejects+=("$2"); shift 2 ;;
    --skip) skip_code=$2; shift 2 ;;
    --) shift; break ;;
    *) echo "check_cli: unknown option '$1' (usage: check_cli.sh [--exit N] [--expect R]... -- cmd...)"; exit 2 ;;
  esac
done
if [ $# -eq 0 ]; then echo "check_cli: no command after --"; exit 2; fi

out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$@" >"$out" 2>&1
rc=$?
cat "$out"
if [ -n "$skip_code" ] && [ "$rc" -eq "$skip_code" ]; then
  echo "check_cli: skipped (exit $rc)"
  exit "$rc"
fi
failed=0
if [ "$rc" -ne "$exit_expected" ]; then
  echo "check_cli: FAIL: exit code $rc, expected $exit_expected"
  failed=1
fi
for r in ${expects[@]+"${expects[@]}"}; do
  if ! grep -Pzq -- "(?s)$r" "$out"; then
    echo "check_cli: FAIL: output does not match: $r"
    failed=1
  fi
done
for r in ${rejects[@]+"${rejects[@]}"}; do
  if grep -Pzq -- "(?s)$r" "$out"; then
    echo "check_cli: FAIL: output matches what it must not: $r"
    failed=1
  fi
done
if [ $failed -eq 0 ]; then
  echo "check_cli: ok (exit $rc, ${#expects[@]} expected and ${#rejects[@]} rejected patterns)"
fi
exit $failed
