#!/usr/bin/python3
"""Runs dxf2gcode (Debian's 20191025 release) in batch mode on one DXF with a
given cut, for bench/gcode_vs_dxf2gcode.sh.

    dxf2gcode_batch.py IN.dxf OUT.ngc --tool 12 --depth 30 --step 10 \
        --feed 3000 --plunge 600 --spindle 18000 --safe 10

What it does, and why:
- dxf2gcode keeps its settings in ~/.config/dxf2gcode (run this with HOME
  pointing to a scratch folder): the tool (number 1: diameter, speed), the
  depths (top 0, slices of --step down to --depth, retract at --safe), the
  feeds, automatic cutter compensation on, and "done by machine" off, so that
  dxf2gcode writes the tool-centre path itself (G40) like fabmesh does,
  instead of G41/G42 for the controller.
- Its automatic compensation decides inside/outside by nesting among the
  shapes of one layer; fabmesh's DXF has the outline on OUTLINE and the holes
  on HOLES, so a copy with every entity on OUTLINE is what it reads (else it
  would cut the holes from the outside, into the part).
- Batch export (-q -e) of this release fails under Python 3.11 / PyQt 5.15 in
  GUI helpers it still calls (QFont with a float size in the route
  annotations, QScrollBar.setValue(1e9) in the log window): both are wrapped
  to take integers. Nothing of the import, offset or G-code writing is touched.
The program must run with Debian's /usr/bin/python3 (dxf2gcode, PyQt5,
configobj and ezdxf are Debian packages).
"""

import argparse
import os
import runpy
import sys


def configure(args):
    import dxf2gcode.globals.globals as g
    from dxf2gcode.globals.config import MyConfig
    import configobj

    g.folder = os.path.join(os.path.expanduser("~"), ".config/dxf2gcode")
    MyConfig()  # writes the default configuration when there is none
    path = os.path.join(g.folder, "config", "config.cfg")
    c = configobj.ConfigObj(path)
    depth = c["Depth_Coordinates"]
    depth["axis3_retract"] = str(args.safe)
    depth["axis3_safe_margin"] = "3.0"
    depth["axis3_start_mill_depth"] = "0.0"
    depth["axis3_slice_depth"] = str(-args.step)
    depth["axis3_mill_depth"] = str(-args.depth)
    c["Feed_Rates"]["f_g1_plane"] = str(args.feed)
    c["Feed_Rates"]["f_g1_depth"] = str(args.plunge)
    c["General"]["automatic_cutter_compensation"] = "True"
    c["General"]["tool_units"] = "mm"
    c["Cutter_Compensation"]["done_by_machine"] = "False"
    c["Tool_Parameters"]["1"]["diameter"] = str(args.tool)
    c["Tool_Parameters"]["1"]["speed"] = str(args.spindle)
    c.write()


def one_layer(source, target):
    import ezdxf

    doc = ezdxf.readfile(source)
    for entity in doc.modelspace():
        entity.dxf.layer = "OUTLINE"
    doc.saveas(target)


def patch_qt():
    from PyQt5 import QtGui, QtWidgets

    base_font = QtGui.QFont

    class QFont(base_font):
        def __init__(self, *a):
            super().__init__(*[int(x) if isinstance(x, float) else x for x in a])

    QtGui.QFont = QFont
    set_value = QtWidgets.QAbstractSlider.setValue
    QtWidgets.QAbstractSlider.setValue = lambda self, v: set_value(self, int(min(v, 2**31 - 1)))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("dxf")
    p.add_argument("out")
    for name, default in (("tool", 12.0), ("depth", 30.0), ("step", 10.0), ("feed", 3000.0),
                          ("plunge", 600.0), ("spindle", 18000.0), ("safe", 10.0)):
        p.add_argument("--" + name, type=float, default=default)
    args = p.parse_args()
    if not os.path.isfile(args.dxf):  # dxf2gcode would wait on a dialog box
        sys.exit("dxf2gcode_batch: no such file: " + args.dxf)
    configure(args)
    merged = args.out + ".one_layer.dxf"
    one_layer(args.dxf, merged)
    patch_qt()
    sys.argv = ["dxf2gcode", "-q", "-e", args.out, merged]
    runpy.run_path("/usr/bin/dxf2gcode", run_name="__main__")


if __name__ == "__main__":
    main()
