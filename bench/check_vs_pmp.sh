#!/usr/bin/env bash
# Mesh check of a closed 1e6-triangle torus STL, in one run: `fabmesh check`
# against `admesh` (no self-intersection test) and against `pmp_check`
# (CGAL Polygon Mesh Processing's own checks, bench/pmp_check.cpp), whole
# processes and stage by stage, with the ratios.
#
#   bench/check_vs_pmp.sh [FABMESH] [PMP_CHECK]
#       defaults: build-bench/pipeline/fabmesh, build-bench/bench/pmp_check
#   environment: NU, NV (torus resolution, default 1000 x 500 = 1e6
#   triangles), RUNS (default 5), KEEP=1, NO_HYPERFINE=1
#
# Build both in Release first:
#   cmake -S . -B build-bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DFABMESH_BUILD_TESTS=OFF -DFABMESH_BUILD_BENCH=ON
#   cmake --build build-bench --target fabmesh pmp_check
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bench_name=check_vs_pmp.sh
fabmesh=${1:-$here/../build-bench/pipeline/fabmesh}
pmp=${2:-$here/../build-bench/bench/pmp_check}
runs=${RUNS:-5}
peer_tools=admesh
# shellcheck source=bench/lib.sh
source "$here/lib.sh"
[[ -x $pmp ]] || die "pmp_check not found at '$pmp' (configure with -DFABMESH_BUILD_BENCH=ON and build the pmp_check target)"
nu=${NU:-1000}
nv=${NV:-500}

stl=$tmp/torus.stl
python3 "$here/make_torus_stl.py" "$stl" "$nu" "$nv"
echo "input: $((2 * nu * nv)) triangles, $(stat -c %s "$stl") bytes; $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"

# Verdicts: all three must accept the torus (admesh: exit 0 and no flips or holes).
"$fabmesh" check --json "$stl" > "$tmp/fm.json" || die "fabmesh check rejected the torus"
"$pmp" "$stl" > "$tmp/pmp.json" || die "pmp_check rejected the torus"
admesh "$stl" > "$tmp/admesh.txt" || die "admesh failed on the torus"
echo "fabmesh: valid=$(json "$tmp/fm.json" 'j["valid"]') genus=$(json "$tmp/fm.json" 'j["genus"]') volume=$(json "$tmp/fm.json" 'j["volume"]')"
echo "pmp:     valid=$(json "$tmp/pmp.json" 'j["valid"]') self_intersecting=$(json "$tmp/pmp.json" 'j["self_intersecting"]') volume=$(json "$tmp/pmp.json" 'j["volume"]')"
echo "admesh:  $(grep -E 'Number of parts|Volume' "$tmp/admesh.txt" | tr -s ' ' | paste -sd ';')"

# Stage timings, alternating the two tools RUNS times; medians.
for ((r = 0; r < runs; r++)); do
  "$fabmesh" check --json "$stl" > "$tmp/fm_$r.json"
  "$pmp" "$stl" > "$tmp/pmp_$r.json"
done
stages() {  # stages PREFIX: "stage median_ms" lines over the runs
  python3 - "$tmp" "$1" "$runs" <<'PY'
import json, statistics, sys
tmp, prefix, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
def report(path):  # fabmesh check --json prints an array of one item per file
    j = json.load(open(path))
    return j[0] if isinstance(j, list) else j
rows = [report("%s/%s_%d.json" % (tmp, prefix, r))["timings_ms"] for r in range(runs)]
for stage in rows[0]:
    print(stage, "%.1f" % statistics.median(row[stage] for row in rows))
PY
}
stages fm > "$tmp/fm_stages.txt"
stages pmp > "$tmp/pmp_stages.txt"
echo "fabmesh check stages (median ms): $(paste -sd ' ' "$tmp/fm_stages.txt" | sed 's/\([0-9]\) /\1, /g')"
echo "pmp_check stages (median ms):     $(paste -sd ' ' "$tmp/pmp_stages.txt" | sed 's/\([0-9]\) /\1, /g')"
fm_si=$(awk '$1 == "self_intersection" {print $2}' "$tmp/fm_stages.txt")
pmp_si=$(awk '$1 == "self_intersection" {print $2}' "$tmp/pmp_stages.txt")

# Whole processes.
read -r fm_med fm_min < <(time_ms fabmesh "$fabmesh" check "$stl")
read -r ad_med ad_min < <(time_ms admesh admesh "$stl")
read -r pmp_med pmp_min < <(time_ms pmp "$pmp" "$stl")
printf '\n%-16s %12s %12s\n' tool "ms median" "ms min"
printf '%-16s %12.1f %12.1f\n' "fabmesh check" "$fm_med" "$fm_min" admesh "$ad_med" "$ad_min" pmp_check "$pmp_med" "$pmp_min"
python3 - "$fm_med" "$ad_med" "$pmp_med" "$fm_si" "$pmp_si" <<'PY'
import sys
fm, ad, pmp, fm_si, pmp_si = map(float, sys.argv[1:])
print("\nfabmesh check / admesh (whole process, median): %.2f  (aim: <= 3)" % (fm / ad))
print("pmp_check / fabmesh check (whole process, median): %.2f" % (pmp / fm))
print("self-intersection, pmp / fabmesh (stage medians): %.1f / %.1f ms = %.1f  (aim: >= 4)" % (pmp_si, fm_si, pmp_si / fm_si))
PY
