# Run by FreeCAD's command line (freecadcmd): for each casting case named in
# FABMESH_CASES (entries "CASE.step=MOULD.step=INDEX=PIECES=DRAFT=ERROR", separated by ':'),
# imports the case and the mould's part INDEX (the mould's STEP file holds its
# parts in order) and prints one JSON line: the case's validity and solids
# (its pieces: a two-piece case's main piece and plate), the volume its
# pieces share, its box's volume, and the volumes of the case and the part
# in common and fused (with the gaps round the pins of a two-piece case,
# voids of its joined pieces, counted in), with DRAFT, the volume the report
# says its draft leans off the part (mm^3) and ERROR, how far that may lie
# from the exact part's. Plaster cast in the case is the
# part less those wedges when they share just that volume and together fill
# the case's box. The shell test (freecad_step_test.sh) judges them.
import json
import os

import Part

for entry in os.environ["FABMESH_CASES"].split(":"):
    case_path, mould_path, index, pieces, draft, draft_error = entry.split("=")
    facts = {"path": case_path, "pieces": int(pieces), "draft": float(draft), "draft_error": float(draft_error)}
    try:
        case = Part.read(case_path)
        part = Part.read(mould_path).Solids[int(index)]
        box = case.BoundBox
        pieces = case.Solids
        facts.update({
            "valid": case.isValid() and all(p.isValid() for p in pieces),
            "solids": len(pieces),
            "pieces_common": sum(a.common(b).Volume for i, a in enumerate(pieces) for b in pieces[i + 1:]),
            "closed": all(s.isClosed() for s in case.Shells),
            "volume": case.Volume,
            "part_volume": part.Volume,
            "part_area": part.Area,
            "box_volume": box.XLength * box.YLength * box.ZLength,
            "part_inside": box.isInside(part.BoundBox),
            "common": case.common(part).Volume,
        })
        # The pieces put together: shut in, the gaps the plate's pins leave
        # in their holes (each a void of the joined pieces, its own shell).
        whole = pieces[0]
        for piece in pieces[1:]:
            whole = whole.fuse(piece)
        gaps = [sh for s in whole.Solids for sh in s.Shells if not sh.isSame(s.OuterShell)]
        facts["voids"] = len(gaps)
        facts["voids_volume"] = sum(abs(Part.Solid(sh).Volume) for sh in gaps)
        # Case and part together: the box, but for those gaps (the joined
        # pieces fused with the part: FreeCAD fuses a compound of several
        # solids with another less reliably).
        facts["fused"] = whole.fuse(part).Volume + facts["voids_volume"]
    except Exception as e:  # FreeCAD raises its own Base.FreeCADError
        facts["error"] = str(e)
    print("FABMESH_CASE " + json.dumps(facts), flush=True)
