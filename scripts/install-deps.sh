#!/usr/bin/env bash
# Installs every dependency fabmesh needs to build, test and benchmark:
# Debian packages with apt-get, and the npm test tools of tools/node (the
# Khronos glTF validator, the CNCjs G-code interpreter) with `npm ci`.
# Idempotent: what is present is skipped, so re-running is cheap.
# Works as root or through sudo. Usage: scripts/install-deps.sh [--bench]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build ccache pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libeigen3-dev libopenmesh-dev libdraco-dev libtbb-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  catch2 libbenchmark-dev libdxflib-dev
  lib3mf-dev libspng-dev zlib1g-dev
  clang clang-tidy libclang-rt-14-dev
  python3 python3-ezdxf
  prusa-slicer chromium draco openscad
  slurm-wlm munge
)
# Node.js and npm come with the machine (NodeSource's nodejs bundles npm and
# conflicts with Debian's npm); install Debian's pair only where there is none.
if ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi
if [[ "${1:-}" == "--bench" ]]; then
  packages+=(admesh hyperfine time dxf2gcode)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} Debian packages present"
else
  echo "install-deps: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# npm test tools, pinned by tools/node/package-lock.json.
if [[ -d tools/node/node_modules/gltf-validator && -d tools/node/node_modules/gcode-toolpath &&
      tools/node/node_modules/.package-lock.json -nt tools/node/package-lock.json ]]; then
  echo "install-deps: npm test tools present"
else
  echo "install-deps: installing the npm test tools (tools/node)"
  (cd tools/node && npm ci --no-audit --no-fund --loglevel=error)
fi
