#!/usr/bin/env bash
# CI step: fabmesh as it is installed (docs/install.md), from an already built
# build folder (no rebuild):
#   - `cmake --install` into a temporary prefix: the files are where they should
#     be, the program runs its bundled example from there, no path of the
#     checkout is compiled in; run as a user runs it (from PATH in an unrelated
#     folder, through a symbolic link) it finds its modules, and without them
#     a design asking for STEP exits 5 (tests/packaging/module_lookup_test.sh);
#     the installed README's links resolve (tests/packaging/doc_links_test.sh);
#   - examples/consumer configured, built and run against that prefix only
#     (find_package(fabmesh 0.4 CONFIG)), and its main.cpp built through pkg-config;
#   - the Python module imported from the prefix's site-packages;
#   - the manual page formatted by man without warnings;
#   - `cpack -G DEB`: its Depends, `apt-get install ./fabmesh_*.deb`, /usr/bin/fabmesh
#     (the bundled example, then `check` of an STL it wrote; from PATH and through a
#     link as above; its documentation's links), the Python module from /usr, then
#     `apt-get remove fabmesh`.
#
#   scripts/ci-package.sh [BUILD_DIR]      (default: build)
#
# Installing the package needs root (or sudo). Fails on the first problem.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
say() { echo "ci-package: $*" >&2; }
# The file the loader would load for libfabmesh when starting $1, resolved.
loaded_libfabmesh() { realpath -e "$(ldd "$1" | awk '$1 ~ /^libfabmesh\.so/ {print $3}')" 2>/dev/null; }
die() { say "FAILED: $*"; exit 1; }

version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")
[[ -n $version ]] || die "no project version in $build/CMakeCache.txt"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi

work="$(mktemp -d /tmp/fabmesh-ci-package.XXXXXX)"
package_installed=0
cleanup() {
  if ((package_installed)); then
    say "removing the fabmesh package after a failure"
    $SUDO apt-get remove -y -qq fabmesh >/dev/null || true
  fi
  rm -rf "$work"
}
trap cleanup EXIT

# --- cmake --install into a temporary prefix ---
prefix="$work/prefix"
cmake --install "$build" --prefix "$prefix" >"$work/install.log" || { cat "$work/install.log"; die "cmake --install"; }
site="$prefix/lib/python3/dist-packages"
expected=(
  bin/fabmesh
  lib/libfabmesh.so "lib/libfabmesh.so.${version%.*}" "lib/libfabmesh.so.$version"
  include/fabmesh/fabmesh.h include/fabmesh/version.h include/fabmesh/build.h include/fabmesh/design.h
  include/fabmesh/mesh.h include/fabmesh/curves.h include/fabmesh/errors.h
  lib/cmake/fabmesh/fabmeshConfig.cmake lib/cmake/fabmesh/fabmeshConfigVersion.cmake
  lib/cmake/fabmesh/fabmeshTargets.cmake
  lib/pkgconfig/fabmesh.pc
  share/fabmesh/examples/vessel_golden_shell.yaml
  share/doc/fabmesh/README.md share/doc/fabmesh/docs/commands.md share/doc/fabmesh/examples/consumer/main.cpp
  share/man/man1/fabmesh.1
  share/bash-completion/completions/fabmesh
  lib/python3/dist-packages/fabmesh.pyi
)
for f in "${expected[@]}"; do [[ -e $prefix/$f ]] || die "cmake --install did not install $f"; done
compgen -G "$site/fabmesh.cpython-*.so" >/dev/null || die "cmake --install did not install the Python module into $site"
unexpected=$(cd "$prefix" && find . -name '*.a' -o -name '*.in' -o -name 'fabmesh_*.so*')
[[ -z $unexpected ]] || die "installed what is internal: $unexpected"
for f in bin/fabmesh "lib/libfabmesh.so.$version" "$(cd "$prefix" && ls lib/python3/dist-packages/fabmesh.cpython-*.so)"; do
  if grep -qF "$root" "$prefix/$f" || grep -qF "$build" "$prefix/$f"; then
    die "$f names the checkout or the build folder (a path compiled in)"
  fi
done
say "installed $(cd "$prefix" && find . -type f | wc -l) files into a temporary prefix"

[[ $("$prefix/bin/fabmesh" --version) == "fabmesh $version" ]] || die "the installed fabmesh --version is not $version"
# The installed program finds its examples relative to itself.
(cd "$work" && "$prefix/bin/fabmesh" -q) || die "$prefix/bin/fabmesh (the bundled example) failed"
compgen -G "$work/out/*.stl" >/dev/null || die "the installed fabmesh wrote no STL into out/"
"$prefix/bin/fabmesh" -q check "$work"/out/*.stl || die "the installed fabmesh check"
rm -rf "$work/out"
# As a user runs it: by its name on PATH, through a link, from another folder.
"$root/tests/packaging/module_lookup_test.sh" "$prefix/bin/fabmesh" \
  "$prefix/share/fabmesh/examples/vessel_golden_solid.yaml" || die "the installed program does not find its modules"
"$root/tests/packaging/doc_links_test.sh" "$prefix/share/doc/fabmesh" || die "the installed documentation's links"

# --- examples/consumer against the prefix, not the build tree ---
cmake -S "$root/examples/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >"$work/consumer.log" ||
  { cat "$work/consumer.log"; die "configuring examples/consumer"; }
found=$(sed -n 's/^fabmesh_DIR:PATH=//p' "$work/consumer/CMakeCache.txt")
[[ $found == "$prefix/lib/cmake/fabmesh" ]] || die "examples/consumer found fabmesh at '$found', not in the prefix"
cmake --build "$work/consumer" >>"$work/consumer.log" || { cat "$work/consumer.log"; die "building examples/consumer"; }
"$work/consumer/fabmesh_consumer" || die "examples/consumer did not get the expected results"
[[ $(loaded_libfabmesh "$work/consumer/fabmesh_consumer") == "$prefix/lib/libfabmesh.so.$version" ]] ||
  die "examples/consumer does not load libfabmesh from the prefix"

# The same program through pkg-config.
PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --exact-version="$version" fabmesh ||
  die "pkg-config does not find fabmesh $version in the prefix"
read -r -a pc_flags <<<"$(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs fabmesh)"
c++ -std=c++17 -O1 "$root/examples/consumer/main.cpp" -o "$work/consumer-pc" "${pc_flags[@]}" \
  -Wl,-rpath,"$prefix/lib" || die "building examples/consumer/main.cpp with pkg-config's flags"
"$work/consumer-pc" >/dev/null || die "examples/consumer built with pkg-config did not get the expected results"
say "examples/consumer built and ran against the prefix (CMake package and pkg-config)"

# --- the Python module from the prefix ---
py_version=$(cd "$work" && PYTHONPATH="$site" /usr/bin/python3 -c "import fabmesh; print(fabmesh.__version__)") ||
  die "import fabmesh from $site"
[[ $py_version == "$version" ]] || die "fabmesh.__version__ is '$py_version', not $version"
py_file=$(cd "$work" && PYTHONPATH="$site" /usr/bin/python3 -c "import fabmesh; print(fabmesh.__file__)")
[[ $py_file == "$site"/* ]] || die "import fabmesh loaded $py_file, not the prefix's module"
[[ $(loaded_libfabmesh "$py_file") == "$prefix/lib/libfabmesh.so.$version" ]] || die "the Python module does not load libfabmesh from the prefix"
say "Python: import fabmesh from the prefix, version $py_version"

# --- the manual page ---
man_warnings=$(LC_ALL=C.UTF-8 MANWIDTH=80 man --warnings -l "$prefix/share/man/man1/fabmesh.1" 2>&1 >/dev/null)
[[ -z $man_warnings ]] || die "man -l warns: $man_warnings"
man_text=$(LC_ALL=C.UTF-8 MANWIDTH=80 man -l "$prefix/share/man/man1/fabmesh.1")
grep -q "fabmesh check MESH" <<<"$man_text" || die "man -l did not render the page"

# --- the Debian package ---
if dpkg-query -W -f='${Status}' fabmesh 2>/dev/null | grep -q "install ok installed"; then
  die "a fabmesh package is installed on this machine already; remove it first"
fi
(cd "$build" && cpack -G DEB -B "$work/deb" >"$work/cpack.log") || { cat "$work/cpack.log"; die "cpack -G DEB"; }
deb="$work/deb/fabmesh_${version}_$(dpkg --print-architecture).deb"
[[ -f $deb ]] || die "cpack made no $(basename "$deb"): $(ls "$work/deb")"
depends=$(dpkg-deb -f "$deb" Depends)
say "$(basename "$deb"): Depends: $depends"
for needed in libc6 libstdc++6 lib3mf1 libocct-data-exchange-7.6 libcpp-httplib0.11; do
  grep -q "\b$needed\b" <<<"$depends" || die "Depends lacks $needed"
done
contents=$(dpkg-deb -c "$deb")
grep -qE '\./usr/lib/python3/dist-packages/fabmesh\.cpython-.*\.so' <<<"$contents" ||
  die "the package has no Python module in /usr/lib/python3/dist-packages"
grep -qE '\./usr/bin/fabmesh$' <<<"$contents" || die "the package has no /usr/bin/fabmesh"

cp "$deb" "$work/"
package_installed=1
(cd "$work" && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "./$(basename "$deb")") ||
  die "apt-get install ./$(basename "$deb")"
mkdir "$work/run"
(cd "$work/run" && /usr/bin/fabmesh) || die "/usr/bin/fabmesh (the bundled example)"
stl=$(compgen -G "$work/run/out/*.stl" | head -n 1) || die "/usr/bin/fabmesh wrote no STL"
/usr/bin/fabmesh check "$stl" || die "/usr/bin/fabmesh check $stl"
# The libraries loaded on first use: lib3mf (3MF) and the STEP module (OpenCASCADE).
(cd "$work/run" && /usr/bin/fabmesh run /usr/share/fabmesh/examples/vessel_golden_solid.yaml \
  --export-format 3mf -o out3mf/ -q && /usr/bin/fabmesh check out3mf/vessel_golden_solid.3mf) ||
  die "/usr/bin/fabmesh wrote or read no 3MF file"
(cd "$work/run" && /usr/bin/fabmesh run /usr/share/fabmesh/examples/vessel_golden_solid.yaml \
  --export-format step -o outstep/ -q && grep -q "ISO-10303-21" outstep/vessel_golden_solid.step) ||
  die "/usr/bin/fabmesh wrote no STEP file"
# The package's program as a user runs it: `fabmesh` on PATH, a link to it, any folder.
[[ $(cd "$work/run" && command -v fabmesh) == /usr/bin/fabmesh ]] || die "fabmesh on PATH is not /usr/bin/fabmesh"
"$root/tests/packaging/module_lookup_test.sh" /usr/bin/fabmesh /usr/share/fabmesh/examples/vessel_golden_solid.yaml ||
  die "/usr/bin/fabmesh does not find its modules from PATH or through a link"
"$root/tests/packaging/doc_links_test.sh" /usr/share/doc/fabmesh || die "the package's documentation's links"
[[ $(man -w fabmesh) == /usr/share/man/man1/fabmesh.1* ]] || die "man -w fabmesh does not find the package's page"
(cd "$work" && /usr/bin/python3 -c "import fabmesh; assert fabmesh.__version__ == '$version', fabmesh.__version__") ||
  die "import fabmesh from the installed package"
DEBIAN_FRONTEND=noninteractive $SUDO apt-get remove -y -qq fabmesh || die "apt-get remove fabmesh"
# remove leaves dpkg's record of the package ("config-files"); leave none.
$SUDO dpkg --purge fabmesh >/dev/null || die "dpkg --purge fabmesh"
package_installed=0
[[ ! -e /usr/bin/fabmesh ]] || die "/usr/bin/fabmesh is still there after apt-get remove"
say "the Debian package installs, runs and removes cleanly"
