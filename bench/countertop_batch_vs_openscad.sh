#!/usr/bin/env bash
# Countertop variants: `fabmesh batch` against OpenSCAD run once per variant.
#
#   bench/countertop_batch_vs_openscad.sh [path/to/fabmesh]     (default: build-bench/pipeline/fabmesh)
#
# The polygon of countertop_vs_openscad.sh (countertop_polygon.py: a 2400 x
# 650 mm outline of K points with a sink and a cooktop of H points each) is
# extruded at VARIANTS thicknesses from 20 to 40 mm: by one `fabmesh batch`
# (a grid over `thickness`, every variant's STL written, at --jobs 1 and
# --jobs 2), and by OpenSCAD as its users sweep a parameter, one process per
# `-D thickness=...` (OS_VARIANTS of the same thicknesses, one after the
# other, and two at a time for the second core). Each is run ROUNDS times,
# alternated; the figure is the wall time per variant, median (min).
#
# Checks: every fabmesh variant ok with the same triangle count; the first
# and last thickness written by both tools pass `fabmesh check` with the same
# triangle count and volumes within 1e-9 of area x thickness.
#
# Environment: VARIANTS (default 1000), OS_VARIANTS (default 50), ROUNDS
# (default 3), K and H (default 2000 and 200), KEEP=1 keeps the folder.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
fabmesh=${1:-$root/build-bench/pipeline/fabmesh}
variants=${VARIANTS:-1000}
os_variants=${OS_VARIANTS:-50}
rounds=${ROUNDS:-3}
K=${K:-2000}
H=${H:-200}
runs=1
bench_name=countertop_batch_vs_openscad.sh
# shellcheck source=lib.sh
source "$here/lib.sh"
command -v xargs >/dev/null || die "xargs not found"

d=$tmp/k${K}_h$H
mkdir -p "$d"
area=$(python3 "$here/countertop_polygon.py" "$K" "$H" "$d")
cat >"$d/sweep.yaml" <<YAML
design: bench.yaml
name: top_t{thickness}
grid:
  thickness: {from: 20, to: 40, steps: $variants}
YAML
# The thicknesses the batch builds, as it names them; OpenSCAD takes the first OS_VARIANTS.
python3 - "$variants" "$os_variants" >"$d/thicknesses.txt" <<'PY'
import sys
n, m = int(sys.argv[1]), int(sys.argv[2])
values = [20 + 20 * i / (n - 1) for i in range(n)] if n > 1 else [20.0]
for v in values[:m]:
    print(repr(v))
PY

echo "fabmesh:  $fabmesh"
echo "openscad: $(openscad --version 2>&1 | head -n 1)"
echo "machine:  $(nproc) cores, $(uname -srm), load average $(cut -d" " -f1-3 /proc/loadavg)"
echo "work:     $variants fabmesh variants, $os_variants OpenSCAD runs, K=$K H=$H, $rounds rounds"
echo

# seconds CMD...: wall seconds of one run (output discarded); fails if CMD fails.
seconds() {
  local t0 t1
  t0=$(date +%s%N)
  "$@" >/dev/null 2>"$tmp/err" || { cat "$tmp/err" >&2; die "command failed: $*"; }
  t1=$(date +%s%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.6f\n", (b - a) / 1e9}'
}
fm_batch() { rm -rf "$d/fm$1"; "$fabmesh" batch "$d/sweep.yaml" -o "$d/fm$1" --jobs "$1" -q; }
os_one() { openscad -o "$d/os/t_$1.stl" --export-format binstl -D "thickness=$1" "$d/bench.scad"; }
export -f os_one
export d
os_serial() { rm -rf "$d/os"; mkdir -p "$d/os"; while read -r t; do os_one "$t"; done <"$d/thicknesses.txt"; }
os_pair() { rm -rf "$d/os"; mkdir -p "$d/os"; xargs -P 2 -I{} bash -c 'os_one {}' <"$d/thicknesses.txt"; }

fm1=() fm2=() os1=() os2=()
fm_batch 1 >/dev/null  # warm-up: the page cache, the dynamic loader
for ((r = 0; r < rounds; r++)); do
  fm1+=("$(seconds fm_batch 1)")
  os1+=("$(seconds os_serial)")
  fm2+=("$(seconds fm_batch 2)")
  os2+=("$(seconds os_pair)")
done

# Checks: the batch's rows, and both tools' first and last thickness.
status=0
python3 - "$d/fm1/summary.jsonl" "$variants" <<'PY' || status=1
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
bad = [r["name"] for r in rows if r["status"] != "ok" or not r["valid"]]
tris = {r["triangles"] for r in rows}
if len(rows) != int(sys.argv[2]) or bad or len(tris) != 1:
    print(f"fabmesh batch: {len(rows)} rows, not ok: {bad[:5]}, triangle counts {sorted(tris)}")
    sys.exit(1)
PY
first=$(head -n 1 "$d/thicknesses.txt")
last=$(tail -n 1 "$d/thicknesses.txt")
for t in "$first" "$last"; do
  name=$(python3 -c 'import json,sys; t=float(sys.argv[2]); print(next(r["files"][0]["path"] for r in map(json.loads, open(sys.argv[1])) if abs(float(r["overrides"]["thickness"]) - t) < 1e-9))' "$d/fm1/summary.jsonl" "$t")
  [[ $name == /* ]] || name=$d/fm1/$name
  check_outputs "$name" "$d/os/t_$t.stl" "$d"
  fm_tri=$(json "$d/fm_check.json" 'j["triangles"]')
  fm_vol=$(json "$d/fm_check.json" 'repr(j["volume"])')
  # Against area x the thickness as the STL stores it (float32; x and y are on a 2^-10 grid, exact there).
  verr=$(python3 -c 'import struct,sys; a,t,f,o=map(float,sys.argv[1:]); e=a*struct.unpack("f",struct.pack("f",t))[0]
print("%.1e %.1e" % (abs(f-e)/e, abs(o-e)/e))' "$area" "$t" "$fm_vol" "$os_vol")
  echo "thickness $t: fabmesh $fm_tri triangles, OpenSCAD $os_tri; volume errors $verr; $checks"
  [[ $checks == ok && $fm_tri == "$os_tri" ]] || status=1
  awk -v e="$verr" 'BEGIN {split(e, v, " "); exit !(v[1] < 1e-9 && v[2] < 1e-9)}' || status=1
done
echo

python3 - "$variants" "$os_variants" "${fm1[*]}" "${fm2[*]}" "${os1[*]}" "${os2[*]}" <<'PY'
import statistics, sys
n, m = int(sys.argv[1]), int(sys.argv[2])
per = lambda runs, count: [float(x) * 1000 / count for x in runs.split()]
fm1, fm2 = per(sys.argv[3], n), per(sys.argv[4], n)
os1, os2 = per(sys.argv[5], m), per(sys.argv[6], m)
med = statistics.median
print("| ms per variant, median (min) | one at a time | two at a time |")
print("|---|---|---|")
print(f"| fabmesh batch (--jobs 1, 2) | {med(fm1):.2f} ({min(fm1):.2f}) | {med(fm2):.2f} ({min(fm2):.2f}) |")
print(f"| OpenSCAD, one process per -D | {med(os1):.2f} ({min(os1):.2f}) | {med(os2):.2f} ({min(os2):.2f}) |")
print(f"| OpenSCAD / fabmesh | {med(os1) / med(fm1):.1f}x ({min(os1) / min(fm1):.1f}x) | "
      f"{med(os2) / med(fm2):.1f}x ({min(os2) / min(fm2):.1f}x) |")
print(f"\nfabmesh --jobs 2 against OpenSCAD one at a time (as its users sweep): {med(os1) / med(fm2):.1f}x")
PY
exit $status
