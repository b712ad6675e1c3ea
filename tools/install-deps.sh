#!/usr/bin/env bash
# Installs Prism's build and test dependencies from Debian 12 packages (needs root or sudo).
# Open MPI (libopenmpi-dev, openmpi-bin) is optional: with it CMake also builds prism-mpi.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
  g++ cmake ninja-build ccache pkg-config \
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev libpng-dev \
  libtinyobjloader-dev libtinygltf-dev libcli11-dev libfmt-dev \
  libgtest-dev libboost-dev python3-matplotlib clang-format \
  libopenmpi-dev openmpi-bin >/dev/null
echo "dependencies installed"
