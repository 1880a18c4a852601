#!/usr/bin/env bash
# Mesh repair: `fabmesh repair` against admesh and a CGAL PMP repair pipeline
# (bench/repair_pmp.cpp) on the broken meshes of tests/data/repair-corpus and
# the STL files of OpenCASCADE's sample data (Debian's occt-misc, read in
# place). For each tool: files made valid (judged by `fabmesh check` of the
# tool's output), the median and worst distance to the input relative to its
# bounding box diagonal (the proven bound of bench/repair_distance.cpp),
# components kept, and time.
#
#   bench/repair_vs_peers.sh [FABMESH] [REPAIR_PMP] [REPAIR_DISTANCE]
#       defaults: build-bench/pipeline/fabmesh, build-bench/bench/repair_pmp, build-bench/bench/repair_distance
#   environment: FILES (inputs, default the corpus and OCCT's STLs), KEEP=1,
#                TOOL_SECONDS (each tool's time on one file, default 120: a tool
#                stopped there wrote nothing valid and is listed as timed out)
#
# Build in Release first:
#   cmake -S . -B build-bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DFABMESH_BUILD_TESTS=OFF -DFABMESH_BUILD_BENCH=ON
#   cmake --build build-bench --target fabmesh repair_pmp repair_distance
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bench_name=repair_vs_peers.sh
fabmesh=${1:-$here/../build-bench/pipeline/fabmesh}
pmp=${2:-$here/../build-bench/bench/repair_pmp}
distance=${3:-$here/../build-bench/bench/repair_distance}
runs=1
limit=${TOOL_SECONDS:-120}
peer_tools=admesh
# shellcheck source=bench/lib.sh
source "$here/lib.sh"
[[ -x $pmp ]] || die "repair_pmp not found at '$pmp' (configure with -DFABMESH_BUILD_BENCH=ON)"
[[ -x $distance ]] || die "repair_distance not found at '$distance' (configure with -DFABMESH_BUILD_BENCH=ON)"

if [[ -z ${FILES:-} ]]; then
  FILES=$(ls "$here"/../tests/data/repair-corpus/*.{stl,obj} /usr/share/opencascade/data/stl/*.stl 2>/dev/null)
fi

ms_now() { date +%s%N | cut -b1-13; }
# components FILE: the connected components `fabmesh check` counts (summed over a file's objects).
components() {
  { "$fabmesh" check --json "$1" 2>/dev/null || true; } | python3 -c '
import json, sys
j = json.load(sys.stdin)[0]
print(j["components"] if "components" in j else sum(o["components"] for o in j.get("objects", [])))' 2>/dev/null || echo 0
}
rows=$tmp/rows.tsv
: > "$rows"
for file in $FILES; do
  stem=$(basename "${file%.*}")
  # admesh reads STL only: OBJ inputs go to it as the same triangles in binary STL.
  stl=$file
  if [[ ${file,,} != *.stl ]]; then
    stl=$tmp/$stem.in.stl
    python3 - "$file" "$stl" <<'PY'
import struct, sys
v, f = [], []
for line in open(sys.argv[1]):
    p = line.split()
    if p and p[0] == "v": v.append(tuple(map(float, p[1:4])))
    if p and p[0] == "f": f.append([int(x.split("/")[0]) - 1 for x in p[1:]])
with open(sys.argv[2], "wb") as out:
    out.write(b" " * 80 + struct.pack("<I", sum(len(x) - 2 for x in f)))
    for poly in f:
        for k in range(1, len(poly) - 1):
            out.write(struct.pack("<3f", 0, 0, 0))
            for i in (poly[0], poly[k], poly[k + 1]):
                out.write(struct.pack("<3f", *v[i]))
            out.write(b"\0\0")
PY
  fi
  components_in=$(components "$file")
  for tool in fabmesh admesh pmp; do
    status=0
    case $tool in
      fabmesh) out=$tmp/$stem.fm.3mf; start=$(ms_now)
        timeout "$limit" "$fabmesh" repair "$file" -o "$out" >/dev/null 2>&1 || status=$? ;;
      admesh) out=$tmp/$stem.ad.stl; start=$(ms_now)
        timeout "$limit" admesh --exact --nearby --remove-unconnected --fill-holes --normal-directions "$stl" \
          -b "$out" >/dev/null 2>&1 || status=$? ;;
      pmp) out=$tmp/$stem.pmp.off; start=$(ms_now); timeout "$limit" "$pmp" "$file" "$out" >/dev/null 2>&1 || status=$? ;;
    esac
    ms=$(( $(ms_now) - start ))
    valid=0 components=0 rel=nan
    if [[ $status -eq 124 ]]; then
      ms="timeout"  # stopped at the limit: whatever it left is not its answer
    elif [[ -s $out ]]; then
      "$fabmesh" check "$out" >/dev/null 2>&1 && valid=1
      components=$(components "$out")
      rel=$("$distance" "$file" "$out" 2>/dev/null | python3 -c 'import json,sys; j=json.load(sys.stdin); print(j["bound"] / j["diagonal"])' || echo nan)
    fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$stem" "$tool" "$valid" "$components_in" "$components" "$rel" "$ms" >> "$rows"
  done
done

python3 - "$rows" <<'PY'
import math, statistics, sys
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1])]
files = sorted({r[0] for r in rows})
print("%-28s %-8s %-6s %-12s %-12s %-8s" % ("file", "tool", "valid", "components", "rel. dist.", "ms"))
for f in files:
    for r in rows:
        if r[0] == f:
            print("%-28s %-8s %-6s %-12s %-12s %-8s" % (f, r[1], "yes" if r[2] == "1" else "no", r[3] + " -> " + r[4],
                                                         "%.2e" % float(r[5]) if r[5] != "nan" else "-", r[6]))
print()
print("%-8s %-12s %-12s %-12s %-16s %-10s" % ("tool", "made valid", "median rel.", "worst rel.", "components kept", "total ms"))
for tool in ("fabmesh", "admesh", "pmp"):
    mine = [r for r in rows if r[1] == tool]
    valid = [r for r in mine if r[2] == "1"]
    rel = [float(r[5]) for r in valid if r[5] != "nan" and not math.isnan(float(r[5]))]
    kept = sum(min(int(r[4]), int(r[3])) for r in valid)
    total_in = sum(int(r[3]) for r in mine)
    print("%-8s %-12s %-12s %-12s %-16s %-10d" % (tool, "%d/%d" % (len(valid), len(mine)),
          "%.2e" % statistics.median(rel) if rel else "-", "%.2e" % max(rel) if rel else "-",
          "%d/%d" % (kept, total_in), sum(int(r[6]) for r in mine if r[6] != "timeout")))
    stopped = [r[0] for r in mine if r[6] == "timeout"]
    if stopped:
        print("%-8s stopped at the time limit on: %s" % (tool, ", ".join(stopped)))
PY
