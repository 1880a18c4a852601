#!/usr/bin/env python3
"""`fabmesh check` against `admesh`, paired: time and peak memory per size.

Usage: bench/check_paired.py [--fabmesh PATH] [--pairs N] [--load]
                             [--sizes NUxNV ...]

For each size, a closed torus of 2 * NU * NV triangles (make_torus_stl.py,
float32 corners shared bit for bit) is checked by both tools, alternately,
PAIRS times after one warm-up each: one `fabmesh check FILE`, then one
`admesh FILE`, then the next pair. Each process is timed on its own (wall
clock around fork and wait) and its peak RSS is the kernel's for that
child (os.wait4). The ratio is taken within each pair, so a change in the
machine's load between pairs moves both sides; the table gives the median
of those ratios and their range. `--load` runs `yes > /dev/null` beside the
whole measurement (one core busy, as when something else runs).

Both tools must accept every file: fabmesh's exit code 0 (valid: closed,
oriented, no self-intersection), admesh's report of 0 edges fixed and 0
facets removed, added or reversed; otherwise the script stops with exit 1.

Fabmesh checks more than admesh: admesh reads, welds exactly, checks edges
and normals and computes the volume; fabmesh also proves the mesh free of
self-intersections with exact predicates.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def run(cmd):
    """(wall seconds, peak RSS in KiB, exit code, stdout) of one process."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    out = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    return wall, usage.ru_maxrss, proc.returncode, out.decode(errors="replace")


def admesh_accepts(out):
    """Whether admesh's report says it changed nothing."""
    checks = {
        "Edges fixed": r"Edges fixed\s*:\s*(\d+)",
        "Facets removed": r"Facets removed\s*:\s*(\d+)",
        "Facets added": r"Facets added\s*:\s*(\d+)",
        "Facets reversed": r"Facets reversed\s*:\s*(\d+)",
    }
    for name, pattern in checks.items():
        m = re.search(pattern, out)
        if not m or int(m.group(1)) != 0:
            return False, name
    return True, ""


def measure(fabmesh, stl, pairs):
    for cmd in ([fabmesh, "check", stl], ["admesh", stl]):  # warm-up: the file in the page cache
        run(cmd)
    rows = []
    for _ in range(pairs):
        fm = run([fabmesh, "check", stl])
        ad = run(["admesh", stl])
        if fm[2] != 0:
            sys.exit(f"check_paired: fabmesh check {stl} exited {fm[2]}:\n{fm[3]}")
        ok, what = admesh_accepts(ad[3])
        if ad[2] != 0 or not ok:
            sys.exit(f"check_paired: admesh did not accept {stl} ({what or 'exit %d' % ad[2]}):\n{ad[3]}")
        rows.append((fm, ad))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fabmesh", default=os.path.join(HERE, "..", "build-bench", "pipeline", "fabmesh"))
    parser.add_argument("--pairs", type=int, default=10)
    parser.add_argument("--load", action="store_true", help="one core kept busy by `yes > /dev/null`")
    parser.add_argument("--sizes", nargs="+", default=["1000x500"], help="NUxNV, 2*NU*NV triangles")
    args = parser.parse_args()
    fabmesh = os.path.abspath(args.fabmesh)
    if not os.access(fabmesh, os.X_OK):
        sys.exit(f"check_paired: no fabmesh at {fabmesh} (build the Release tree: see bench/README.md)")
    if subprocess.run(["sh", "-c", "command -v admesh"], capture_output=True).returncode != 0:
        sys.exit("check_paired: admesh not found on PATH (scripts/install-deps.sh --bench installs it)")

    busy = subprocess.Popen(["yes"], stdout=subprocess.DEVNULL) if args.load else None
    try:
        with tempfile.TemporaryDirectory(prefix="check_paired.") as tmp:
            print(f"load average at start: {open('/proc/loadavg').read().split()[0]}"
                  f"{', one core busy (yes)' if busy else ''}; {args.pairs} pairs per size")
            print("| triangles | fabmesh ms med (range) | admesh ms med (range) | fabmesh/admesh med (range)"
                  " | fabmesh MiB | admesh MiB | memory ratio | fabmesh ms per 1e6 |")
            print("|---|---|---|---|---|---|---|---|")
            for size in args.sizes:
                nu, nv = (int(x) for x in size.split("x"))
                stl = os.path.join(tmp, f"torus_{size}.stl")
                subprocess.run([sys.executable, os.path.join(HERE, "make_torus_stl.py"), stl, str(nu), str(nv)],
                               check=True)
                rows = measure(fabmesh, stl, args.pairs)
                os.remove(stl)
                fm_t = [r[0][0] * 1000 for r in rows]
                ad_t = [r[1][0] * 1000 for r in rows]
                ratios = [f / a for f, a in zip(fm_t, ad_t)]
                fm_m = max(r[0][1] for r in rows) / 1024
                ad_m = max(r[1][1] for r in rows) / 1024
                tris = 2 * nu * nv
                print(f"| {tris:,} | {statistics.median(fm_t):.0f} ({min(fm_t):.0f}-{max(fm_t):.0f})"
                      f" | {statistics.median(ad_t):.0f} ({min(ad_t):.0f}-{max(ad_t):.0f})"
                      f" | {statistics.median(ratios):.2f} ({min(ratios):.2f}-{max(ratios):.2f})"
                      f" | {fm_m:.1f} | {ad_m:.1f} | {fm_m / ad_m:.2f}"
                      f" | {statistics.median(fm_t) / (tris / 1e6):.0f} |", flush=True)
    finally:
        if busy:
            busy.kill()
            busy.wait()


if __name__ == "__main__":
    main()
