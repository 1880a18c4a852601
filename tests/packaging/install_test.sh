#!/usr/bin/env bash
# `cmake --install` into a temporary prefix gives a usable fabmesh: the
# files of docs/install.md, nothing internal; the CMake package found by
# version (its own MAJOR.MINOR accepted, the minors beside it and 1.0 refused) with fabmesh::fabmesh
# pointing into the prefix; the pkg-config file; each public header compiles
# on its own with the standard library only; the Python module's and the
# program's run paths are relative to themselves; the program run as a user
# runs it (from PATH, through a link, from another folder) finds its modules
# (module_lookup_test.sh); the installed README's links resolve (doc_links_test.sh).
# Usage: install_test.sh BUILD_DIR VERSION CXX PYTHON_MODULE_BUILT(1|0)
set -uo pipefail
build=$1 version=$2 cxx=$3 python_built=$4
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
work=$(mktemp -d "${TMPDIR:-/tmp}/fabmesh-install-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1 || { cat "$work/install.log"; echo "FAIL: cmake --install"; exit 1; }

for f in bin/fabmesh lib/libfabmesh.so "lib/libfabmesh.so.${version%.*}" "lib/libfabmesh.so.$version" \
  include/fabmesh/fabmesh.h include/fabmesh/version.h \
  lib/cmake/fabmesh/fabmeshConfig.cmake lib/cmake/fabmesh/fabmeshConfigVersion.cmake \
  lib/cmake/fabmesh/fabmeshTargets.cmake lib/pkgconfig/fabmesh.pc \
  share/fabmesh/examples/vessel_golden_shell.yaml share/doc/fabmesh/README.md share/doc/fabmesh/docs/install.md \
  share/doc/fabmesh/examples/consumer/CMakeLists.txt share/doc/fabmesh/configs/examples/vessel_golden_solid.yaml \
  share/man/man1/fabmesh.1 share/bash-completion/completions/fabmesh \
  share/fabmesh/studio/index.html share/fabmesh/studio/studio.js share/fabmesh/studio/three/build/three.module.js \
  share/fabmesh/studio/three/examples/jsm/loaders/GLTFLoader.js lib/fabmesh/fabmesh-step.so lib/fabmesh/fabmesh-http.so; do
  [[ -e $prefix/$f ]] || fail "not installed: $f"
done
internal=$(cd "$prefix" && find . -name '*.a' -o -name '*.in' -o -name 'libfabmesh_*')
[[ -z $internal ]] || fail "internal files installed: $internal"
grep -q "FABMESH_VERSION_STRING \"$version\"" "$prefix/include/fabmesh/version.h" || fail "version.h does not say $version"

# Run paths: relative to the installed file, never the build folder.
runpath() { readelf -d "$1" | sed -n 's/.*(RUNPATH).*\[\(.*\)\]/\1/p'; }
# The program links no library of the prefix: no run path to search.
[[ -z $(readelf -d "$prefix/bin/fabmesh" | grep -E '\((RUNPATH|RPATH)\)') ]] ||
  fail "bin/fabmesh has a run path: $(readelf -d "$prefix/bin/fabmesh" | grep -E '\((RUNPATH|RPATH)\)')"
if ldd "$prefix/bin/fabmesh" | grep -qF "$prefix/"; then fail "bin/fabmesh links a library of the prefix"; fi
module=$(compgen -G "$prefix/lib/python3/dist-packages/fabmesh.cpython-*.so" | head -n 1)
if [[ $python_built == 1 ]]; then
  if [[ -z $module ]]; then
    fail "the Python module was built but not installed into lib/python3/dist-packages"
  else
    [[ $(runpath "$module") == '$ORIGIN/../..' ]] || fail "the Python module's RUNPATH is '$(runpath "$module")'"
    [[ -e $prefix/lib/python3/dist-packages/fabmesh.pyi ]] || fail "fabmesh.pyi is not beside the Python module"
  fi
else
  echo "NOTE: this build has no Python module (FABMESH_PYTHON off, or pybind11 missing): not checked"
  [[ -z $module ]] || fail "a Python module was installed though none was built"
fi
for f in "$prefix/lib/libfabmesh.so.$version" "$prefix/bin/fabmesh"; do
  if grep -qF "$build" "$f"; then fail "$f names the build folder"; fi
done

# The installed program finds its STEP module (loaded only for STEP files).
step_out=$work/step-out
if "$prefix/bin/fabmesh" run "$prefix/share/fabmesh/examples/vessel_golden_solid.yaml" --export-format step \
  -o "$step_out/" -q >"$work/step.log" 2>&1; then
  grep -q "ISO-10303-21" "$step_out/vessel_golden_solid.step" || fail "the installed program's STEP file is no STEP file"
else
  cat "$work/step.log"
  fail "the installed program could not write a STEP file"
fi
grep -qF "$build" "$prefix/lib/fabmesh/fabmesh-step.so" && fail "the STEP module names the build folder"
here=$(cd "$(dirname "$0")" && pwd)
"$here/module_lookup_test.sh" "$prefix/bin/fabmesh" "$prefix/share/fabmesh/examples/vessel_golden_solid.yaml" ||
  fail "the installed program, run from PATH or through a link, does not find its modules"
if [[ $python_built == 1 && -n $module ]]; then
  # The Python module finds the STEP module from libfabmesh's own file, from any folder.
  mkdir -p "$work/python-run"
  (cd "$work/python-run" && PYTHONPATH="$prefix/lib/python3/dist-packages" /usr/bin/python3 -c "
import fabmesh
fabmesh.build(fabmesh.read_design('$prefix/share/fabmesh/examples/vessel_golden_solid.yaml')).write('cup.step')
assert open('cup.step').read(13) == 'ISO-10303-21;'") >"$work/python-run.log" 2>&1 ||
    fail "the installed Python module wrote no STEP file: $(tail -n 3 "$work/python-run.log")"
fi
"$here/doc_links_test.sh" "$prefix/share/doc/fabmesh" || fail "the installed documentation has broken links"
# The project's README, not docs/README.md installed over it (as docs/ once was, into the same folder).
cmp -s "$prefix/share/doc/fabmesh/README.md" "$here/../../README.md" || fail "share/doc/fabmesh/README.md is not the README"
cmp -s "$prefix/share/doc/fabmesh/docs/README.md" "$here/../../docs/README.md" || fail "docs/README.md is not installed"

# The CMake package, by version, from a project that compiles nothing.
find_fabmesh() {  # VERSION -> configure exit code; writes the target's include folder
  local dir=$work/find-$1
  mkdir -p "$dir"
  cat >"$dir/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.20)
project(find_fabmesh LANGUAGES NONE)
find_package(fabmesh $1 CONFIG REQUIRED)
get_target_property(includes fabmesh::fabmesh INTERFACE_INCLUDE_DIRECTORIES)
get_target_property(location fabmesh::fabmesh LOCATION)
file(WRITE \${CMAKE_BINARY_DIR}/found.txt "\${fabmesh_VERSION};\${includes};\${location}")
CMAKE
  cmake -S "$dir" -B "$dir/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >"$dir/log" 2>&1
}
minor=${version%.*}  # 0.4 of 0.4.0
previous=0.$((${minor#0.} - 1)) next=0.$((${minor#0.} + 1))
if find_fabmesh "$minor"; then
  IFS=';' read -r found_version found_includes found_location <"$work/find-$minor/build/found.txt"
  [[ $found_version == "$version" ]] || fail "find_package(fabmesh $minor) found version $found_version"
  [[ $found_includes == "$prefix/include" ]] || fail "fabmesh::fabmesh includes '$found_includes', not $prefix/include"
  [[ $found_location == "$prefix/lib/libfabmesh.so.$version" ]] || fail "fabmesh::fabmesh is '$found_location'"
else
  cat "$work/find-$minor/log"
  fail "find_package(fabmesh $minor CONFIG) failed"
fi
for refused in "$previous" "$next" 1.0; do
  if find_fabmesh "$refused"; then fail "find_package(fabmesh $refused) accepted $version"; fi
done

# pkg-config.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
[[ $(pkg-config --modversion fabmesh) == "$version" ]] || fail "pkg-config --modversion fabmesh: $(pkg-config --modversion fabmesh)"
[[ $(cd "$(pkg-config --variable=includedir fabmesh)" && pwd) == "$prefix/include" ]] || fail "pkg-config includedir is not $prefix/include"
[[ $(cd "$(pkg-config --variable=libdir fabmesh)" && pwd) == "$prefix/lib" ]] || fail "pkg-config libdir is not $prefix/lib"

# Every public header compiles on its own, and includes only fabmesh's
# headers and the standard library's (no CGAL, OpenMesh, yaml-cpp, ...).
for header in "$prefix"/include/fabmesh/*.h; do
  name=fabmesh/$(basename "$header")
  echo "#include <$name>" | "$cxx" -std=c++17 -fsyntax-only -Wall -Wextra -Werror -I"$prefix/include" -x c++ - ||
    fail "$name does not compile on its own"
  others=$(grep -E '^\s*#\s*include' "$header" | grep -vE '[<"]fabmesh/[a-z_]+\.h[>"]' | grep -vE '<[a-z_]+>')
  [[ -z $others ]] || fail "$name includes more than fabmesh and the standard library: $others"
done

if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "cmake --install gives a usable fabmesh $version"
