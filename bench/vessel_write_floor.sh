#!/usr/bin/env bash
# A large vessel against the write floor: fabmesh run (build + validate + binary STL with
# fsync) versus `dd conv=fsync` of the same number of bytes, alternated, with peak RSS.
#
#   bench/vessel_write_floor.sh [FABMESH...]     (default: build-bench/pipeline/fabmesh)
#
# Several binaries (e.g. before and after a change) are timed in the same rounds.
# Environment: N and K (angular steps and profile points, default 1475 and 2950:
# 2*K*N = 8.7e6 triangles, a 435 MB STL; N above ~1500 leaves too little of the
# tolerance for float32 STL and the output is skipped), ROUNDS (default 5), KEEP=1.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
[[ $# -gt 0 ]] || set -- "$root/build-bench/pipeline/fabmesh"
fabmesh=$1
runs=1
N=${N:-1475}; K=${K:-2950}; rounds=${ROUNDS:-5}
bench_name=vessel_write_floor.sh
peer_tools=dd
# shellcheck source=lib.sh
source "$here/lib.sh"

python3 "$here/vessel_exact_volume.py" sample "$K" > "$tmp/profile.txt"
tol=$(awk -v N="$N" 'BEGIN {R = 0} {if ($1 > R) R = $1} END {pi = atan2(0, -1); printf "%.12g", R * (1 - cos(pi / (N - 0.5))) / 0.9}' "$tmp/profile.txt")
awk -v tol="$tol" 'BEGIN {
    print "name: bench"; print "kind: vessel"; print "units: mm"; print "tolerance: " tol
    print "outputs: [stl]"; print "max_triangles: 50000000"; print "on_output_error: fail"
    print "profile:"; print "  family: tbezier"; print "  segments:" }
  NR == 1 {r = $1; z = $2; next}
  NR == 2 {printf "    - line: {from: [%s, %s], to: [%s, %s]}\n", r, z, $1, $2; next}
  {printf "    - line: {to: [%s, %s]}\n", $1, $2}
  END {print "body:"; print "  mode: solid"}' "$tmp/profile.txt" > "$tmp/bench.yaml"

echo "machine: $(nproc) cores, $(uname -srm), load average $(cut -d" " -f1-3 /proc/loadavg)"
echo "vessel N=$N K=$K, $rounds rounds; each round runs every binary once, then dd"
declare -A wall rss stages
floor=()
for ((r = 0; r < rounds; r++)); do
  for b in "$@"; do
    mkdir -p "$tmp/out"
    /usr/bin/time -f "%e %M" -o "$tmp/t.txt" "$b" run "$tmp/bench.yaml" -o "$tmp/out" --json > "$tmp/r.json" \
      || die "fabmesh failed: $b"
    read -r s kb < "$tmp/t.txt"
    wall[$b]+="$s "; rss[$b]+="$kb "
    stages[$b]=$(json "$tmp/r.json" '", ".join("%s %.0f" % kv for kv in j["timings_ms"].items() if "." not in kv[0])')
  done
  stl=$tmp/out/bench.stl
  t0=$(date +%s%N)
  dd if="$stl" of="$tmp/floor.stl" bs=4M conv=fsync 2>/dev/null
  t1=$(date +%s%N)
  floor+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f", (b - a) / 1e9}')")
  rm -f "$tmp/floor.stl"
done
med() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}'; }
bytes=$(stat -c %s "$tmp/out/bench.stl")
fl=$(printf '%s ' "${floor[@]}" | med)
echo "STL: $bytes bytes, $(json "$tmp/r.json" 'j["triangles"]') triangles"
echo
echo "| binary | wall s med (all) | peak MiB med | - dd floor s | stages ms (last run) |"
echo "|---|---|---|---|---|"
for b in "$@"; do
  m=$(echo "${wall[$b]}" | med); k=$(echo "${rss[$b]}" | med)
  printf '| %s | %.2f (%s) | %.0f | %+.2f | %s |\n' "$b" "$m" "${wall[$b]% }" "$(awk -v k="$k" 'BEGIN {print k / 1024}')" \
    "$(awk -v a="$m" -v b="$fl" 'BEGIN {print a - b}')" "${stages[$b]}"
done
echo "| dd if=STL bs=4M conv=fsync | $fl (${floor[*]}) | | | |"
