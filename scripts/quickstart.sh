#!/usr/bin/env bash
# Installs the Debian packages the package needs, builds it, and fits a
# model to the bundled real single-view scan of a mug.
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends \
  cmake make g++ libcgal-dev libeigen3-dev libboost-dev libboost-graph-dev libgmp-dev libmpfr-dev \
  libboost-program-options-dev nlohmann-json3-dev libtbb-dev
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2 --target blended_fit
build/bin/blended_fit data/scans/pcl_mug_scan.xyz
