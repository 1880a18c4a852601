"""Reads a DXF drawing with ezdxf as a fabricator's CAD would, and prints
what the kitchen tests check, as JSON: the audit's errors and fixes, every
DIMENSION (layer, kind, measurement, definition points, whether its block of
geometry is there), every TEXT (layer, text, height), each layer's entities'
boxes, and the drawing's box.

Usage: python3 dxf_sheet_dump.py FILE.dxf
"""
import json
import logging
import sys

import ezdxf
from ezdxf import bbox

# ezdxf's text boxes ask matplotlib for a font, which logs each miss.
logging.getLogger("matplotlib").setLevel(logging.ERROR)

doc = ezdxf.readfile(sys.argv[1])
audit = doc.audit()
msp = doc.modelspace()
dims = []
for d in msp.query("DIMENSION"):
    block = d.get_geometry_block()
    dims.append({
        "layer": d.dxf.layer,
        "kind": d.dimtype,
        "measurement": d.get_measurement(),
        "from": list(d.dxf.defpoint2)[:2],
        "to": list(d.dxf.defpoint3)[:2],
        "angle": d.dxf.get("angle", 0.0),
        "block": block is not None and len(block) > 0,
    })
texts = [{"layer": t.dxf.layer, "text": t.dxf.text, "height": t.dxf.height} for t in msp.query("TEXT")]
boxes = []
for e in msp:
    if e.dxftype() in ("DIMENSION", "TEXT"):
        continue
    b = bbox.extents([e])
    boxes.append({"layer": e.dxf.layer, "type": e.dxftype(), "lo": list(b.extmin)[:2], "hi": list(b.extmax)[:2]})
whole = bbox.extents(msp)
print(json.dumps({
    "errors": [str(x.message) for x in audit.errors],
    "fixes": [str(x.message) for x in audit.fixes],
    "dimstyle_text": doc.dimstyles.get("Standard").dxf.get("dimtxt", 0.0),
    "dimensions": dims,
    "texts": texts,
    "boxes": boxes,
    "lo": list(whole.extmin)[:2],
    "hi": list(whole.extmax)[:2],
}))
