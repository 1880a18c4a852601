#!/usr/bin/env bash
# fabmesh vs OpenSCAD: revolve the same polyline vessel profile into a binary STL.
#
#   bench/vessel_vs_openscad.sh [path/to/fabmesh]     (default: build-bench/pipeline/fabmesh)
#
# The profile is the golden quasi-cubic B-spline of docs/math/curves.md section 2, scaled
# by 30 to mm, sampled as K points rounded to a 2^-10 mm grid (bench/vessel_exact_volume.py),
# revolved in N angular steps: 2*K*N triangles for both tools. Each size times
# whole processes (hyperfine if installed, else a loop), measures peak RSS with
# /usr/bin/time -f %M, times `cp` of the STL as the floor, checks both meshes
# with `fabmesh check`, and compares volumes with the exact smooth volume.
#
# Environment: RUNS (timed runs per command, default 10), SIZES (space-separated
# "N:K" pairs, default "100:50 400:250 840:417" = 1e4, 2e5, 7e5 triangles),
# KEEP=1 keeps the temporary folder, NO_HYPERFINE=1 times with a plain loop.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
fabmesh=${1:-$root/build-bench/pipeline/fabmesh}
runs=${RUNS:-10}
sizes=${SIZES:-"100:50 400:250 840:417"}
helper=$here/vessel_exact_volume.py

bench_name=vessel_vs_openscad.sh
# shellcheck source=lib.sh
source "$here/lib.sh"

python3 "$helper" selftest >/dev/null || die "vessel_exact_volume.py selftest failed"
vexact=$(python3 "$helper" volume)

echo "fabmesh:  $fabmesh"
echo "openscad: $(openscad --version 2>&1 | head -n 1)"
echo "timing:   $([[ $have_hyperfine == 1 ]] && hyperfine --version || echo 'date loop') ($runs runs after 1 warm-up; peak RSS from /usr/bin/time -f %M)"
echo "machine:  $(nproc) cores, $(uname -srm), load average $(cut -d" " -f1-3 /proc/loadavg)"
echo "exact volume of the smooth golden profile (scale 30): $vexact mm^3"
echo

rows=()
timings=()
status=0
for size in $sizes; do
  N=${size%%:*}; K=${size##*:}
  d=$tmp/n${N}_k$K; mkdir -p "$d/fm" "$d/os"
  python3 "$helper" sample "$K" > "$d/profile.txt"    # rim (top) to base, 2^-10 mm grid

  # Tolerance that makes fabmesh pick N: N = ceil(pi / acos(1 - 0.9 t / R)); aim at N - 0.5.
  tol=$(awk -v N="$N" 'BEGIN {R = 0} {if ($1 > R) R = $1} END {pi = atan2(0, -1); printf "%.12g", R * (1 - cos(pi / (N - 0.5))) / 0.9}' "$d/profile.txt")

  awk -v tol="$tol" 'BEGIN {
      print "name: bench"; print "kind: vessel"; print "units: mm"; print "tolerance: " tol
      print "outputs: [stl]"; print "max_triangles: 50000000"
      print "profile:"; print "  family: tbezier"; print "  segments:" }
    NR == 1 {r = $1; z = $2; next}
    NR == 2 {printf "    - line: {from: [%s, %s], to: [%s, %s]}\n", r, z, $1, $2; next}
    {printf "    - line: {to: [%s, %s]}\n", $1, $2}
    END {print "body:"; print "  mode: solid"}' "$d/profile.txt" > "$d/bench.yaml"

  # One run for the report (N actually chosen, triangles, volume, timings) and peak memory.
  fm_cmd=("$fabmesh" run "$d/bench.yaml" -o "$d/fm" --json)
  "${fm_cmd[@]}" > "$d/fm.json" || die "fabmesh run failed on $d/bench.yaml"
  fm_n=$(json "$d/fm.json" 'j["build"]["angular_segments"]')
  [[ $fm_n == "$N" ]] || echo "note: asked for N=$N, fabmesh chose N=$fm_n (OpenSCAD uses $fm_n)" >&2
  fm_stl=$(json "$d/fm.json" 'j["outputs"][0]')
  fm_tri=$(json "$d/fm.json" 'j["triangles"]')
  fm_vol=$(json "$d/fm.json" 'repr(j["volume"])')
  timings+=("N=$fm_n K=$K triangles=$fm_tri: $(json "$d/fm.json" '", ".join("%s %.1f" % kv for kv in j["timings_ms"].items())')")
  fm_kb=$(peak_kb "${fm_cmd[@]}")

  # Same section polygon for OpenSCAD: profile bottom to top, then (0, z_top), (0, z_bottom).
  tac "$d/profile.txt" | awk -v N="$fm_n" '
    NR == 1 {zb = $2} {zt = $2; pts = pts sprintf("[%s,%s],", $1, $2)}
    END {printf "rotate_extrude($fn=%d) polygon(points=[%s[0,%s],[0,%s]]);\n", N, pts, zt, zb}' > "$d/bench.scad"
  os_cmd=(openscad -o "$d/os/out.stl" --export-format binstl "$d/bench.scad")
  os_kb=$(peak_kb "${os_cmd[@]}")

  read -r fm_ms fm_min < <(time_ms "fm_$N" "${fm_cmd[@]}")
  read -r os_ms os_min < <(time_ms "os_$N" "${os_cmd[@]}")
  read -r cp_ms cp_min < <(time_ms "cp_$N" cp "$fm_stl" "$d/floor.stl")

  check_outputs "$fm_stl" "$d/os/out.stl" "$d"
  if ! awk -v a="$fm_tri" -v b="$os_tri" 'BEGIN {d = a - b; if (d < 0) d = -d; exit !(d <= 0.01 * a)}'; then
    checks="$checks,triangles-differ"; status=1
  fi
  checks=${checks#ok,}

  rows+=("$(awk -v tgt="$((2 * K * N))" -v n="$fm_n" -v k="$K" -v ft="$fm_tri" -v ot="$os_tri" \
      -v fms="$fm_ms" -v oms="$os_ms" -v fmin="$fm_min" -v omin="$os_min" -v fkb="$fm_kb" -v okb="$os_kb" -v cms="$cp_ms" \
      -v fv="$fm_vol" -v ov="$os_vol" -v ve="$vexact" -v ck="$checks" 'BEGIN {
    printf "| %7d | %4d | %4d | %8d | %8d | %7.1f (%7.1f) | %7.1f (%7.1f) | %5.2f (%5.2f) | %7.1f | %7.1f | %6.2f | %+.3e | %+.3e | %s |",
      tgt, n, k, ft, ot, fms, fmin, oms, omin, oms / fms, omin / fmin, fkb / 1024, okb / 1024, cms, (fv - ve) / ve, (ov - ve) / ve, ck }')")
done

echo "| target  |    N |    K | fm tris  | os tris  | fm ms med (min)   | os ms med (min)   | os/fm med (min) | fm MiB  | os MiB  | cp ms  | fm vol err | os vol err | checks |"
echo "|---------|------|------|----------|----------|-------------------|-------------------|-----------------|---------|---------|--------|------------|------------|--------|"
printf '%s\n' "${rows[@]}"
echo
echo "fm = fabmesh run --json (build + validate + binary STL), os = openscad --export-format binstl;"
echo "times are wall ms of whole processes, median (min) of $runs runs; MiB = peak RSS; cp ms = median cp of"
echo "fabmesh's STL to a new file (the write floor; no fsync, while fabmesh fsyncs its output and OpenSCAD does not);"
echo "vol err = (mesh volume - exact smooth volume) / exact (fabmesh: its JSON; OpenSCAD: fabmesh check)."
echo
echo "fabmesh timings_ms (one run):"
printf '  %s\n' "${timings[@]}"
exit $status
