#!/usr/bin/python3
"""fabmesh's kitchen nesting vs libnest2d (Debian's python3-pynest2d): slabs
used for the same pieces on the same slabs (the issue's invariant: fabmesh
uses no more slabs than libnest2d), and the time each takes.

    /usr/bin/python3 bench/nest_vs_libnest2d.py [path/to/fabmesh]   (default: build-bench/pipeline/fabmesh)

Needs Debian's `python3-pynest2d` (`scripts/install-deps.sh --bench`) and
`python3-yaml` (`--test`), so it runs with Debian's /usr/bin/python3, not a
python3 earlier on PATH. Environment: RUNS (timed runs of each, default
10), CASES (space-separated case names, default all), KEEP=1 keeps the
temporary folder.

For each kitchen (the two examples, a larger L, a straight 5.5 m run, a G
with a peninsula, also on 3200 x 1600 slabs, and three of them on small
2000 x 1000 slabs so that there are many pieces, the U also with
`grain: any`; the generated designs are written to the temporary folder,
the variants are `-D` overrides). "Pieces" are all that fabmesh nested: the
top's pieces and the L's backsplash strips (`piece-N`, `backsplash-N`),
the same slab stock:

1. Times the whole `fabmesh run DESIGN -o DIR/ --json` (the design's own
   outputs: reading, seams, pieces, nesting and its exact verification,
   meshes, validation, writing with fsync) with time.perf_counter: one
   warm-up run, then RUNS runs; min, median, max. Reads slabs, lower bound,
   utilisation, the effective margin and spacing (the nesting line: the
   slab's numbers widened by the build's deviation) and the `nesting` stage's
   own time from the JSON.
2. Takes each piece's outer loop from DIR/NAME.layout.svg (the first subpath
   of every `<path class="piece">`, whatever its id, y negated back; their
   names must be the report's pieces), moved to its own bounding
   box's lower-left corner: the same polygons fabmesh nested, in the
   orientation fabmesh placed them (long side along the slab for
   `grain: along`).
3. Nests them with pynest2d's nest() (first fit, NFP placer, Clipper):
   integer micrometres (vertices rounded to 1 um, clockwise as libnest2d's
   Clipper backend wants), distance = the effective spacing rounded up to
   the um, plus 2 um for the rounding, made even; libnest2d inflates every
   item by half the distance and keeps the inflated items inside the bin,
   so the bin is the usable area (slab - 2 effective margins, rounded down,
   minus 2 um) plus the distance in each direction. Rotations: 0 and pi for
   `grain: along` (the grain's two turns from fabmesh's placed orientation),
   the four quarter turns for `any`; the other NfpConfig fields keep their
   defaults (accuracy 0.65, alignment and starting point CENTER, parallel,
   no holes explored). Slab defects are not given to libnest2d (its fixed
   items are moved by the final alignment in this version), which can only
   help it. Times the nest() call alone (fresh items each run; min, median,
   max of RUNS), counts the bins (a run that leaves an item without a bin
   says how many), and checks one layout: every piece inside the usable
   area and at least the distance from every other piece on its bin.
4. Prints one row per case and exits 1 if fabmesh used more slabs than
   libnest2d on any case or refused a case's design (naming it; a refused
   case has a row saying so, its error under the table, and the other cases
   still run), 2 on an error of the bench's own.
"""
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

NAME = "nest_vs_libnest2d.py"


def die(msg):
    print(f"{NAME}: error: {msg}", file=sys.stderr)
    sys.exit(2)


try:
    from pynest2d import Box, Item, NfpConfig, Point, nest
except ImportError as e:
    die(f"cannot import pynest2d ({e}); Debian: apt-get install -y python3-pynest2d, "
        "and run with /usr/bin/python3")
try:
    import yaml
except ImportError as e:
    die(f"cannot import yaml ({e}); Debian: apt-get install -y python3-yaml")

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
EXAMPLES = os.path.join(ROOT, "configs", "examples")
SMALL = {"slab.length": "2000", "slab.width": "1000"}
LARGE = {"slab.length": "3200", "slab.width": "1600", "slab.margin": "15", "slab.spacing": "16"}  # the U example's stock
BIG_L = {"run": "5600", "leg": "3000"}

# A straight run: 5.5 m, sink and cooktop; needs one seam on a 3000 mm slab.
RUN_5500 = """name: run_5500
kind: countertop
units: mm
tolerance: 0.05
thickness: 30
outline:
  family: tbezier
  closed: true
  segments:
    - line: {from: [0, 0], to: [5500, 0]}
    - line: {to: [5500, 650]}
    - line: {to: [0, 650]}
    - line: {to: [0, 0]}
holes:
  - rounded_rect: {center: [1500, 325], size: [860, 440], radius: 30}
  - rounded_rect: {center: [4200, 325], size: [560, 490], radius: 10}
slab: {length: 3000, width: 1400, margin: 10, spacing: 14, grain: along}
seams: auto
outputs: [stl, layout_svg, cutlist]
"""

# A G: a U of 4800 x 3000 (650 deep) whose right leg returns into a 900 mm
# deep peninsula (a breakfast bar) 2200 mm long.
G_4800 = """name: g_4800
kind: countertop
units: mm
tolerance: 0.05
thickness: 30
outline:
  family: tbezier
  closed: true
  segments:
    - line: {from: [0, 0], to: [650, 0]}
    - line: {to: [650, 2350]}
    - line: {to: [4150, 2350]}
    - line: {to: [4150, 900]}
    - line: {to: [2600, 900]}
    - line: {to: [2600, 0]}
    - line: {to: [4800, 0]}
    - line: {to: [4800, 3000]}
    - line: {to: [0, 3000]}
    - line: {to: [0, 0]}
holes:
  - rounded_rect: {center: [2400, 2675], size: [860, 440], radius: 30}
  - rounded_rect: {center: [325, 1200], size: [500, 560], radius: 10}
slab: {length: 3000, width: 1400, margin: 10, spacing: 14, grain: along}
seams: auto
outputs: [stl, layout_svg, cutlist]
"""


def cases(tmp):
    for name, text in (("run_5500", RUN_5500), ("g_4800", G_4800)):
        with open(os.path.join(tmp, name + ".yaml"), "w") as f:
            f.write(text)
    l_yaml, u_yaml = (os.path.join(EXAMPLES, n) for n in ("kitchen_l.yaml", "kitchen_u.yaml"))
    run, g = (os.path.join(tmp, n + ".yaml") for n in ("run_5500", "g_4800"))
    u_small = {"seams": "auto", "slab.defects": "[]", **SMALL}  # the example's seams and flaw suit 3200 x 1600 only
    return [
        ("kitchen_l", l_yaml, {}),
        ("kitchen_u", u_yaml, {}),
        ("l_5600x3000", l_yaml, BIG_L),
        ("run_5500", run, {}),
        ("g_4800x3000", g, {}),
        ("g_4800x3000_3200", g, LARGE),
        ("l_5600x3000_small", l_yaml, {**BIG_L, **SMALL}),
        ("u_small", u_yaml, u_small),
        ("u_small_any", u_yaml, {**u_small, "slab.grain": "any"}),  # any quarter turn
        ("g_4800x3000_small", g, SMALL),
    ]


def slab_of(design, defines):
    """The design's slab: its YAML with the case's slab.* overrides."""
    with open(design) as f:
        slab = dict(yaml.safe_load(f)["slab"])
    for key, value in defines.items():
        if key.startswith("slab."):
            slab[key[5:]] = yaml.safe_load(value)
    return slab


class Refused(Exception):
    """fabmesh exited non-zero on a case's design."""


def run_fabmesh(fabmesh, design, defines, out, runs):
    cmd = [fabmesh, "run", design, "-o", out + "/", "--json"]
    for key, value in defines.items():
        cmd += ["-D", f"{key}={value}"]
    times, reports = [], []
    for i in range(runs + 1):
        start = time.perf_counter()
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        elapsed = time.perf_counter() - start
        if p.returncode != 0:
            raise Refused(f"fabmesh exited {p.returncode} on {' '.join(cmd)}:\n    {p.stderr.strip()}")
        if i > 0:  # the first run warms the caches
            times.append(1e3 * elapsed)
            reports.append(json.loads(p.stdout)[0])
    return times, reports


def svg_pieces(path):
    """{name: outer loop in slab coordinates (mm), moved to its bounding box's lower-left corner}."""
    with open(path) as f:
        svg = f.read()
    pieces = {}
    tags = [t for t in re.findall(r"<path\b[^>]*>", svg) if re.search(r'\bclass="piece"', t)]
    for tag in tags:
        name, d = (re.search(rf'\b{a}="([^"]+)"', tag) for a in ("id", "d"))
        if not name or not d:
            die(f"{path}: a piece without id or d: {tag[:120]}")
        name, d = name.group(1), d.group(1)
        if name in pieces:
            die(f"{path}: two pieces named {name}")
        first = d.split("Z")[0]
        nums = [float(t) for t in re.findall(r"-?[0-9.]+(?:[eE][-+]?[0-9]+)?", first)]
        pts = [(nums[i], -nums[i + 1]) for i in range(0, len(nums), 2)]
        x0, y0 = min(p[0] for p in pts), min(p[1] for p in pts)
        pieces[name] = [(x - x0, y - y0) for x, y in pts]
    return pieces


def to_um(loop):
    pts = []
    for x, y in loop:
        q = (round(x * 1000.0), round(y * 1000.0))
        if not pts or pts[-1] != q:
            pts.append(q)
    if pts[0] == pts[-1]:
        pts.pop()
    twice_area = sum(pts[i][0] * pts[(i + 1) % len(pts)][1] - pts[(i + 1) % len(pts)][0] * pts[i][1]
                     for i in range(len(pts)))
    return pts[::-1] if twice_area > 0 else pts  # clockwise for libnest2d's Clipper backend


def run_libnest2d(loops_um, bin_um, dist_um, rotations, runs):
    times, bins, checked = [], [], math.inf
    for i in range(runs + 1):
        items = [Item([Point(x, y) for x, y in loop]) for loop in loops_um]
        for it in items:
            if it.area() <= 0:
                die("a piece is not clockwise for libnest2d")
        config = NfpConfig()
        config.rotations = rotations
        box = Box(bin_um[0], bin_um[1])
        start = time.perf_counter()
        n = nest(items, box, dist_um, config)
        elapsed = time.perf_counter() - start
        if i == 0:
            continue
        times.append(1e3 * elapsed)
        ids = [it.binId() for it in items]
        if min(ids) < 0:
            bins.append(f"{sum(1 for b in ids if b < 0)} unplaced")
            continue
        used = max(ids) + 1
        if used != n:
            die(f"libnest2d's nest() returned {n} but its items use {used} bins")
        if i == 1:  # check one layout: inside the bin less half the distance, the distance apart
            shapes = [[(v.x(), v.y()) for v in map(s.vertex, range(s.vertexCount()))]
                      for s in (it.transformedShape() for it in items)]
            inside = [(bin_um[k] - dist_um) / 2 + 2 for k in (0, 1)]
            if any(abs(p[k]) > inside[k] for s in shapes for p in s for k in (0, 1)):
                die("libnest2d placed a piece outside the usable area")
            gaps = [gap(shapes[a], shapes[b]) for a in range(len(items)) for b in range(a + 1, len(items))
                    if ids[a] == ids[b]]
            checked = min(gaps, default=math.inf)
            if checked < dist_um - 4:
                die(f"libnest2d placed two pieces {checked} um apart (distance {dist_um} um)")
        bins.append(used)
    return times, bins, checked


def gap(p, q):
    """Least distance between two simple polygons' areas (0 if they overlap)."""
    def inside(pt, poly):
        x, y, c = pt[0], pt[1], False
        for (x1, y1), (x2, y2) in zip(poly, poly[1:] + poly[:1]):
            if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
                c = not c
        return c

    def seg_point(a, b, c):
        dx, dy = b[0] - a[0], b[1] - a[1]
        t = max(0.0, min(1.0, ((c[0] - a[0]) * dx + (c[1] - a[1]) * dy) / (dx * dx + dy * dy or 1)))
        return math.hypot(a[0] + t * dx - c[0], a[1] + t * dy - c[1])

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    if inside(p[0], q) or inside(q[0], p):
        return 0.0
    best = math.inf
    for a, b in zip(p, p[1:] + p[:1]):
        for c, d in zip(q, q[1:] + q[:1]):
            if cross(a, b, c) * cross(a, b, d) < 0 and cross(c, d, a) * cross(c, d, b) < 0:
                return 0.0
            best = min(best, seg_point(a, b, c), seg_point(a, b, d), seg_point(c, d, a), seg_point(c, d, b))
    return best


def spread(times):
    return f"{min(times):.1f} / {statistics.median(times):.1f} / {max(times):.1f}"


def main():
    fabmesh = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build-bench", "pipeline", "fabmesh")
    if not os.access(fabmesh, os.X_OK):
        die(f"fabmesh not found or not executable at '{fabmesh}' (build it: cmake -S . -B build-bench -G Ninja "
            "-DCMAKE_BUILD_TYPE=Release -DFABMESH_BUILD_TESTS=OFF && cmake --build build-bench --target fabmesh)")
    fabmesh = os.path.abspath(fabmesh)
    runs = int(os.environ.get("RUNS", "10"))
    only = os.environ.get("CASES", "").split()
    tmp = tempfile.mkdtemp(prefix="nest_vs_libnest2d.")
    keep = os.environ.get("KEEP") == "1"
    if keep:
        print(f"keeping {tmp}")
    try:
        version = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "python3-pynest2d"],
                                 stdout=subprocess.PIPE, text=True).stdout or "?"
        print(f"fabmesh:   {fabmesh}")
        print(f"libnest2d: python3-pynest2d {version} (nest(): first fit, NFP placer, Clipper)")
        print(f"timing:    time.perf_counter, {runs} runs after 1 warm-up; min / median / max")
        print(f"machine:   {os.cpu_count()} cores, load average {' '.join(open('/proc/loadavg').read().split()[:3])}")
        print()
        rows, notes, worse = [], [], []
        for name, design, defines in cases(tmp):
            if only and name not in only:
                continue
            out = os.path.join(tmp, name)
            os.makedirs(out)
            try:
                fm_times, reports = run_fabmesh(fabmesh, design, defines, out, runs)
            except Refused as e:
                worse.append(f"{name}: fabmesh refused the design")
                rows.append(f"| {name} | - | - | refused | - | - | - | - | - | REFUSED |")
                notes.append(f"{name}: {e}")
                continue
            report = reports[-1]
            kitchen = report["build"]["kitchen"]
            stage = [r["timings_ms"].get("nesting", float("nan")) for r in reports]
            m = re.search(r"margins of ([0-9.]+), at least ([0-9.]+) apart", kitchen["nesting"])
            if not m:
                die(f"{name}: no effective margin and spacing in the nesting line: {kitchen['nesting']}")
            margin, spacing = float(m.group(1)), float(m.group(2))
            slab = slab_of(design, defines)
            svg = os.path.join(out, f"{report['name']}.layout.svg")
            loops = svg_pieces(svg)
            if sorted(loops) != sorted(p["name"] for p in kitchen["pieces"]):
                die(f"{name}: the layout's pieces {sorted(loops)} are not the report's")
            dist = 2 * math.ceil((math.ceil(spacing * 1000.0) + 2) / 2)
            usable = (float(slab["length"]) - 2 * margin, float(slab["width"]) - 2 * margin)
            bin_um = tuple(math.floor(u * 1000.0) - 2 + dist for u in usable)
            rotations = [0.0, math.pi] if slab.get("grain", "along") == "along" else \
                [0.0, 0.5 * math.pi, math.pi, 1.5 * math.pi]
            loops_um = [to_um(loops[k]) for k in sorted(loops)]
            ln_times, ln_bins, ln_gap = run_libnest2d(loops_um, bin_um, dist, rotations, runs)
            ln_text = " or ".join(sorted(set(map(str, ln_bins))))  # one value unless runs differ
            fm_slabs = kitchen["slabs"]
            # A run that left pieces unplaced (binId -1) is no layout: fabmesh, which placed all, is not worse.
            ok = all(not isinstance(b, int) or fm_slabs <= b for b in ln_bins)
            if not ok:
                worse.append(f"{name}: fabmesh {fm_slabs} slabs, libnest2d {ln_text}")
            strips = sum(1 for k in loops if not k.startswith("piece-"))
            counted = f"{len(loops)} ({strips} strips)" if strips else str(len(loops))
            rows.append(f"| {name} | {counted} | {kitchen['lower_bound']} | {fm_slabs} | {ln_text} | "
                        f"{100 * max(kitchen['utilisation']):.1f}% | {spread(fm_times)} | "
                        f"{statistics.median(stage):.2f} | {spread(ln_times)} | {'ok' if ok else 'MORE'} |")
            notes.append(f"{name}: slab {slab['length']} x {slab['width']}, grain {slab.get('grain', 'along')}; "
                         f"effective margin {margin}, spacing {spacing}; libnest2d bin {bin_um[0]} x {bin_um[1]} um, "
                         f"distance {dist} um, least gap in its layout "
                         f"{f'{ln_gap / 1000:.3f} mm' if ln_gap < math.inf else '- (one piece a bin)'}; "
                         f"fabmesh utilisation {', '.join(f'{100 * u:.1f}%' for u in kitchen['utilisation'])}"
                         + (f"; {len(slab['defects'])} slab defect(s), given to fabmesh only"
                            if slab.get("defects") else ""))
        print("| case | pieces (of which strips) | lower bound | fabmesh slabs | libnest2d slabs | fabmesh fullest slab | "
              "fabmesh run ms min / med / max | fabmesh nesting stage ms (med) | libnest2d nest() ms min / med / max "
              "| fabmesh <= libnest2d |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        print("\n".join(rows))
        print()
        print("fabmesh run = the whole process (build, nesting and its exact verification, meshes, writing);")
        print("libnest2d = the nest() call alone on the same pieces; fullest slab = fabmesh's highest utilisation")
        print("(pieces' area over the usable area).")
        print("\n".join("  " + n for n in notes))
        if worse:
            for w in worse:
                print(f"{NAME}: fabmesh does worse than libnest2d: {w}", file=sys.stderr)
            return 1
        return 0
    finally:
        if not keep:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
