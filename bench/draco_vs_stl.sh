#!/usr/bin/env bash
# Whole-process cost of the Draco output against the STL output (issue 12):
# the golden shell vessel at ~1.9e5 triangles, `outputs: [stl]` vs
# `outputs: [stl, drc]`, for each fabmesh binary given (e.g. a baseline and
# the current build, timed in the same run), plus the median `timings_ms`
# of RUNS runs (NO_HYPERFINE=1: only these) and draco_encoder (Debian draco-tools) on the same STL.
#
#   bench/draco_vs_stl.sh [FABMESH ...]     # default: build-bench/pipeline/fabmesh
#   RUNS=10 TOLERANCE=0.00043 bench/draco_vs_stl.sh /tmp/fabmesh-main build-bench/pipeline/fabmesh
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
runs=${RUNS:-10}
tolerance=${TOLERANCE:-0.00043}
design=$here/configs/examples/vessel_golden_shell.yaml
[ $# -gt 0 ] || set -- "$here/build-bench/pipeline/fabmesh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

commands=()
for bin in "$@"; do
  for outputs in "[stl]" "[stl,drc]"; do
    commands+=("$bin run $design -D tolerance=$tolerance -D outputs=$outputs -o $work/out/")
  done
done
if [ -z "${NO_HYPERFINE:-}" ] && command -v hyperfine >/dev/null; then
  hyperfine -N --warmup 1 --runs "$runs" "${commands[@]}"
fi

# Median stage timings of each binary with both outputs.
for bin in "$@"; do
  for i in $(seq "$runs"); do
    "$bin" run "$design" -D tolerance="$tolerance" -D "outputs=[stl,drc]" -o "$work/out/" --json
  done | python3 -c '
import json, statistics, sys
text = sys.stdin.read()
decoder, reports, i = json.JSONDecoder(), [], 0
while i < len(text):
    if text[i].isspace(): i += 1; continue
    value, i = decoder.raw_decode(text, i)
    reports += value
keys = ["build", "validate", "encode_stl", "encode_drc", "write"]
print(sys.argv[1], reports[0]["triangles"], "triangles; median ms:",
      ", ".join(k + " %.1f" % statistics.median(r["timings_ms"][k] for r in reports) for k in keys))
' "$bin"
done

# draco_encoder on the same mesh, for reference (its default 11 bits, and 17).
if command -v draco_encoder >/dev/null; then
  "$1" run "$design" -D tolerance="$tolerance" -D "outputs=[stl]" -o "$work/out/" >/dev/null
  for qp in 11 17; do
    start=$(date +%s.%N)
    draco_encoder -i "$work/out/vessel_golden_shell.stl" -o "$work/ref.drc" -qp "$qp" >/dev/null
    end=$(date +%s.%N)
    echo "draco_encoder -qp $qp: $(python3 -c "print(f'{($end - $start) * 1000:.0f}')") ms, $(stat -c %s "$work/ref.drc") bytes"
  done
fi
