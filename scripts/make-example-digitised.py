#!/usr/bin/env python3
"""Writes configs/examples/countertop_digitised.csv: a worktop outline as a
templating system's digitiser gives it, a dense list of points rounded to
0.01 mm. Its front edge is a concave arc of radius 19 m (rising 38 mm into
the part at the middle) by 301 points, its back corners are rounded convexly
(radius 100 mm) by 41 points each; the left edge closes the loop in the
design. Deterministic: run it again, get the same bytes."""
import math
import pathlib

OUT = pathlib.Path(__file__).resolve().parent.parent / "configs" / "examples" / "countertop_digitised.csv"


def points():
    r = 19000.0
    lift = math.sqrt(r * r - 1200.0 * 1200.0)
    for i in range(301):
        x = 2400.0 * i / 300
        yield x, math.sqrt(r * r - (x - 1200.0) ** 2) - lift
    for i in range(41):
        a = math.pi / 2 * i / 40
        yield 2300 + 100 * math.cos(a), 550 + 100 * math.sin(a)
    for i in range(41):
        a = math.pi / 2 + math.pi / 2 * i / 40
        yield 100 + 100 * math.cos(a), 550 + 100 * math.sin(a)


def fmt(v):
    s = f"{v:.2f}"
    return "0.00" if s == "-0.00" else s


def main():
    rows = [f"{fmt(x)},{fmt(y)}" for x, y in points()]
    OUT.write_text("\n".join(rows) + "\n", encoding="ascii")
    print(f"wrote {OUT} ({len(rows)} points)")


if __name__ == "__main__":
    main()
