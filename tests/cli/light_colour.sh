#!/usr/bin/env bash
# `srp synth-demo --light-rgb/--light-direction`: the same first frame rendered under white light and under
# a warm lamp (R 1.0, G 0.9, B 0.78); the mean colour's blue-to-red ratio must drop by the lamp's ratio.
# Usage: light_colour.sh <path to srp>
set -eu
SRP=$1
HERE=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/srp_light_XXXXXX")
trap 'rm -rf "$TMP"' EXIT
render() {  # name, then extra options
  local name=$1
  shift
  "$SRP" synth-demo -q --clean --max-frames 1 --width 160 --height 120 -o "$TMP/$name.rawlog" "$@" > /dev/null
  "$SRP" replay -q "$TMP/$name.rawlog" -o "$TMP/$name" > /dev/null
  python3 "$HERE/mean_colour.py" "$TMP/$name"/color_*.png
}
white=$(render white)
warm=$(render warm --light-rgb 1,0.9,0.78)
turned=$(render turned --light-rgb 1,0.9,0.78 --light-direction -0.5,0.6,-0.65)
echo "mean R G B: white $white, warm $warm, warm from the side $turned"
python3 - "$white" "$warm" "$turned" <<'PY'
import sys
white, warm, turned = ([float(v) for v in a.split()] for a in sys.argv[1:])
# The renderer is linear (no gamma): every lit pixel's blue scales by 0.78/1.0 against red, and green by 0.9,
# except where white light saturates a channel (then the lamp's ratio is higher). Asserted: within 0.03.
for channel, lamp in ((2, 0.78), (1, 0.9)):
    ratio = (warm[channel] / warm[0]) / (white[channel] / white[0])
    assert abs(ratio - lamp) < 0.03, f"channel {channel}: warm/white ratio {ratio:.3f}, expected {lamp} +- 0.03"
# Turned 40 deg above the table from the side, the same lamp lights the table less (its cosine) than from above.
assert sum(turned) < sum(warm) - 3, f"the light's direction changed nothing: {turned} vs {warm}"
print("ok")
PY
