#!/usr/bin/env bash
# Installs the Debian packages srp needs.
#   scripts/install-deps.sh          to build srp and run it (make demo)
#   scripts/install-deps.sh --test   also what the tests, notebooks and benchmarks need (make test)
# Idempotent: only missing packages are installed; apt-get is the only network use.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake pkg-config
  # core utilities
  libeigen3-dev nlohmann-json3-dev libcli11-dev
  # taskdb
  libsqlite3-dev libsqlitecpp-dev sqlite3
  # taskdb on a shared server (libpqxx), and the server its tests start
  libpqxx-dev postgresql
  # perception and calibration (ViSP modules used, not the meta package)
  libvisp-core-dev libvisp-detection-dev libvisp-vision-dev libvisp-io-dev libvisp-mbt-dev libvisp-klt-dev
  libopencv-dev libopencv-contrib-dev
  # MRPT modules used (not libmrpt-dev, which pulls in ROS)
  libmrpt-poses-dev libmrpt-obs-dev libmrpt-opengl-dev libmrpt-img-dev
  libmrpt-hwdrivers-dev mrpt-common
  # headless rendering (EGL on Mesa's software driver)
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgles-dev
  # language
  libdlib-dev wordnet-dev wordnet-base
  # motion and execution
  libnlopt-cxx-dev libsimbody-dev liburdfdom-dev liburdfdom-headers-dev
  # the ROS 2 trajectory export (a YAML emitter, not hand-written text)
  libyaml-cpp-dev
  # synthetic demos: the hand's AprilTag (tag36h11 bit patterns)
  libapriltag-dev
  # rawlog: gzip members compressed with libdeflate (fast, in parallel)
  libdeflate-dev
  # knowledge base: users' CAD files of their parts (OBJ, STL, PLY, glTF, COLLADA)
  libassimp-dev
  # calibration files in ROS camera_info YAML
  libyaml-cpp-dev
  # diagnostics: srp's log categories (srp/core/Log.h)
  libspdlog-dev
  # the man pages, generated from each command's --help at build time
  help2man
)

# Only for make test: GoogleTest, Google Benchmark, Debian's ViSP test images,
# GNU time (bench-program.sh).
TEST_PACKAGES=(
  libgtest-dev libgmock-dev libbenchmark-dev time
  visp-images-data
  # tests: exported trajectories are read back the way `ros2 topic pub` reads them (PyYAML)
  python3 python3-yaml
  # scripts/check-format.sh (CTest style.format): the files of scripts/format-checked.txt follow .clang-format
  clang-format
  # scripts/check-structure.py: function lengths
  universal-ctags
)
if [ "${1:-}" = "--test" ]; then PACKAGES+=("${TEST_PACKAGES[@]}"); fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${#missing[@]} missing packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
