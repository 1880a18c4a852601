#!/usr/bin/env bash
# fabmesh vs OpenSCAD: extrude the same polygon with holes into a binary STL slab.
#
#   bench/countertop_vs_openscad.sh [path/to/fabmesh]     (default: build-bench/pipeline/fabmesh)
#
# The outline is a 2400 x 650 mm rounded rectangle (corner radius 100) sampled
# as K points evenly along its length, with a sink (rounded rectangle) and a
# cooktop (ellipse) of H points each, all rounded to a 2^-10 mm grid so both
# tools read exactly the same coordinates. fabmesh gets each loop as a
# `polyline` read from a CSV file (a line is sampled exactly), OpenSCAD as
# linear_extrude(height = 30) polygon(points, paths). Each size times whole
# processes (hyperfine if installed, else a loop), measures peak RSS with
# /usr/bin/time -f %M, checks both STLs with `fabmesh check` and compares the
# volumes with the polygon's exact area x 30.
#
# Environment: RUNS (timed runs per command, default 10), SIZES (space-separated
# "K:H" pairs, default "2000:200 200000:2000"), KEEP=1 keeps the temporary
# folder, NO_HYPERFINE=1 times with a plain loop.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
fabmesh=${1:-$root/build-bench/pipeline/fabmesh}
runs=${RUNS:-10}
sizes=${SIZES:-"2000:200 200000:2000"}

bench_name=countertop_vs_openscad.sh
# shellcheck source=lib.sh
source "$here/lib.sh"

# make_inputs K H DIR: writes DIR/bench.yaml, DIR/bench.scad and prints the exact polygon area (mm^2).
make_inputs() {
  python3 - "$1" "$2" "$3" <<'PY'
import math, sys
K, H, d = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
q = 1024.0  # 2^-10 mm grid

def rounded_rect(cx, cy, w, h, r, n, ccw):
    # n points evenly spaced along the boundary of a rounded rectangle.
    sides = [w - 2 * r, h - 2 * r] * 2
    L = sum(sides) + 2 * math.pi * r
    pts = []
    for i in range(n):
        s = L * i / n
        x0, y0, ang = cx + w / 2 - r, cy - h / 2, 0.0  # start of the lower side's right end, heading +y around
        # walk: lower side (left->right), corner, right side, corner, top (right->left), corner, left side, corner
        segs = [("line", (cx - w / 2 + r, cy - h / 2), (1, 0), sides[0]), ("arc", (cx + w / 2 - r, cy - h / 2 + r), -90, None),
                ("line", (cx + w / 2, cy - h / 2 + r), (0, 1), sides[1]), ("arc", (cx + w / 2 - r, cy + h / 2 - r), 0, None),
                ("line", (cx + w / 2 - r, cy + h / 2), (-1, 0), sides[2]), ("arc", (cx - w / 2 + r, cy + h / 2 - r), 90, None),
                ("line", (cx - w / 2, cy + h / 2 - r), (0, -1), sides[3]), ("arc", (cx - w / 2 + r, cy - h / 2 + r), 180, None)]
        for kind, p, a, length in segs:
            length = length if kind == "line" else math.pi * r / 2
            if s <= length or kind == segs[-1][0] and p == segs[-1][1]:
                if kind == "line":
                    pts.append((p[0] + a[0] * s, p[1] + a[1] * s))
                else:
                    t = math.radians(a) + s / r
                    pts.append((p[0] + r * math.cos(t), p[1] + r * math.sin(t)))
                break
            s -= length
    return zigzag(pts, ccw)

def zigzag(pts, ccw):
    # Every other point moves 2^-7 mm outward: no vertex is (nearly) collinear with its neighbours, so
    # OpenSCAD keeps them all (it drops vertices within ~2e-5 mm of their neighbours' chord) and both
    # tools triangulate the same polygon. Then the 2^-10 mm grid.
    n = len(pts)
    out = []
    for i, (x, y) in enumerate(pts):
        if i % 2:
            (xa, ya), (xb, yb) = pts[i - 1], pts[(i + 1) % n]
            tx, ty = xb - xa, yb - ya
            t = math.hypot(tx, ty)
            x, y = x + ty / t / 128, y - tx / t / 128
        out.append((round(x * q) / q, round(y * q) / q))
    return out if ccw else out[::-1]

def ellipse(cx, cy, a, b, n, ccw):
    return zigzag([(cx + a * math.cos(2 * math.pi * i / n), cy + b * math.sin(2 * math.pi * i / n)) for i in range(n)], ccw)

def area(p):
    return 0.5 * sum(p[i][0] * p[(i + 1) % len(p)][1] - p[(i + 1) % len(p)][0] * p[i][1] for i in range(len(p)))

outer = rounded_rect(1200, 325, 2400, 650, 100, K, True)
holes = [rounded_rect(650, 330, 560, 400, 40, H, False), ellipse(1650, 330, 280, 230, H, False)]

loop_files = []

def curve(pts, indent):
    # One `polyline` entry whose points come from a CSV file beside the design
    # (straight lines through the points, closed back to the first).
    name = f"loop{len(loop_files)}.csv"
    loop_files.append(name)
    with open(f"{d}/{name}", "w") as csv:
        csv.write("".join(f"{x!r},{y!r}\n" for x, y in pts + [pts[0]]))
    return [f"{indent}family: tbezier", f"{indent}closed: true", f"{indent}segments:",
            f"{indent}  - polyline: {{file: {name}}}"]

y = ["name: bench", "kind: countertop", "units: mm", "tolerance: 0.01", "thickness: 30", "outputs: [stl]",
     "max_triangles: 50000000", "outline:"] + curve(outer, "  ") + ["holes:"]
for h in holes:
    y.append("  - outline:")
    y += curve(h, "      ")
open(f"{d}/bench.yaml", "w").write("\n".join(y) + "\n")

allp = outer + holes[0] + holes[1]
paths, start = [], 0
for loop in [outer] + holes:
    paths.append("[" + ",".join(str(i) for i in range(start, start + len(loop))) + "]")
    start += len(loop)
scad = "linear_extrude(height = 30) polygon(points = [" + ",".join(f"[{x!r},{yy!r}]" for x, yy in allp) + \
       "], paths = [" + ",".join(paths) + "]);\n"
open(f"{d}/bench.scad", "w").write(scad)
print(repr(area(outer) + area(holes[0]) + area(holes[1])))
PY
}

echo "fabmesh:  $fabmesh"
echo "openscad: $(openscad --version 2>&1 | head -n 1)"
echo "timing:   $([[ $have_hyperfine == 1 ]] && hyperfine --version || echo 'date loop') ($runs runs after 1 warm-up; peak RSS from /usr/bin/time -f %M)"
echo "machine:  $(nproc) cores, $(uname -srm), load average $(cut -d" " -f1-3 /proc/loadavg)"
echo

rows=()
timings=()
status=0
for size in $sizes; do
  K=${size%%:*}; H=${size##*:}
  d=$tmp/k${K}_h$H; mkdir -p "$d/fm" "$d/os"
  area=$(make_inputs "$K" "$H" "$d")
  vexact=$(awk -v a="$area" 'BEGIN {printf "%.17g", a * 30}')

  fm_cmd=("$fabmesh" run "$d/bench.yaml" -o "$d/fm" --json)
  "${fm_cmd[@]}" > "$d/fm.json" || die "fabmesh run failed on $d/bench.yaml"
  fm_stl=$(json "$d/fm.json" 'j["outputs"][0]')
  fm_tri=$(json "$d/fm.json" 'j["triangles"]')
  fm_vol=$(json "$d/fm.json" 'repr(j["volume"])')
  fm_pts=$(json "$d/fm.json" 'j["build"]["outline_points"]')
  [[ $fm_pts == "$K" ]] || { echo "note: fabmesh sampled $fm_pts outline points, not $K" >&2; status=1; }
  timings+=("K=$K H=$H triangles=$fm_tri: $(json "$d/fm.json" '", ".join("%s %.1f" % kv for kv in j["timings_ms"].items())')")
  fm_kb=$(peak_kb "${fm_cmd[@]}")

  os_cmd=(openscad -o "$d/os/out.stl" --export-format binstl "$d/bench.scad")
  os_kb=$(peak_kb "${os_cmd[@]}")

  read -r fm_ms fm_min < <(time_ms "fm_$K" "${fm_cmd[@]}")
  read -r os_ms os_min < <(time_ms "os_$K" "${os_cmd[@]}")

  check_outputs "$fm_stl" "$d/os/out.stl" "$d"
  checks=${checks#ok,}

  rows+=("$(awk -v k="$K" -v h="$H" -v ft="$fm_tri" -v ot="$os_tri" -v fms="$fm_ms" -v oms="$os_ms" -v fmin="$fm_min" \
      -v omin="$os_min" -v fkb="$fm_kb" -v okb="$os_kb" -v fv="$fm_vol" -v ov="$os_vol" -v ve="$vexact" -v ck="$checks" 'BEGIN {
    printf "| %6d | %4d | %7d | %7d | %8.1f (%8.1f) | %8.1f (%8.1f) | %6.2f (%6.2f) | %6.1f | %6.1f | %+.2e | %+.2e | %s |",
      k, h, ft, ot, fms, fmin, oms, omin, oms / fms, omin / fmin, fkb / 1024, okb / 1024, (fv - ve) / ve, (ov - ve) / ve, ck }')")
done

echo "|      K |    H | fm tris | os tris | fm ms med (min)     | os ms med (min)     | os/fm med (min) | fm MiB | os MiB | fm vol err | os vol err | checks |"
echo "|--------|------|---------|---------|---------------------|---------------------|-----------------|--------|--------|------------|------------|--------|"
printf '%s\n' "${rows[@]}"
echo
echo "K = outline points, H = points of each of the two holes; fm = fabmesh run --json (parse, region checks,"
echo "CDT, slab, validation, binary STL with fsync), os = openscad --export-format binstl; wall ms of whole"
echo "processes, median (min) of $runs runs; vol err = (volume - exact polygon area x 30) / exact."
echo
echo "fabmesh timings_ms (one run):"
printf '  %s\n' "${timings[@]}"
exit $status
