"""The countertop polygon the countertop benchmarks give both tools.

    python3 bench/countertop_polygon.py K H DIR

Writes DIR/bench.yaml (a fabmesh countertop whose three loops are `polyline`
CSV files beside it, DIR/loop0.csv...) and DIR/bench.scad (OpenSCAD's
linear_extrude of the same polygon, `thickness` a variable that `-D
thickness=...` sets, 30 by default as in the design), and prints the
polygon's exact area (mm^2). The outline is a 2400 x 650 mm rounded rectangle
of K points, the sink a rounded rectangle and the cooktop an ellipse of H
points each, every other point moved 2^-7 mm outward and all on a 2^-10 mm
grid, so both tools read and triangulate the same coordinates.
"""
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
scad = "thickness = 30;\nlinear_extrude(height = thickness) polygon(points = [" + ",".join(f"[{x!r},{yy!r}]" for x, yy in allp) + \
       "], paths = [" + ",".join(paths) + "]);\n"
open(f"{d}/bench.scad", "w").write(scad)
print(repr(area(outer) + area(holes[0]) + area(holes[1])))
