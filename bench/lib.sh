# Shared by the peer benchmarks: tool checks, a scratch folder and timing.
# Source it after setting: bench_name (for messages and the temp folder),
# fabmesh (binary path), runs (timed runs per command) and optionally
# peer_tools (the peer programs that must be on PATH; default openscad).
# Provides: die, json FILE EXPR, peak_kb CMD..., time_ms NAME CMD..., check_outputs, $tmp.

die() { echo "$bench_name: error: $*" >&2; exit 2; }
[[ -x $fabmesh ]] || die "fabmesh not found or not executable at '$fabmesh' (build it: cmake -S . -B build-bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DFABMESH_BUILD_TESTS=OFF && cmake --build build-bench --target fabmesh)"
fabmesh=$(cd "$(dirname "$fabmesh")" && pwd)/$(basename "$fabmesh")
for tool in ${peer_tools:-openscad}; do
  command -v "$tool" >/dev/null 2>&1 || die "$tool not found on PATH (Debian: apt-get install -y $tool)"
done
[[ -x /usr/bin/time ]] || die "/usr/bin/time (GNU time) not found (Debian: apt-get install -y time)"
command -v python3 >/dev/null 2>&1 || die "python3 not found"
have_hyperfine=0
[[ ${NO_HYPERFINE:-0} == 1 ]] || ! command -v hyperfine >/dev/null 2>&1 || have_hyperfine=1

tmp=$(mktemp -d "${TMPDIR:-/tmp}/${bench_name%.sh}.XXXXXX")
if [[ ${KEEP:-0} == 1 ]]; then echo "keeping $tmp"; else trap 'rm -rf "$tmp"' EXIT; fi

# json FILE PYTHON-EXPR: evaluates EXPR with the parsed JSON as `j`.
json() { python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); j=j[0] if isinstance(j,list) else j; print(eval(sys.argv[2]))' "$1" "$2"; }

# peak_kb CMD...: peak RSS (KB) of one run of CMD (output discarded); fails if CMD fails.
peak_kb() {
  local f=$tmp/peak.txt
  if ! /usr/bin/time -f %M -o "$f" "$@" >/dev/null 2>"$tmp/peak.err"; then
    cat "$tmp/peak.err" >&2; die "command failed: $*"
  fi
  tail -n 1 "$f"
}

# time_ms NAME CMD...: "median min" wall time (ms) of $runs runs of CMD, after one warm-up run.
time_ms() {
  local name=$1; shift
  if [[ $have_hyperfine == 1 ]]; then
    local cmd
    cmd=$(printf '%q ' "$@")
    hyperfine --runs "$runs" --warmup 1 --style none --export-json "$tmp/hf_$name.json" "$cmd" >/dev/null 2>&1 \
      || die "hyperfine failed on: $cmd"
    json "$tmp/hf_$name.json" '"%.2f %.2f" % (j["results"][0]["median"]*1000, j["results"][0]["min"]*1000)'
  else
    local i t0 t1 all=()
    "$@" >/dev/null 2>&1  # warm-up
    for ((i = 0; i < runs; i++)); do
      t0=$(date +%s%N); "$@" >/dev/null 2>&1; t1=$(date +%s%N)
      all+=($(( (t1 - t0) / 1000 )))
    done
    printf '%s\n' "${all[@]}" | sort -n | awk '{a[NR]=$1} END {m=(NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2; printf "%.2f %.2f\n", m/1000, a[1]/1000}'
  fi
}


# check_outputs FM_STL OS_STL DIR: validates both tools' STL files with the
# same checker (`fabmesh check`); sets os_tri, os_vol and checks ("ok" or the
# failures), and status=1 when either file is invalid.
check_outputs() {
  "$fabmesh" check "$1" --json > "$3/fm_check.json" || true
  "$fabmesh" check "$2" --json > "$3/os_check.json" || true
  local fm_valid os_valid
  fm_valid=$(json "$3/fm_check.json" 'j["valid"]')
  os_valid=$(json "$3/os_check.json" 'j["valid"]')
  os_tri=$(json "$3/os_check.json" 'j["triangles"]')
  os_vol=$(json "$3/os_check.json" 'repr(j["volume"])')
  checks=ok
  [[ $fm_valid == True ]] || { checks="fabmesh-invalid"; status=1; }
  [[ $os_valid == True ]] || { checks="$checks,openscad-invalid"; status=1; }
}
