#!/usr/bin/env bash
# Installs contour4d's build and test dependencies from Debian 12 packages (idempotent).
# Only what is missing is installed; nothing is downloaded outside apt.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config clang clang-format libclang-rt-14-dev
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libeigen3-dev
  libinsighttoolkit5-dev libgdcm-tools libdcmtk-dev
  libtinygltf-dev libmeshoptimizer-dev libzstd-dev libstb-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev libspdlog-dev
  libtbb-dev
  libtet1.5-dev openfoam
  libgtest-dev libgmock-dev libbenchmark-dev
  libglfw3-dev libegl-dev libgl-dev libgles-dev libegl1-mesa-dev libgl1-mesa-dri
  python3 python3-numpy python3-pytest python3-meshio pybind11-dev snakemake chromium python3-vtk9 python3-nibabel python3-skimage python3-matplotlib python3-pil python3-pydicom
  libegl-mesa0 mesa-utils
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} Debian packages already installed"
  exit 0
fi

echo "setup: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
