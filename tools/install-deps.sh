#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs, only those missing.
set -euo pipefail

PACKAGES=(
  cmake ninja-build g++ make pkg-config git
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools glslang-dev spirv-tools libspirv-cross-c-shared-dev
  libglm-dev libglfw3-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libtinyexr-dev
  libopenvdb-dev libnanovdb-dev libopenvdb-tools libboost-iostreams-dev
  libgtest-dev assimp-testmodels libxml2-utils
  clang libclang-rt-14-dev
  chromium
  libimgui-dev xvfb xauth
  slurm-wlm munge  # avsm-sweep slurm; the tests start a local single-node cluster
)

missing=()
for package in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
