#!/usr/bin/env bash
# Installs the Debian packages Cleave builds and tests with. Idempotent; runs apt-get update first.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

PACKAGES=(
  build-essential cmake ninja-build pkg-config ccache git python3
  libglfw3-dev libglm-dev libbullet-dev libtinygltf-dev libstb-dev
  nlohmann-json3-dev
  libegl-dev libgl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libglx-mesa0 libgbm1 libglapi-mesa
  libosmesa6-dev python3-glad
  libgtest-dev libgmock-dev libbenchmark-dev assimp-testmodels libcgal-demo
  xvfb xauth xdotool
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# Always refresh the package lists: a fresh machine may have none, and Mesa packages must match.
$SUDO apt-get update -qq
if [ "${#missing[@]}" -gt 0 ]; then
  echo "cleave: installing ${missing[*]}"
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
