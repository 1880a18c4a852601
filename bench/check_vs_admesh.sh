#!/usr/bin/env bash
# Whole-command comparison: `fabmesh check` against `admesh` on a closed
# 1e6-triangle binary STL (a finely tessellated torus), plus fabmesh's own
# per-stage timings (self-intersection among them).
# Needs: a Release fabmesh (default build-bench/pipeline/fabmesh), python3, admesh,
# and optionally hyperfine (scripts/install-deps.sh --bench installs them).
# Usage: bench/check_vs_admesh.sh [FABMESH_BINARY] [NU NV]
# (bench/check_vs_pmp.sh adds CGAL PMP and per-stage ratios.)
# Note what is compared: admesh reads, welds (exact), checks edges/normals and
# computes the volume; fabmesh check also runs an exact self-intersection test.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
fabmesh="${1:-$here/../build-bench/pipeline/fabmesh}"
nu="${2:-1000}"
nv="${3:-500}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
stl="$work/torus.stl"

python3 "$here/make_torus_stl.py" "$stl" "$nu" "$nv"
echo "input: $((2 * nu * nv)) triangles, $(stat -c %s "$stl") bytes"

"$fabmesh" check --json "$stl" > "$work/report.json"
python3 - "$work/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))[0]  # one item per file
print("fabmesh verdict: valid=%s genus=%s triangles=%d welded=%d" % (r["valid"], r["genus"], r["triangles"], r["welded_vertices"]))
print("fabmesh stages (ms): " + ", ".join("%s %.0f" % kv for kv in r["timings_ms"].items()))
PY

if command -v hyperfine > /dev/null; then
  hyperfine --warmup 1 --runs 5 \
    -n "fabmesh check" "'$fabmesh' check '$stl'" \
    -n "admesh" "admesh '$stl'"
else
  for cmd in "$fabmesh check $stl" "admesh $stl"; do
    start=$(date +%s.%N)
    $cmd > /dev/null
    end=$(date +%s.%N)
    echo "$cmd: $(echo "$end - $start" | bc) s"
  done
fi
