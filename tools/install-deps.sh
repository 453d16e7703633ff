#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the Debian packages Cleave builds and tests with. Idempotent; runs apt-get update first.
# `tools/install-deps.sh DIR...` also installs the npm packages some tests use into each DIR (the
# build folder's npm/, see below); that part only warns when npm or the registry is not there, and
# the tests that need the packages then skip with the reason.
# The Python tests' packages (pytest, numpy, trimesh; tests/python/requirements.txt) are not
# installed here but by the build, into <build>/pyenv, with the interpreter the module `cleave` is
# built for (python3-dev, python3-venv and pybind11-dev below; see docs/python.md).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

PACKAGES=(
  build-essential cmake ninja-build pkg-config ccache git python3 python3-dev python3-venv pybind11-dev
  libglfw3-dev libglm-dev libbullet-dev libtinygltf-dev libstb-dev
  nlohmann-json3-dev libimgui-dev
  libegl-dev libgl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libglx-mesa0 libgbm1 libglapi-mesa
  libosmesa6-dev python3-glad
  libgtest-dev libgmock-dev libbenchmark-dev assimp-testmodels libcgal-demo
  xvfb xauth xdotool
)
# node and npm, for the npm packages below: Debian's nodejs and npm, unless the commands are already
# there (another nodejs package, NodeSource's for one, ships npm and conflicts with Debian's npm).
NODE_PACKAGES=()
command -v node >/dev/null 2>&1 || NODE_PACKAGES+=(nodejs)
command -v npm >/dev/null 2>&1 || NODE_PACKAGES+=(npm)
# npm packages, pinned: the Khronos glTF validator (tests/assets/skinned_glb_test.cpp) and the
# Stanford bunny (tests/assets/corpus_test.cpp). ./cleave passes <build>/npm as DIR, where the tests
# look for node_modules/ (CLEAVE_NPM_DIR overrides that).
NPM_PACKAGES=(gltf-validator@2.0.0-dev.3.10 bunny@1.0.1)

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
if [ "${#NODE_PACKAGES[@]}" -gt 0 ]; then
  echo "cleave: installing ${NODE_PACKAGES[*]}"
  $SUDO apt-get install -y -qq --no-install-recommends "${NODE_PACKAGES[@]}" ||
    echo "cleave: warning: could not install ${NODE_PACKAGES[*]}; the tests that need npm packages will skip" >&2
fi

# npm_installed DIR: every NPM_PACKAGES entry is in DIR/node_modules at its version.
npm_installed() {
  local spec name
  for spec in "${NPM_PACKAGES[@]}"; do
    name="${spec%@*}"
    [ "$(node -p 'require(process.argv[1]).version' "$1/node_modules/$name/package.json" 2>/dev/null)" \
      = "${spec##*@}" ] || return 1
  done
}

for dir in "$@"; do
  dir="$(mkdir -p "$dir" && cd "$dir" && pwd)"
  if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    echo "cleave: warning: node or npm not found; not installing ${NPM_PACKAGES[*]} into $dir" \
      "(the tests that need them will skip)" >&2
    continue
  fi
  npm_installed "$dir" && continue
  echo "cleave: installing ${NPM_PACKAGES[*]} into $dir"
  # Bounded retries: an unreachable registry costs well under a minute, not several.
  if ! npm install --no-audit --no-fund --save-exact --fetch-timeout=60000 --fetch-retry-maxtimeout=10000 \
    --prefix "$dir" "${NPM_PACKAGES[@]}" || ! npm_installed "$dir"; then
    echo "cleave: warning: npm could not install ${NPM_PACKAGES[*]} into $dir" \
      "(the tests that need them will skip)" >&2
  fi
done
