#!/usr/bin/python3
"""Many variants built from Python, on one thread and two, against `fabmesh batch --jobs 2` (issue 25, "Speed").

Usage (from the source tree, with a built module and program):

    PYTHONPATH=build/python /usr/bin/python3 bench/python_batch.py [--fabmesh build/pipeline/fabmesh]
        [--variants 1000] [--rounds 3] [--keep]

The variants are those of bench/batch_overhead.sh: the bundled shell vessel
(configs/examples/vessel_golden_shell.yaml) with tolerance 0.02, STL only,
and the wall swept over `variants` distinct values from 0.2 to 0.42 cm
(rounded to 12 significant digits, so both sides get the very same numbers).
In each round, one after the other:

  (a) one thread: for each value, fabmesh.load_design(path, overrides=...)
      then fabmesh.build(design);
  (b) the same tasks on a ThreadPoolExecutor(max_workers=2) (the module
      releases the GIL while it reads and builds);
  (c) `fabmesh batch MANIFEST --jobs 2 -o DIR -q --json` on a manifest of the
      same values (a `zip` of body.wall), into a fresh DIR each round.

Not the same work: build() builds, validates and encodes the STL in memory
(and copies the mesh out for .vertices/.triangles); batch also computes each
variant's key, writes and fsyncs each STL, hashes it, and writes its ledger
and summaries. (a) and (b) run in this process (the module already
imported); (c) is the whole command, process start included.

Prints the wall time of each arm per round and their medians, CPU time /
wall time (about 2 when two threads really run at once), the speed-up
(a)/(b) (aim >= 1.7) and (b)/(c) (aim: within 15 %). After timing, checks
that every variant is valid and that Python's and the batch's triangle
counts agree for every variant.
"""
import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SET = {"tolerance": 0.02, "outputs": ["stl"]}


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--fabmesh", default=os.path.join(ROOT, "build", "pipeline", "fabmesh"))
    p.add_argument("--design", default=os.path.join(ROOT, "configs", "examples", "vessel_golden_shell.yaml"))
    p.add_argument("--variants", type=int, default=1000)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--keep", action="store_true", help="keep the temporary folder")
    args = p.parse_args()
    fabmesh_bin = os.path.realpath(args.fabmesh)
    design_path = os.path.realpath(args.design)
    if not os.access(fabmesh_bin, os.X_OK):
        sys.exit(f"python_batch: no fabmesh program at {fabmesh_bin} (--fabmesh)")
    import fabmesh

    n = args.variants
    walls = [float(f"{0.2 + 0.22 * k / (n - 1):.12g}") for k in range(n)]
    if len(set(walls)) != n:
        sys.exit("python_batch: the wall values repeat")
    tmp = tempfile.mkdtemp(prefix="python_batch.")
    try:
        manifest = os.path.join(tmp, "sweep.yaml")
        with open(manifest, "w") as f:
            f.write(f"design: {json.dumps(design_path)}\nname: cup_{{index}}\n"
                    f"set: {json.dumps(SET)}\nzip:\n  body.wall: {json.dumps(walls)}\n")
        print(f"python_batch: {n} variants of {design_path} (tolerance 0.02, STL, body.wall {walls[0]} .. {walls[-1]}); "
              f"fabmesh {fabmesh.__version__} module {fabmesh.__file__}, program {fabmesh_bin}; "
              f"{os.cpu_count()} cores, load {' '.join(open('/proc/loadavg').read().split()[:3])}")

        def task(wall):
            design = fabmesh.load_design(design_path, overrides={**SET, "body.wall": wall})
            return fabmesh.build(design).valid

        def arm_a():
            return [task(w) for w in walls]

        def arm_b():
            with ThreadPoolExecutor(max_workers=2) as pool:
                return list(pool.map(task, walls))

        def arm_c(r):
            out = subprocess.run([fabmesh_bin, "batch", manifest, "--jobs", "2", "-o", os.path.join(tmp, f"out{r}"),
                                  "-q", "--json"], capture_output=True, text=True)
            item = json.loads(out.stdout)[0]
            if out.returncode != 0 or item.get("ok") != n:
                sys.exit(f"python_batch: batch failed (exit {out.returncode}): {out.stdout[:2000]} {out.stderr[:2000]}")
            return item

        task(walls[0])  # warm-up
        times = {"a": [], "b": [], "c": []}
        cpu = {"a": [], "b": [], "c": []}
        for r in range(args.rounds):
            for arm in "abc":
                c0, k0, t0 = time.process_time(), children_cpu(), time.perf_counter()
                if arm == "c":
                    arm_c(r)
                else:
                    valid = arm_a() if arm == "a" else arm_b()
                    if not all(valid):
                        sys.exit(f"python_batch: arm {arm}: {valid.count(False)} variants not valid")
                wall = time.perf_counter() - t0
                used = (children_cpu() - k0) if arm == "c" else (time.process_time() - c0)
                times[arm].append(wall)
                cpu[arm].append(used / wall)
            print(f"  round {r + 1}: (a) {times['a'][-1]:.2f} s  (b) {times['b'][-1]:.2f} s  (c) {times['c'][-1]:.2f} s  "
                  f"load {open('/proc/loadavg').read().split()[0]}", flush=True)

        med = {k: statistics.median(v) for k, v in times.items()}
        names = {"a": "(a) Python, 1 thread", "b": "(b) Python, 2-thread pool", "c": "(c) fabmesh batch --jobs 2"}
        print(f"\n{n} variants, {args.rounds} rounds; wall s median (min), ms per variant, CPU/wall")
        for k in "abc":
            print(f"  {names[k]:<28} {med[k]:7.2f} ({min(times[k]):7.2f})  {med[k] * 1000 / n:6.2f} ms  "
                  f"{statistics.median(cpu[k]):.2f}")
        speedup = med["a"] / med["b"]
        vs = med["b"] / med["c"]
        print(f"  speed-up (a)/(b): {speedup:.2f}x (aim >= 1.7: {'met' if speedup >= 1.7 else 'NOT met'}); "
              f"per round {', '.join('%.2f' % (x / y) for x, y in zip(times['a'], times['b']))}")
        print(f"  (b)/(c): {vs:.3f} (aim within 15 %: {'met' if abs(vs - 1) <= 0.15 else 'NOT met'}); "
              f"per round {', '.join('%.3f' % (x / y) for x, y in zip(times['b'], times['c']))}")

        # Same variants on both sides: the triangle counts of every variant.
        rows = [json.loads(line) for line in open(os.path.join(tmp, "out0", "summary.jsonl"))]
        mismatch = 0
        for w, row in zip(walls, rows):
            built = fabmesh.build(fabmesh.load_design(design_path, overrides={**SET, "body.wall": w}))
            if row["overrides"]["body.wall"] != repr(w) and float(row["overrides"]["body.wall"]) != w:
                mismatch += 1
            elif row["status"] != "ok" or not built.valid or row["triangles"] != built.report["triangles"]:
                mismatch += 1
        print(f"  consistency: {len(rows)} batch rows; Python and batch agree on value, validity and triangle count "
              f"for {len(rows) - mismatch} of {n}")
        if mismatch or len(rows) != n:
            sys.exit(1)
    finally:
        if args.keep:
            print(f"kept {tmp}")
        else:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
