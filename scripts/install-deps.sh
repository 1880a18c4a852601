#!/usr/bin/env bash
# Installs what fabmesh needs, with apt-get (Debian 12):
#
#   scripts/install-deps.sh           build and run fabmesh: the compiler, CMake, the
#                                     libraries' -dev packages (cpp-httplib for the
#                                     studio, OpenCASCADE for STEP files), pybind11
#                                     and the Python headers (the Python module),
#                                     numpy (to use it), and the npm
#                                     packages of tools/node (three.js: the studio's 3D view)
#   scripts/install-deps.sh --test    also what the test suite and CI use: Catch2, clang
#                                     and clang-tidy, the tools outputs are checked with
#                                     (Chromium, PrusaSlicer, OpenSCAD, Draco's tools,
#                                     FreeCAD's freecadcmd for STEP files,
#                                     ezdxf, pytest, meshio, Open3D), a single-node
#                                     Slurm, and Node.js for the npm test tools of
#                                     tools/node (the Khronos glTF validator, the CNCjs
#                                     G-code interpreter, puppeteer-core for the studio's
#                                     page in Chromium)
#   scripts/install-deps.sh --bench   also the peer tools and Google Benchmark of bench/
#
# Flags combine (--test --bench). Idempotent: what is present is skipped, so
# re-running is cheap. Works as root or through sudo.
set -euo pipefail
cd "$(dirname "$0")/.."

test_deps=0 bench_deps=0
for arg in "$@"; do
  case "$arg" in
    --test) test_deps=1 ;;
    --bench) bench_deps=1 ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "install-deps: unknown argument '$arg' (use --test, --bench)" >&2; exit 2 ;;
  esac
done

# Building and running fabmesh, its library and its Python module.
packages=(
  build-essential cmake ninja-build ccache pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libeigen3-dev libopenmesh-dev libdraco-dev libtbb-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  libdxflib-dev lib3mf-dev libspng-dev zlib1g-dev libmuparser-dev libcpp-httplib-dev
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev libocct-data-exchange-dev
  python3 python3-dev pybind11-dev python3-numpy
)
# Node.js and npm come with the machine (NodeSource's nodejs bundles npm and
# conflicts with Debian's npm); install Debian's pair only where there is none.
# npm installs three.js (the studio's 3D view), pinned in tools/node.
if ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi
if ((test_deps)); then
  packages+=(
    catch2
    clang clang-tidy libclang-rt-14-dev
    python3-ezdxf python3-pytest python3-meshio python3-open3d python3-yaml python3-jsonschema
    prusa-slicer chromium draco openscad freecad
    slurm-wlm munge
    groff-base man-db
  )
fi
if ((bench_deps)); then
  packages+=(libbenchmark-dev admesh hyperfine time dxf2gcode occt-misc python3-pynest2d)
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

# npm packages, pinned by tools/node/package-lock.json: three.js (the studio's
# page, copied into the build) and the test tools (one lock file holds both).
npm_present=1
for module in three gltf-validator gcode-toolpath puppeteer-core; do
  [[ -d tools/node/node_modules/$module ]] || npm_present=0
done
if ((npm_present)) && [[ tools/node/node_modules/.package-lock.json -nt tools/node/package-lock.json ]]; then
  echo "install-deps: npm packages present"
else
  echo "install-deps: installing the npm packages (tools/node)"
  (cd tools/node && npm ci --no-audit --no-fund --loglevel=error)
fi
