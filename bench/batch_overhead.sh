#!/usr/bin/env bash
# The batch layer's cost: 1000 variants of the bundled shell vessel
# (configs/examples/vessel_golden_shell.yaml, STL only, tolerance 0.02) with
# the wall swept from 0.2 to 0.42 cm, built by `fabmesh batch`.
#
#   bench/batch_overhead.sh [FABMESH]        (default build-bench/pipeline/fabmesh, a Release build)
#   VARIANTS=10000 bench/batch_overhead.sh   (the 10,000-variant consistency run)
#
# Prints: wall time and peak RSS at --jobs 1 and --jobs 2, the speedup, the
# per-variant overhead of the batch layer beyond the variant's own job (wall
# time per variant at --jobs 1 minus the mean of the jobs' own times from the
# summary), a rerun where every variant is reused, the peak RSS of a batch a
# tenth the size (memory must not grow with the batch), and a consistency
# check of the summary against the files (rows, keys, sizes, digests).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
fabmesh="$(realpath "${1:-$root/build-bench/pipeline/fabmesh}")"
variants="${VARIANTS:-1000}"
[[ -x $fabmesh ]] || { echo "batch_overhead: no fabmesh at $fabmesh (cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DFABMESH_BUILD_TESTS=OFF && cmake --build build-bench --target fabmesh)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "batch_overhead: /usr/bin/time (GNU time) is missing" >&2; exit 2; }
tmp="$(mktemp -d "${TMPDIR:-/tmp}/batch_overhead.XXXXXX")"
if [[ ${KEEP:-0} == 1 ]]; then echo "keeping $tmp"; else trap 'rm -rf "$tmp"' EXIT; fi

cp "$root/configs/examples/vessel_golden_shell.yaml" "$tmp/cup.yaml"
manifest() {  # manifest FILE STEPS
  cat >"$1" <<YAML
design: cup.yaml
name: cup_w{body.wall}
set: {tolerance: 0.02, outputs: [stl]}
grid:
  body.wall: {from: 0.2, to: 0.42, steps: $2}
YAML
}
manifest "$tmp/sweep.yaml" "$variants"
manifest "$tmp/tenth.yaml" $((variants / 10))

# run NAME ARGS...: one batch run; prints "wall_s peak_kb" and keeps its --json report in $tmp/NAME.json.
run() {
  local name=$1; shift
  /usr/bin/time -f "%e %M" -o "$tmp/$name.time" "$fabmesh" batch "$@" --json -q >"$tmp/$name.json"
  cat "$tmp/$name.time"
}

echo "batch_overhead: $variants variants, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $fabmesh"
read -r wall1 rss1 < <(run jobs1 "$tmp/sweep.yaml" -o "$tmp/one" --jobs 1)
read -r wall2 rss2 < <(run jobs2 "$tmp/sweep.yaml" -o "$tmp/two" --jobs 2)
read -r wallr rssr < <(run rerun "$tmp/sweep.yaml" -o "$tmp/two" --jobs 2)
read -r wallt rsst < <(run tenth "$tmp/tenth.yaml" -o "$tmp/tenth" --jobs 2)

python3 - "$tmp" "$variants" "$wall1" "$rss1" "$wall2" "$rss2" "$wallr" "$rssr" "$wallt" "$rsst" <<'PY'
import hashlib, json, os, sys
tmp, n = sys.argv[1], int(sys.argv[2])
wall1, rss1, wall2, rss2, wallr, rssr, wallt, rsst = map(float, sys.argv[3:])

def rows(folder):
    with open(f"{tmp}/{folder}/summary.jsonl") as f:
        return [json.loads(line) for line in f]

one, two = rows("one"), rows("two")
job = [r["timings_ms"]["job"] for r in one]
mean_job = sum(job) / len(job)
resolve = sum(r["timings_ms"]["resolve"] for r in one) / n
record = sum(r["timings_ms"]["record"] for r in one) / n
report1 = json.load(open(f"{tmp}/jobs1.json"))[0]  # batch --json: an array of one item
overhead = wall1 * 1000 / n - mean_job
print(f"  --jobs 1: {wall1:.2f} s wall, {wall1 * 1000 / n:.2f} ms per variant, peak RSS {rss1 / 1024:.0f} MiB")
print(f"  --jobs 2: {wall2:.2f} s wall, peak RSS {rss2 / 1024:.0f} MiB; speedup {wall1 / wall2:.2f}x")
print(f"  a variant's own job (build, validate, encode, write): mean {mean_job:.2f} ms")
print(f"  batch overhead beyond the job, per variant: {overhead:.2f} ms "
      f"(of which resolve+key {resolve:.3f} ms, digests+ledger {record:.3f} ms, "
      f"plan of all keys {report1['timings_ms']['plan'] / n:.3f} ms; the rest is process start, "
      f"reading the manifest and writing the summary)")
print(f"  rerun, all {n} reused: {wallr:.2f} s ({wallr * 1000 / n:.3f} ms per variant)")
print(f"  peak RSS: {n // 10} variants {rsst / 1024:.0f} MiB, {n} variants {rss2 / 1024:.0f} MiB (--jobs 2)")

# Consistency: one ok row per variant, unique names and keys, every file there with its size and digest,
# and the same summary (timings aside) and bytes at --jobs 1 and 2.
problems = []
if len(two) != n: problems.append(f"{len(two)} rows for {n} variants")
if len({r["name"] for r in two}) != n or len({r["key"] for r in two}) != n: problems.append("names or keys repeat")
for r in two:
    if r["status"] != "ok" or not r["valid"]: problems.append(f"{r['name']}: {r['status']}")
    for f in r["files"]:
        data = open(f"{tmp}/two/{f['path']}", "rb").read()
        if len(data) != f["bytes"] or hashlib.sha256(data).hexdigest() != f["sha256"]:
            problems.append(f"{f['path']}: size or digest differs from the summary")
strip = lambda rs: [{k: v for k, v in r.items() if k != "timings_ms"} for r in rs]
if strip(one) != strip(two): problems.append("--jobs 1 and --jobs 2 summaries differ")
print(f"  consistency: {len(two)} rows, {sum(len(r['files']) for r in two)} files listed: "
      + ("ok" if not problems else "FAILED: " + "; ".join(problems[:10])))
sys.exit(1 if problems else 0)
PY
diff -r --exclude=.batch --exclude='summary.*' "$tmp/one" "$tmp/two" >/dev/null \
  && echo "  outputs of --jobs 1 and --jobs 2: byte-identical" \
  || { echo "  outputs of --jobs 1 and --jobs 2 DIFFER"; exit 1; }
