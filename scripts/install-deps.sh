#!/usr/bin/env bash
# Installs the Debian packages periflex builds and tests with.
# Safe to run again: when every package is present it changes nothing.
# Usage: scripts/install-deps.sh [--compute-only]
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config file
  libeigen3-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libstb-dev gnuplot-nox libdeflate-dev
  libsuitesparse-dev libopenblas0-serial
  libgtest-dev libgmock-dev libbenchmark-dev libboost-dev libpolyclipping-dev
  pybind11-dev python3-dev python3-numpy python3-pytest
  python3-matplotlib python3-pil jupyter-nbconvert python3-ipykernel python3-nbformat
)
if [[ "${1:-}" != "--compute-only" ]]; then
  packages+=(
    libimgui-dev libglfw3-dev libgl-dev libegl-dev libopengl-dev
    libegl-mesa0 libgl1-mesa-dri xvfb xauth ffmpeg xdotool
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "Installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
