#!/usr/bin/env bash
# The libraries only some runs use are loaded only by those runs: neither the
# program nor the library links lib3mf (3MF), OpenCASCADE (STEP), cpp-httplib
# or OpenSSL (the studio), which cost every process start their loading and
# symbol binding; they are loaded with dlopen when a run needs them
# (io/module.h, io/mesh/threemf.cpp). A run that does not need them does not
# map them either. And the loader looks for the libraries the program links
# only in absolute folders: never in the folder it is started from, where
# anyone's library of the same name would be loaded (the padding CMake gives
# a build tree's run path when an install one replaces it did that). The
# same holds for the Python module, when given, imported from an empty folder.
# Usage: lazy_libraries_test.sh FABMESH LIBFABMESH [PYTHON_MODULE]
set -uo pipefail
program=$1 library=$2 module=${3:-}
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
optional='lib3MF|libzip|libcrypto|libssl|libcpp-httplib|libTK'
for binary in "$program" "$library"; do
  linked=$(ldd "$binary" | grep -E "$optional")
  [[ -z $linked ]] || fail "$(basename "$binary") links what it should load on demand: $linked"
done
work=$(mktemp -d "${TMPDIR:-/tmp}/fabmesh-lazy.XXXXXX")
trap 'rm -rf "$work"' EXIT
# What `fabmesh --version` maps (the dynamic loader's own list).
mapped=$(LD_DEBUG=libs "$program" --version 2>&1 >/dev/null | grep -oE "calling init: [^ ]+" | grep -E "$optional")
[[ -z $mapped ]] || fail "fabmesh --version loads: $mapped"
# Where the loader looked, started from an empty folder.
relative=$(cd "$work" && LD_DEBUG=libs "$program" --version 2>&1 >/dev/null | grep -E "trying file=[^/]" | head -n 3)
[[ -z $relative ]] || fail "fabmesh looks for its libraries in the working folder: $relative"
# The Python module's run path: absolute folders or $ORIGIN, no empty entry
# (one would be the working folder), and importing it from an empty folder
# makes the loader try no relative file.
if [[ -n $module ]]; then
  module_runpath=$(readelf -d "$module" | sed -n 's/.*(RUNPATH).*\[\(.*\)\]/\1/p')
  [[ -n $module_runpath ]] || fail "the Python module has no run path (it links libfabmesh)"
  IFS=: read -r -a entries <<<"$module_runpath:"
  for entry in "${entries[@]}"; do
    [[ $entry == /* || $entry == '$ORIGIN'* ]] ||
      fail "the Python module's run path '$module_runpath' has the entry '$entry' (the working folder)"
  done
  [[ $module_runpath != *: && $module_runpath != :* && $module_runpath != *::* ]] ||
    fail "the Python module's run path '$module_runpath' has an empty entry (the working folder)"
  imported=$(cd "$work" && PYTHONPATH=$(dirname "$module") LD_DEBUG=libs python3 -c "import fabmesh" 2>&1)
  grep -q "calling init: .*$(basename "$module")" <<<"$imported" ||
    fail "the Python module was not imported: $(tail -n 3 <<<"$imported")"
  relative=$(grep -E "trying file=[^/]" <<<"$imported" | head -n 3)
  [[ -z $relative ]] || fail "importing the Python module looks in the working folder: $relative"
fi
# And a run that writes 3MF and STEP loads both.
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
LD_DEBUG=libs "$program" run "$source_dir/configs/examples/vessel_golden_solid.yaml" --export-format 3mf \
  -o "$work/3mf/" -q 2>"$work/3mf.log" >/dev/null || fail "the 3MF run failed: $(tail -n 3 "$work/3mf.log")"
grep -q "calling init: .*lib3MF" "$work/3mf.log" || fail "a 3MF run did not load lib3mf"
LD_DEBUG=libs "$program" run "$source_dir/configs/examples/vessel_golden_solid.yaml" --export-format step \
  -o "$work/step/" -q 2>"$work/step.log" >/dev/null || fail "the STEP run failed: $(tail -n 3 "$work/step.log")"
grep -q "calling init: .*fabmesh-step.so" "$work/step.log" || fail "a STEP run did not load the STEP module"
if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "lib3mf, OpenCASCADE and cpp-httplib are loaded only by the runs that use them"
