#!/usr/bin/env bash
# srp installed and packaged, used the way a user or another project uses it.
#
#   install_test.sh prefix    BUILD_DIR PREFIX        cmake --install --strip into PREFIX, check the layout
#   install_test.sh consumer  SOURCE_DIR PREFIX WORK  build examples/consumer against PREFIX (find_package(srp)), run it
#   install_test.sh relocated SOURCE_DIR PREFIX       copy PREFIX elsewhere, hide the source tree (a private mount
#                                                     namespace when allowed), run srp from the copy: parse, the demo
#                                                     (synth-demo, program, execute) and perceive on the bundled
#                                                     recording; no source path in the binary
#   install_test.sh deb       BUILD_DIR WORK          cpack the .deb packages, dpkg -x them, run srp --version
set -euo pipefail
mode=$1
fail() { echo "FAIL: $*" >&2; exit 1; }
step() { printf '\n== %s\n' "$*"; }

case $mode in
  prefix)
    build=$2 prefix=$3
    rm -rf "$prefix"
    cmake --install "$build" --prefix "$prefix" --strip > "$prefix.log" 2>&1 || { cat "$prefix.log"; fail "cmake --install"; }
    for f in bin/srp share/srp/datasets/kb/catalogue.json share/srp/datasets/language/model/language_model.dat \
             share/srp/sim/scenes/default.json share/srp/sim/ur5/ur5.urdf share/srp/calib/camera.xml \
             share/srp/datasets/real/visp-rbt-cube/color_0000.png include/srp/core/DataPaths.h \
             include/srp/language/InstructionParser.h share/bash-completion/completions/srp \
             share/man/man1/srp.1 share/man/man1/srp-program.1 share/man/man1/srp-db-show.1; do
      [ -e "$prefix/$f" ] || fail "not installed: $prefix/$f"
    done
    # The man pages are the commands' --help, without the build machine's data folder.
    grep -q -- "intrinsics" "$prefix/share/man/man1/srp-program.1" || fail "srp-program.1 lacks --intrinsics"
    if grep -q "Data folder:" "$prefix"/share/man/man1/*.1; then fail "a man page names the build's data folder"; fi
    pages=$(ls "$prefix"/share/man/man1/srp*.1 | wc -l)
    [ "$pages" -ge 25 ] || fail "only $pages man pages"
    config=$(find "$prefix" -name srpConfig.cmake | head -1)
    [ -n "$config" ] || fail "no srpConfig.cmake under $prefix"
    for m in core taskdb language perception motion programming execution calib kb rawlog synth plot experiment; do
      [ -n "$(find "$prefix" -name "libsrp_$m.a")" ] || fail "libsrp_$m.a not installed"
    done
    echo "installed into $prefix: $(du -sh "$prefix" | cut -f1) ($config), $pages man pages"
    ;;

  consumer)
    src=$2 prefix=$3 work=$4
    rm -rf "$work"
    step "configure and build examples/consumer against $prefix"
    cmake -S "$src/examples/consumer" -B "$work" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
      > "$work.configure.log" 2>&1 || { cat "$work.configure.log"; fail "configure the consumer"; }
    cmake --build "$work" -j 2 > "$work.build.log" 2>&1 || { cat "$work.build.log"; fail "build the consumer"; }
    step "run it"
    out=$(cd "$work" && env -u SRP_DATA_DIR ./srp_consumer 2>&1) || { echo "$out"; fail "srp_consumer exited non-zero"; }
    echo "$out"
    grep -q "cuboid" <<<"$out" || fail "no cuboid in the consumer's plan"
    grep -q "gray box" <<<"$out" || fail "no gray box in the consumer's plan"
    grep -Eq "tcp at q = 0: \[[-0-9.e]+, [-0-9.e]+, [-0-9.e]+\] m" <<<"$out" || fail "no tool position"
    ;;

  relocated)
    src=$(cd "$2" && pwd) prefix=$3
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/srp_relocated_XXXXXX")
    trap 'rm -rf "$tmp"' EXIT
    cp -a "$prefix" "$tmp/moved"
    srp="$tmp/moved/bin/srp"
    step "no path of the source tree ($src) in the installed binary"
    if grep -c -F "$src" "$srp" >/dev/null; then
      strings "$srp" | grep -F "$src" | head -5
      fail "the installed srp holds the source path $src"
    fi
    echo "none"
    # The runs below, from the copy, with the working folder outside the repository.
    cat > "$tmp/run.sh" <<RUN
set -euo pipefail
cd "$tmp"
unset SRP_DATA_DIR
srp="$srp"
data="$tmp/moved/share/srp"
if [ -d "$src/datasets" ]; then echo "source tree visible: $src/datasets"; else echo "source tree hidden: $src is empty"; fi
"\$srp" --version
"\$srp" --help | grep -F "Data folder: \$data (next to the executable)"
echo "-- srp parse"
"\$srp" parse --json "Pick up the cuboid from the blue box and place it in the gray box." | grep -q '"color": "gray"'
echo "-- the demo: synth-demo, program, execute (the shipped default scene, Appendix A instruction 1)"
instruction="Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, carefully lift the star and position it next to the cuboid in the gray box. Then, move the parallelogram, placing it beside the star in the gray box. Finally, pick up the octagon and place it adjacent to the parallelogram in the gray box."
"\$srp" synth-demo -q -o demo.rawlog
"\$srp" program -q --instruction "\$instruction" --demo demo.rawlog --db task.db --name demo > program.txt
"\$srp" execute --db task.db --task 1 --out execute --frame-period 0 > execute.txt || { cat execute.txt; exit 1; }
cat execute.txt
grep -q "^4/4 steps done" execute.txt
echo "-- srp perceive on the bundled recording (\$data/datasets/real/visp-rbt-cube)"
"\$srp" import "\$data/datasets/real/visp-rbt-cube" cube.rawlog --json | grep -q '"frames": 50'
"\$srp" perceive --demo cube.rawlog --kb "\$data/datasets/real/visp-rbt-cube/catalogue.json" --objects cube \
  --hand none --moving-camera --json > perceive.json
grep -Eq '"detected_frames": (4[5-9]|50)' perceive.json
echo "relocated prefix: every run passed"
RUN
    if unshare -m true 2>/dev/null; then
      step "hide the source tree (private mount namespace, tmpfs over $src) and run from $tmp/moved"
      unshare -m bash -c "mount -t tmpfs none '$src' && bash '$tmp/run.sh'"
    else
      step "run from $tmp/moved (no mount namespace here: the source tree stays visible, the installed srp does not look there)"
      bash "$tmp/run.sh"
    fi
    ;;

  deb)
    build=$2 work=$3
    rm -rf "$work" && mkdir -p "$work"
    step "cpack: the Debian packages"
    (cd "$build" && cpack -G DEB -B "$work/packages" > "$work/cpack.log" 2>&1) || { cat "$work/cpack.log"; fail "cpack"; }
    ls -la "$work/packages"/*.deb
    for p in "$work/packages"/*.deb; do dpkg-deb --info "$p" | grep -E "Package:|Depends:" ; done
    step "dpkg -x srp and srp-data, run srp --version from the extracted tree"
    for p in "$work/packages"/srp_*.deb "$work/packages"/srp-data_*.deb; do dpkg -x "$p" "$work/root"; done
    (cd "$work" && env -u SRP_DATA_DIR "$work/root/usr/bin/srp" --version) | grep -E "^srp [0-9]+\.[0-9]+\.[0-9]+$"
    (cd "$work" && env -u SRP_DATA_DIR "$work/root/usr/bin/srp" --help) | grep -F "Data folder: $work/root/usr/share/srp"
    ;;

  *) fail "unknown mode '$mode'" ;;
esac
