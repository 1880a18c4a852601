# Run by FreeCAD's command line (freecadcmd): imports each STEP file named in
# FABMESH_STEP_FILES (separated by ':') with FreeCAD's Part workbench and
# prints one JSON line per file: valid, closed, solids, shells, faces, edges,
# volume, area; for the files also named in FABMESH_STEP_PIECES, the largest
# volume two of its solids have in common ("overlap": pieces that go
# together, such as a master's sections, must share none).
# The shell test (freecad_step_test.sh) judges them.
import json
import os

import Part

pieces = set(filter(None, os.environ.get("FABMESH_STEP_PIECES", "").split(":")))

for path in os.environ["FABMESH_STEP_FILES"].split(":"):
    shape = Part.Shape()
    try:
        shape.read(path)
        facts = {
            "path": path,
            "read": True,
            "valid": shape.isValid(),
            "closed": all(s.isClosed() for s in shape.Shells) if shape.Shells else False,
            "solids": len(shape.Solids),
            "shells": len(shape.Shells),
            "faces": len(shape.Faces),
            "edges": len(shape.Edges),
            "volume": shape.Volume if shape.Solids else 0.0,
            "area": shape.Area,
        }
        if path in pieces:
            solids = shape.Solids
            facts["overlap"] = max(
                (solids[i].common(solids[j]).Volume for i in range(len(solids)) for j in range(i + 1, len(solids))),
                default=0.0,
            )
    except Exception as e:  # FreeCAD raises its own Base.FreeCADError
        facts = {"path": path, "read": False, "error": str(e)}
    print("FABMESH_STEP " + json.dumps(facts), flush=True)
