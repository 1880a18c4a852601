#!/usr/bin/python3
"""fabmesh.check on numpy arrays against `fabmesh check` and Open3D (issue 25, "Speed").

Usage (from the source tree, with a built module and program):

    PYTHONPATH=build/python /usr/bin/python3 bench/python_check.py [--fabmesh build/pipeline/fabmesh]
        [--nu 1000 --nv 500] [--runs 5] [--o3d-sizes 50x50,100x50,100x100] [--o3d-timeout 120]

Builds the closed torus of bench/make_torus_stl.py (2 * nu * nv triangles,
default 1e6; the same parametrisation, vertices rounded to float32 as the
STL holds them) as numpy arrays (float64 (N, 3), int64 (M, 3), C order, so
the binding takes them without conversion), writes it as a binary STL to a
temporary folder, and times, alternating within one run, `runs` times each:

  (a) fabmesh.check(vertices, triangles): wall time in this process
      (array checks, the copy into the library's soup, weld, validation,
      the report as a dict);
  (b) `fabmesh check torus.stl --json` in a child process: its validate
      stage, the sum of timings_ms topology + geometry + self_intersection
      (the three stages of the validation proper; read and weld are
      reported beside it, and the whole command's wall time);
  (c) Open3D on the same arrays: TriangleMesh from Vector3dVector /
      Vector3iVector, is_self_intersecting(), is_watertight().

Open3D's self-intersection test is a loop over all pairs of triangles
(quadratic), and its is_watertight() runs it again, so at 1e6 triangles one
call takes hours: (c) at full size is attempted once in a child process and
stopped after --o3d-timeout seconds (a lower bound). (a) and (c) are then
timed against each other, alternating, on smaller tori (--o3d-sizes,
NUxNV), and Open3D's time is extrapolated to full size by the power law
fitted to them.

Prints medians (and min) in ms and the ratios (a)/(b) and (a)/(c).
"""
import argparse
import json
import math
import multiprocessing
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
VALIDATE_KEYS = ("topology", "geometry", "self_intersection")


def torus(nu, nv):
    """The torus of make_torus_stl.py: ring i at angle u_i, tube angle v_j; vertex i * nv + j."""
    big, small = 3.0, 1.0
    u = 2 * np.pi * np.arange(nu) / nu
    v = 2 * np.pi * np.arange(nv) / nv
    uu, vv = np.meshgrid(u, v, indexing="ij")
    r = big + small * np.cos(vv)
    points = np.stack([r * np.cos(uu), r * np.sin(uu), small * np.sin(vv)], axis=-1)
    vertices = np.ascontiguousarray(points.astype(np.float32).astype(np.float64).reshape(-1, 3))
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    i1, j1 = (i + 1) % nu, (j + 1) % nv
    a, b, c, d = i * nv + j, i1 * nv + j, i1 * nv + j1, i * nv + j1
    # outward, as make_torus_stl.py: (a, b, c) then (a, c, d) for each quad
    tri = np.stack([np.stack([a, b, c], -1), np.stack([a, c, d], -1)], axis=2)
    return vertices, np.ascontiguousarray(tri.reshape(-1, 3).astype(np.int64))


def write_stl(path, vertices, triangles):
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attr", "<u2")])
    data = np.zeros(len(triangles), dtype=record)
    data["corners"] = vertices[triangles].astype(np.float32)
    with open(path, "wb") as f:
        f.write(b"fabmesh bench torus".ljust(80, b" "))
        f.write(np.uint32(len(triangles)).tobytes())
        f.write(data.tobytes())


def run_fabmesh(fabmesh, args, stl):
    """(b): one `fabmesh check --json`; returns (wall ms, validate ms, timings dict, item)."""
    t0 = time.perf_counter()
    out = subprocess.run([fabmesh, "check", stl, "--json"], check=False, capture_output=True, text=True)
    wall = (time.perf_counter() - t0) * 1000
    item = json.loads(out.stdout)[0]
    timings = item["timings_ms"]
    return wall, sum(timings[k] for k in VALIDATE_KEYS), timings, item


def run_fabmesh_check(fabmesh_module, vertices, triangles):
    """(a): returns (wall ms, item)."""
    t0 = time.perf_counter()
    item = fabmesh_module.check(vertices, triangles)
    return (time.perf_counter() - t0) * 1000, item


def run_open3d(vertices, triangles):
    """(c): returns (total ms, construct ms, is_self_intersecting ms, is_watertight ms, verdicts)."""
    import open3d as o3d
    t0 = time.perf_counter()
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(vertices), o3d.utility.Vector3iVector(triangles))
    t1 = time.perf_counter()
    si = mesh.is_self_intersecting()
    t2 = time.perf_counter()
    wt = mesh.is_watertight()
    t3 = time.perf_counter()
    ms = lambda a, b: (b - a) * 1000
    return ms(t0, t3), ms(t0, t1), ms(t1, t2), ms(t2, t3), (si, wt)


def _open3d_child(nu, nv, queue):
    v, t = torus(nu, nv)
    queue.put(run_open3d(v, t))


def open3d_with_timeout(nu, nv, timeout):
    """(c) at full size in a child process; None when it did not finish within `timeout` seconds."""
    queue = multiprocessing.get_context("fork").Queue()
    child = multiprocessing.get_context("fork").Process(target=_open3d_child, args=(nu, nv, queue))
    t0 = time.perf_counter()
    child.start()
    child.join(timeout)
    elapsed = time.perf_counter() - t0
    if child.is_alive():
        child.kill()
        child.join()
        return None, elapsed
    return queue.get(), elapsed


def med(xs):
    return statistics.median(xs)


def fmt(xs):
    return "%9.1f (%9.1f)" % (med(xs), min(xs))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--fabmesh", default=os.path.join(HERE, "..", "build", "pipeline", "fabmesh"))
    p.add_argument("--nu", type=int, default=1000)
    p.add_argument("--nv", type=int, default=500)
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--o3d-sizes", default="50x50,100x50,100x100")
    p.add_argument("--o3d-timeout", type=float, default=120.0)
    args = p.parse_args()
    fabmesh_bin = os.path.realpath(args.fabmesh)
    if not os.access(fabmesh_bin, os.X_OK):
        sys.exit(f"python_check: no fabmesh program at {fabmesh_bin} (--fabmesh)")
    import fabmesh
    import open3d as o3d

    print(f"python_check: fabmesh {fabmesh.__version__} module {fabmesh.__file__}, program {fabmesh_bin}; "
          f"numpy {np.__version__}, open3d {o3d.__version__}; {os.cpu_count()} cores, "
          f"load {' '.join(open('/proc/loadavg').read().split()[:3])}")
    vertices, triangles = torus(args.nu, args.nv)
    with tempfile.TemporaryDirectory(prefix="python_check.") as tmp:
        stl = os.path.join(tmp, "torus.stl")
        write_stl(stl, vertices, triangles)
        print(f"torus: {len(vertices)} vertices, {len(triangles)} triangles; {stl}: {os.path.getsize(stl)} bytes")

        # Warm-up (page cache, allocator) and the verdicts must agree.
        _, item_a = run_fabmesh_check(fabmesh, vertices, triangles)
        _, _, timings_b, item_b = run_fabmesh(fabmesh_bin, args, stl)
        for key in ("valid", "vertices", "triangles", "genus", "watertight", "self_intersecting"):
            if item_a[key] != item_b[key]:
                sys.exit(f"python_check: {key} differs: module {item_a[key]!r}, program {item_b[key]!r}")
        if not item_a["valid"]:
            sys.exit("python_check: the torus is not valid")
        print(f"verdicts agree: valid {item_a['valid']}, genus {item_a['genus']}, "
              f"{item_a['vertices']} vertices, self_intersecting {item_a['self_intersecting']}")
        print(f"timings_ms keys of `fabmesh check --json`: {', '.join(timings_b)}; "
              f"validate stage = {' + '.join(VALIDATE_KEYS)}")

        a, a_stage, b_wall, b_val, b_weld, b_read, b_stage = [], [], [], [], [], [], []
        for _ in range(args.runs):
            ms, item = run_fabmesh_check(fabmesh, vertices, triangles)
            a.append(ms)
            a_stage.append(item["timings_ms"])
            wall, val, timings, _ = run_fabmesh(fabmesh_bin, args, stl)
            b_wall.append(wall)
            b_val.append(val)
            b_weld.append(timings["weld"])
            b_read.append(timings["read"])
            b_stage.append(timings)

        print(f"\n{len(triangles)} triangles, {args.runs} runs alternating; ms median (min)")
        print(f"  (a) fabmesh.check(arrays), wall      {fmt(a)}")
        for key in a_stage[0]:
            print(f"        of which its stage {key:<17} {fmt([s[key] for s in a_stage])}")
        a_val = [sum(s[k] for k in VALIDATE_KEYS) for s in a_stage]
        print(f"        its validate stage              {fmt(a_val)}")
        print(f"        outside the stages (binding: arrays in, copy, dict out) {fmt([x - sum(s.values()) for x, s in zip(a, a_stage)])}")
        print(f"  (b) fabmesh check torus.stl: validate {fmt(b_val)}")
        for key in b_stage[0]:
            if key in VALIDATE_KEYS:
                print(f"        of which {key:<26} {fmt([s[key] for s in b_stage])}")
        print(f"        read                            {fmt(b_read)}")
        print(f"        weld                            {fmt(b_weld)}")
        print(f"        whole command, wall             {fmt(b_wall)}")
        ratio_ab = med(a) / med(b_val)
        print(f"  (a)/(b) validate: {ratio_ab:.2f} (aim <= 1.2: {'met' if ratio_ab <= 1.2 else 'NOT met'}); "
              f"(a)/(b) weld+validate: {med(a) / med([x + y for x, y in zip(b_val, b_weld)]):.2f}; "
              f"(a)/(b) whole command: {med(a) / med(b_wall):.2f}")

    # (c) at full size: once, bounded.
    print(f"\n(c) Open3D at {len(triangles)} triangles, once, stopped after {args.o3d_timeout:.0f} s:")
    full, elapsed = open3d_with_timeout(args.nu, args.nv, args.o3d_timeout)
    if full is None:
        print(f"  did not finish in {elapsed:.0f} s (stopped): (a)/(c) < {med(a) / (elapsed * 1000):.5f}")
    else:
        print(f"  {full[0]:.0f} ms (construct {full[1]:.0f}, is_self_intersecting {full[2]:.0f}, "
              f"is_watertight {full[3]:.0f}); verdicts {full[4]}; (a)/(c) = {med(a) / full[0]:.4f}")

    # (a) against (c) on smaller tori, alternating.
    print(f"\n(a) against (c) on smaller tori, {args.runs} runs alternating; ms median (min)")
    print("  triangles |   (a) fabmesh.check   |   (c) Open3D total    | o3d self_int | o3d watertight | (a)/(c)")
    sizes, times_c = [], []
    for size in args.o3d_sizes.split(","):
        nu, nv = map(int, size.split("x"))
        v, t = torus(nu, nv)
        fabmesh.check(v, t)
        run_open3d(v, t)
        sa, sc, ssi, swt = [], [], [], []
        verdicts = None
        for _ in range(args.runs):
            sa.append(run_fabmesh_check(fabmesh, v, t)[0])
            total, _, si, wt, verdicts = run_open3d(v, t)
            sc.append(total)
            ssi.append(si)
            swt.append(wt)
        if verdicts != (False, True):
            print(f"  note: Open3D says self_intersecting={verdicts[0]}, watertight={verdicts[1]}")
        sizes.append(len(t))
        times_c.append(med(sc))
        print(f"  {len(t):9d} | {fmt(sa)} | {fmt(sc)} | {med(ssi):12.1f} | {med(swt):14.1f} | {med(sa) / med(sc):.4f}")
    if len(sizes) >= 2:
        k, c = np.polyfit(np.log(sizes), np.log(times_c), 1)
        at_full = math.exp(c) * len(triangles) ** k
        print(f"  Open3D's time grows as n^{k:.2f}; extrapolated to {len(triangles)} triangles: {at_full / 1000:.0f} s, "
              f"(a)/(c) = {med(a) / at_full:.6f}")


if __name__ == "__main__":
    main()
