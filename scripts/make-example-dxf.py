#!/usr/bin/python3
"""Writes the DXF templates the examples read (configs/examples/*.dxf) with
ezdxf, as a shop's CAD or templating system would: entities of mixed kinds
drawn in no particular order or direction, text and points beside them, other
layers. Run it again after changing it; the files are committed.

    /usr/bin/python3 scripts/make-example-dxf.py [OUT_DIR]   (default: configs/examples)
"""
import math
import pathlib
import sys

import ezdxf


def kitchen_template(path):
    """A 2400 x 650 mm worktop: a quarter-round front-left corner (ARC), a
    bulged front-right corner (one LWPOLYLINE span), straight edges drawn as
    LINEs, some backwards; a sink (closed LWPOLYLINE with bulged corners), a
    tap hole (CIRCLE) and an oval cut-out (ELLIPSE) on layer HOLES."""
    doc = ezdxf.new("R2010", setup=False)
    doc.header["$INSUNITS"] = 4  # millimetres
    doc.header["$MEASUREMENT"] = 1
    for name in ("OUTLINE", "HOLES", "NOTES"):
        doc.layers.add(name)
    msp = doc.modelspace()
    out = {"layer": "OUTLINE"}
    r = 80.0
    # Outline, counter-clockwise from the front-left corner's end: front edge,
    # the front-right corner as a bulged polyline span, right, back, left edges,
    # and the front-left corner arc.
    msp.add_line((r, 0), (2300, 0), dxfattribs=out)
    # A quarter turn to the left: bulge tan(90 / 4 degrees).
    msp.add_lwpolyline([(2300, 0, 0, 0, math.tan(math.radians(22.5))), (2400, 100)],
                       format="xyseb", dxfattribs=out)
    msp.add_line((2400, 650), (2400, 100), dxfattribs=out)  # drawn backwards
    msp.add_line((2400, 650), (0, 650), dxfattribs=out)
    msp.add_line((0, r), (0, 650), dxfattribs=out)  # backwards
    msp.add_arc((r, r), r, 180, 270, dxfattribs=out)
    msp.add_text("FRONT", dxfattribs={"layer": "OUTLINE", "height": 25}).set_placement((1100, 40))
    holes = {"layer": "HOLES"}
    # Sink: 760 x 440 with 60 mm corners, centred at (1500, 330), clockwise as drawn.
    cx, cy, hw, hh, rc = 1500.0, 330.0, 380.0, 220.0, 60.0
    q = math.tan(math.radians(22.5))
    sink = [
        (cx - hw + rc, cy - hh, 0), (cx + hw - rc, cy - hh, q),
        (cx + hw, cy - hh + rc, 0), (cx + hw, cy + hh - rc, q),
        (cx + hw - rc, cy + hh, 0), (cx - hw + rc, cy + hh, q),
        (cx - hw, cy + hh - rc, 0), (cx - hw, cy - hh + rc, q),
    ]
    msp.add_lwpolyline(sink, format="xyb", close=True, dxfattribs=holes)
    msp.add_circle((1500, 600 - 10), 17.5, dxfattribs=holes)  # tap hole
    msp.add_ellipse((600, 330), major_axis=(200, 0), ratio=0.6, dxfattribs=holes)
    msp.add_point((1500, 330), dxfattribs=holes)
    msp.add_text("SINK", dxfattribs={"layer": "NOTES", "height": 30}).set_placement((1450, 320))
    msp.add_line((0, -50), (2400, -50), dxfattribs={"layer": "NOTES"})
    doc.saveas(path)


def main():
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "configs/examples")
    kitchen_template(out / "kitchen_template.dxf")


if __name__ == "__main__":
    main()
