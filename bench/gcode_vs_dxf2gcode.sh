#!/usr/bin/env bash
# Router programs of the countertop examples: fabmesh (from the exact curves)
# vs dxf2gcode (from fabmesh's DXF of the same design), same tool and cut.
# Both programs run through the CNCjs interpreter (tools/node/gcode-trace.js);
# the moves at the final depth are measured against the EXACT offset of the
# design's exact curves. Method and results: bench/README.md.
#
#   bench/gcode_vs_dxf2gcode.sh [BUILD_DIR]      # default: build (tests on: it needs fabmesh_cnc_bench)
#
# EXAMPLES="countertop_g1 ..." picks the designs; KEEP=1 keeps the scratch folder.
set -euo pipefail
cd "$(dirname "$0")/.."
bench_name=gcode_vs_dxf2gcode
die() { echo "$bench_name: error: $*" >&2; exit 2; }

build=${1:-build}
tool=$build/tests/fabmesh_cnc_bench
[[ -x $tool ]] || die "$tool not found (cmake -S . -B $build && cmake --build $build --target fabmesh_cnc_bench)"
command -v dxf2gcode >/dev/null 2>&1 || die "dxf2gcode not found (Debian: apt-get install -y dxf2gcode, or scripts/install-deps.sh --bench)"
/usr/bin/python3 -c 'import dxf2gcode, PyQt5, configobj, ezdxf' 2>/dev/null \
  || die "Debian's python3 lacks dxf2gcode, PyQt5, configobj or ezdxf (apt-get install -y dxf2gcode python3-ezdxf)"
command -v node >/dev/null 2>&1 || die "node not found"
[[ -d tools/node/node_modules/gcode-toolpath ]] || die "npm package gcode-toolpath missing (scripts/install-deps.sh --test)"

tmp=$(mktemp -d "${TMPDIR:-/tmp}/$bench_name.XXXXXX")
if [[ ${KEEP:-0} == 1 ]]; then echo "keeping $tmp"; else trap 'rm -rf "$tmp"' EXIT; fi
# dxf2gcode's settings and Qt's runtime folder live in a scratch HOME, never the user's.
mkdir -p "$tmp/home" "$tmp/xdg" && chmod 700 "$tmp/xdg"
export HOME=$tmp/home XDG_RUNTIME_DIR=$tmp/xdg QT_QPA_PLATFORM=offscreen

json() { /usr/bin/python3 -c 'import json,sys; j=json.loads(sys.argv[1]); print(eval(sys.argv[2]))' "$1" "$2"; }

printf '| %-27s | %-9s | %6s | %6s | %5s | %6s | %12s | %12s |\n' design tool lines moves arcs "at -z" "max dev (mm)" "clearance-r"
printf '|%s|%s|%s|%s|%s|%s|%s|%s|\n' ----------------------------- ----------- -------- -------- ------- -------- -------------- --------------
status=0
for example in ${EXAMPLES:-countertop_g1 countertop_g2 countertop_asymmetric_line}; do
  design=configs/examples/$example.yaml
  [[ -f $design ]] || die "no design $design"
  depth=$(awk '/^thickness:/ {print $2}' "$design")
  "$tool" program "$design" "$tmp/$example" 0 || die "fabmesh_cnc_bench program failed on $design"
  /usr/bin/python3 bench/dxf2gcode_batch.py "$tmp/$example.dxf" "$tmp/$example.ngc" --tool 12 --depth "$depth" \
    --step 10 --feed 3000 --plunge 600 --spindle 18000 --safe 10 >"$tmp/$example.d2g.log" 2>&1 \
    || { tail -5 "$tmp/$example.d2g.log" >&2; die "dxf2gcode failed on $tmp/$example.dxf"; }
  [[ -s $tmp/$example.ngc ]] || die "dxf2gcode wrote no program for $example"
  for side in fabmesh dxf2gcode; do
    prog=$tmp/$example.nc
    [[ $side == dxf2gcode ]] && prog=$tmp/$example.ngc
    m=$("$tool" measure "$design" "$prog") || die "measuring $prog failed"
    printf '| %-27s | %-9s | %6s | %6s | %5s | %6s | %12.4f | %12.4f |\n' "$example" "$side" \
      "$(json "$m" 'j["lines"]')" "$(json "$m" 'j["moves_at_depth"]')" "$(json "$m" 'j["arcs_at_depth"]')" \
      "$(json "$m" 'j["depth"]')" "$(json "$m" 'j["max_deviation"]')" "$(json "$m" 'j["least_clearance"]')"
    # Both must reach the depth; fabmesh must keep its tolerance (the design's) and leave no unknown codes.
    if [[ $side == fabmesh ]]; then
      tol=$(awk '/^tolerance:/ {print $2}' "$design")
      ok=$(json "$m" "int(j['max_deviation'] <= $tol and j['unknown'] == 0 and abs(j['depth'] - $depth) < 0.01)")
      [[ $ok == 1 ]] || { echo "$bench_name: fabmesh's program for $example is off: $m" >&2; status=1; }
    fi
  done
done
exit $status
