#!/usr/bin/env bash
# Installs the Debian packages mrloc needs, and only those that are missing: when all are
# present it returns in well under a second.
#   scripts/install-deps.sh tour   what building the program and running ./run.sh's tour need
#   scripts/install-deps.sh        that and what the tests, the sanitized build, fuzzing,
#                                  MRPT's example data and `mrloc batch` need (./test.sh)
set -euo pipefail
set_name="${1:-all}"
case "$set_name" in tour | all) ;; *) echo "install-deps: give tour or nothing" >&2; exit 2 ;; esac

packages=(
  build-essential cmake pkg-config
  libmrpt-dev            # MRPT 2.5: poses, observations, rawlogs, config, opengl (CFBORender)
  libeigen3-dev liboctomap-dev zlib1g-dev
  libopencv-dev          # imgproc (omnivision's bands), calib3d (formation's lens model); with libopencv-contrib-dev, which it pulls
  libopencv-contrib-dev  # in: aruco, the detector formation measures AprilTag 3 against
  libapriltag-dev        # AprilTag 3 (BSD-2): formation's tag detector (paper 003), the better one
  nlohmann-json3-dev     # metrics.json writing and reading
  libboost-dev           # Boost.Geometry: the overlay region of polymap (polygon booleans)
  gnuplot-nox            # error-over-time and CDF plots (pngcairo terminal)
  libegl1 libegl-mesa0 libgl1-mesa-dri   # head-less EGL rendering for CFBORender
  # `mrloc import rosbag` (doc/import.md), compiled into the program: ROS 1 bags read by
  # librosbag-storage (BSD), the message types it converts, and the ROS 2 headers Debian's
  # pluginlib-dev (which rosbag/bag.h includes) wants on the path
  librosbag-storage-dev libnav-msgs-dev libsensor-msgs-dev libtf2-msgs-dev libgeometry-msgs-dev
  pluginlib-dev librcpputils-dev libclass-loader-dev libament-index-cpp-dev
)
if [ "$set_name" = all ]; then packages+=(
  libgtest-dev libbenchmark-dev   # the tests and the benchmarks (not built by ./run.sh)
  clang libclang-rt-14-dev   # the sanitized build and libFuzzer (scripts/sanitize.sh, fuzz.sh)
  mrpt-common            # MRPT's example rawlogs and INIs: tests and fuzzing seeds
  mrpt-apps              # MRPT's own ro-localization / pf-localization: timed beside mrloc localize (doc/framesync.md)
  xvfb                   # xvfb-run: MRPT's apps open a window even when asked for a log
  parallel               # GNU parallel: `mrloc batch` runs its trials through it (doc/batch.md; it says so when missing)
  # the test bag's script (tests/data/rosbag/make_tiny_bag.py), run again by a test
  python3-rosbag python3-nav-msgs python3-sensor-msgs python3-tf2-msgs python3-geometry-msgs
); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${#missing[@]} packages and what they need: ${missing[*]}" >&2
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
# apt's own lines (one per package fetched, unpacked and set up): never minutes of silence
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
