#!/usr/bin/env bash
# fabmesh vs OpenSCAD: extrude the same polygon with holes into a binary STL slab.
#
#   bench/countertop_vs_openscad.sh [path/to/fabmesh]     (default: build-bench/pipeline/fabmesh)
#
# The outline is a 2400 x 650 mm rounded rectangle (corner radius 100) sampled
# as K points evenly along its length, with a sink (rounded rectangle) and a
# cooktop (ellipse) of H points each, all rounded to a 2^-10 mm grid so both
# tools read exactly the same coordinates. fabmesh gets each loop as a
# `polyline` read from a CSV file (a line is sampled exactly), OpenSCAD as
# linear_extrude(height = 30) polygon(points, paths). Each size times whole
# processes (hyperfine if installed, else a loop), measures peak RSS with
# /usr/bin/time -f %M, checks both STLs with `fabmesh check` and compares the
# volumes with the polygon's exact area x 30.
#
# Environment: RUNS (timed runs per command, default 10), SIZES (space-separated
# "K:H" pairs, default "2000:200 200000:2000"), KEEP=1 keeps the temporary
# folder, NO_HYPERFINE=1 times with a plain loop.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
fabmesh=${1:-$root/build-bench/pipeline/fabmesh}
runs=${RUNS:-10}
sizes=${SIZES:-"2000:200 200000:2000"}

bench_name=countertop_vs_openscad.sh
# shellcheck source=lib.sh
source "$here/lib.sh"

# make_inputs K H DIR: writes DIR/bench.yaml, DIR/bench.scad and prints the exact polygon area (mm^2).
make_inputs() { python3 "$here/countertop_polygon.py" "$1" "$2" "$3"; }

echo "fabmesh:  $fabmesh"
echo "openscad: $(openscad --version 2>&1 | head -n 1)"
echo "timing:   $([[ $have_hyperfine == 1 ]] && hyperfine --version || echo 'date loop') ($runs runs after 1 warm-up; peak RSS from /usr/bin/time -f %M)"
echo "machine:  $(nproc) cores, $(uname -srm), load average $(cut -d" " -f1-3 /proc/loadavg)"
echo

rows=()
timings=()
status=0
for size in $sizes; do
  K=${size%%:*}; H=${size##*:}
  d=$tmp/k${K}_h$H; mkdir -p "$d/fm" "$d/os"
  area=$(make_inputs "$K" "$H" "$d")
  vexact=$(awk -v a="$area" 'BEGIN {printf "%.17g", a * 30}')

  fm_cmd=("$fabmesh" run "$d/bench.yaml" -o "$d/fm" --json)
  "${fm_cmd[@]}" > "$d/fm.json" || die "fabmesh run failed on $d/bench.yaml"
  fm_stl=$(json "$d/fm.json" 'j["outputs"][0]')
  fm_tri=$(json "$d/fm.json" 'j["triangles"]')
  fm_vol=$(json "$d/fm.json" 'repr(j["volume"])')
  fm_pts=$(json "$d/fm.json" 'j["build"]["outline_points"]')
  [[ $fm_pts == "$K" ]] || { echo "note: fabmesh sampled $fm_pts outline points, not $K" >&2; status=1; }
  timings+=("K=$K H=$H triangles=$fm_tri: $(json "$d/fm.json" '", ".join("%s %.1f" % kv for kv in j["timings_ms"].items())')")
  fm_kb=$(peak_kb "${fm_cmd[@]}")

  os_cmd=(openscad -o "$d/os/out.stl" --export-format binstl "$d/bench.scad")
  os_kb=$(peak_kb "${os_cmd[@]}")

  read -r fm_ms fm_min < <(time_ms "fm_$K" "${fm_cmd[@]}")
  read -r os_ms os_min < <(time_ms "os_$K" "${os_cmd[@]}")

  check_outputs "$fm_stl" "$d/os/out.stl" "$d"
  checks=${checks#ok,}

  rows+=("$(awk -v k="$K" -v h="$H" -v ft="$fm_tri" -v ot="$os_tri" -v fms="$fm_ms" -v oms="$os_ms" -v fmin="$fm_min" \
      -v omin="$os_min" -v fkb="$fm_kb" -v okb="$os_kb" -v fv="$fm_vol" -v ov="$os_vol" -v ve="$vexact" -v ck="$checks" 'BEGIN {
    printf "| %6d | %4d | %7d | %7d | %8.1f (%8.1f) | %8.1f (%8.1f) | %6.2f (%6.2f) | %6.1f | %6.1f | %+.2e | %+.2e | %s |",
      k, h, ft, ot, fms, fmin, oms, omin, oms / fms, omin / fmin, fkb / 1024, okb / 1024, (fv - ve) / ve, (ov - ve) / ve, ck }')")
done

echo "|      K |    H | fm tris | os tris | fm ms med (min)     | os ms med (min)     | os/fm med (min) | fm MiB | os MiB | fm vol err | os vol err | checks |"
echo "|--------|------|---------|---------|---------------------|---------------------|-----------------|--------|--------|------------|------------|--------|"
printf '%s\n' "${rows[@]}"
echo
echo "K = outline points, H = points of each of the two holes; fm = fabmesh run --json (parse, region checks,"
echo "CDT, slab, validation, binary STL with fsync), os = openscad --export-format binstl; wall ms of whole"
echo "processes, median (min) of $runs runs; vol err = (volume - exact polygon area x 30) / exact."
echo
echo "fabmesh timings_ms (one run):"
printf '  %s\n' "${timings[@]}"
exit $status
