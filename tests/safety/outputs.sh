#!/usr/bin/env bash
# Outputs never destroy inputs: every command that writes is given an output that is
# one of its inputs (by the same name, another spelling, a symlink, a hard link), two
# outputs on one file, an output folder holding an input, or an existing output
# without -w/--overwrite. Each must fail before it writes, and every input and every
# existing file must keep its bytes (sha256 before and after).
#
# usage: outputs.sh SRP_EXECUTABLE SCRATCH_FOLDER
set -u
SRP=$1
T=$2
SRC=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$T"
mkdir -p "$T/data"
cd "$T" || exit 1

# Inputs of every kind the commands read.
"$SRP" db import "$SRC/datasets/examples/appendix_c_instruction1.json" --db data/task.db > /dev/null || exit 1
cp "$SRC/sim/scenes/default.json" data/scene.json
cp "$SRC/datasets/real/visp-rbt-cube/cube.obj" data/cube.obj
cp "$SRC/datasets/kb/catalogue.json" data/catalogue.json
cp "$SRC/libs/language/tests/data/tiny_corpus.json" data/corpus.json
cp "$SRC/calib/camera.xml" data/camera.xml
mkdir -p data/images && cp "$SRC"/datasets/real/visp-calib-chessboard/chessboard-0[12].jpg data/images/
echo '{"pairs": []}' > data/pairs.json
mkdir -p data/frames && cp "$SRC"/datasets/real/visp-rbt-cube/{cam.json,color_000[01].png,depth_000[01].png} data/frames/
printf 'not a rawlog' > data/demo.rawlog
echo 'existing output' > data/existing.txt
ln -s task.db data/task_link.db
ln data/scene.json data/scene_hardlink.json

cases=0
refused=0
destroyed=0
accepted=0

# The bytes of every file that was there before (a database's -wal/-shm that SQLite adds
# on a read are not inputs); a file gone or changed shows.
find data -type f | sort > inputs.txt
snapshot() { while read -r f; do sha256sum "$f" 2>&1; done < inputs.txt; }

# case NAME -- command...: must exit non-zero; no file under data/ may change.
case_() {
  local name=$1
  shift 2
  cases=$((cases + 1))
  local before after
  before=$(snapshot)
  "$@" > "out_$cases.log" 2>&1
  local rc=$?
  after=$(snapshot)
  if [ "$before" != "$after" ]; then
    destroyed=$((destroyed + 1))
    echo "DESTROYED: $name: $*"
    diff <(echo "$before") <(echo "$after") | head -5
  fi
  if [ $rc -eq 0 ]; then
    accepted=$((accepted + 1))
    echo "NOT REFUSED: $name: $*"
    tail -3 "out_$cases.log"
  else
    refused=$((refused + 1))
  fi
}

EX=("$SRP" execute --db data/task.db --task 1 --frame-period 0)
for out in data/task.db ./data/task.db data/../data/task.db "$T/data/task.db" data/task_link.db data/scene.json \
           data/scene_hardlink.json data/existing.txt; do
  case_ "execute --urscript onto an input" -- "${EX[@]}" --scene data/scene.json --urscript "$out" --out x1
  case_ "execute --trajectory-yaml onto an input" -- "${EX[@]}" --scene data/scene.json --trajectory-yaml "$out" --out x2
done
case_ "execute: script and YAML on one file" -- "${EX[@]}" --urscript same.out --trajectory-yaml ./same.out --out x3
case_ "execute --out folder holding the database" -- "${EX[@]}" --out data -w
case_ "execute --out onto the database" -- "${EX[@]}" --out data/task.db -w
case_ "execute --out folder with other files" -- "${EX[@]}" --out data/images -w

for out in data/task.db data/task_link.db data/existing.txt; do
  case_ "db export --out onto an input or existing file" -- "$SRP" db export 1 --db data/task.db --out "$out" --format json
done

case_ "kb add: mesh is the catalogue" -- "$SRP" kb add --catalogue data/catalogue.json --name cube2 --mesh data/catalogue.json
case_ "kb add: a hostile name" -- "$SRP" kb add --catalogue data/catalogue.json --name $'cube\r\n---' --mesh data/cube.obj
case_ "kb add: the catalogue is a folder" -- "$SRP" kb add --catalogue data --name cube2 --mesh data/cube.obj
case_ "kb build over existing meshes" -- "$SRP" kb build --catalogue "$SRC/datasets/kb/catalogue.json"

for out in data/images/chessboard-01.jpg data/images data/existing.txt; do
  case_ "calibrate --out onto an input" -- "$SRP" calibrate --images 'data/images/*.jpg' --pattern chessboard:9x6:0.025 --out "$out"
done
case_ "calibrate --draw onto the images folder" -- "$SRP" calibrate --images 'data/images/*.jpg' --pattern chessboard:9x6:0.025 --out cam.xml --draw data/images -w
case_ "calibrate extrinsics --out onto --image" -- "$SRP" calibrate extrinsics --image data/images/chessboard-01.jpg --intrinsics data/camera.xml --tag-size 0.1 --tag 0:0,0,0,0,0,0 --out data/images/chessboard-01.jpg
case_ "calibrate extrinsics --out onto --intrinsics" -- "$SRP" calibrate extrinsics --image data/images/chessboard-01.jpg --intrinsics data/camera.xml --tag-size 0.1 --tag 0:0,0,0,0,0,0 --out data/camera.xml
case_ "calibrate hand-eye --out onto --pairs" -- "$SRP" calibrate hand-eye --pairs data/pairs.json --out data/pairs.json
case_ "calibrate board over an existing file" -- "$SRP" calibrate board --pattern chessboard:9x6:0.025 --out data/existing.txt
case_ "calibrate board: a 4800 dpi giant" -- "$SRP" calibrate board --pattern chessboard:200x200:1.0 --out giant.png --dpi 4800

case_ "train-language --out onto --train" -- "$SRP" train-language --train data/corpus.json --out data/corpus.json
case_ "train-language --out existing" -- "$SRP" train-language --train data/corpus.json --out data/existing.txt
case_ "eval-language --predictions onto --data" -- "$SRP" eval-language --data data/corpus.json --predictions data/corpus.json

case_ "replay --video onto the rawlog" -- "$SRP" replay data/demo.rawlog --video data/demo.rawlog
case_ "replay --export folder holding the rawlog" -- "$SRP" replay data/demo.rawlog --export data -w

case_ "synth-demo -o onto --scene" -- "$SRP" synth-demo -q --scene data/scene.json -o data/scene.json --max-frames 1
case_ "synth-demo -o existing" -- "$SRP" synth-demo -q --scene data/scene.json -o data/existing.txt --max-frames 1
case_ "synth-demo --contact-sheet onto --scene" -- "$SRP" synth-demo -q --scene data/scene.json -o d.rawlog --contact-sheet data/scene.json --max-frames 1

for out in data/frames/cam.json data/frames/color_0000.png data/frames data/demo.rawlog; do
  case_ "import onto its own folder, a frame or an existing rawlog" -- "$SRP" import data/frames "$out" --fps 10
done

case_ "program --report onto the demo's folder" -- "$SRP" program -i "Pick up the cuboid." --demo data/demo.rawlog --db p.db --report data -w
case_ "program --db onto the demo" -- "$SRP" program -i "Pick up the cuboid." --demo data/demo.rawlog --db data/demo.rawlog
case_ "program --name hostile" -- "$SRP" program -i "Pick up the cuboid." --demo data/demo.rawlog --db p.db --name $'x\n---\npoints: []'

case_ "perceive --csv onto --demo" -- "$SRP" perceive --demo data/demo.rawlog --csv data/demo.rawlog
case_ "perceive --csv onto --kb" -- "$SRP" perceive --demo data/demo.rawlog --kb data/catalogue.json --csv data/catalogue.json
case_ "perceive --draw folder holding the demo" -- "$SRP" perceive --demo data/demo.rawlog --draw data -w
case_ "perceive --draw folder with other files" -- "$SRP" perceive --demo data/demo.rawlog --draw data/images -w
case_ "motion --out-dir folder holding the database" -- "$SRP" motion 1 --db data/task.db --out-dir data -w
case_ "parse --db --name hostile" -- "$SRP" parse "Pick up the cuboid and place it in the gray box." --db data/task.db --name $'t\r---'
case_ "record over an existing file" -- "$SRP" record data/existing.txt --frames 1

echo "[ sweep ] outputs onto inputs: $cases cases, $refused refused, $accepted not refused, $destroyed inputs destroyed"
[ $destroyed -eq 0 ] && [ $accepted -eq 0 ]
