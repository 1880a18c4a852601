#!/usr/bin/env bash
# Every bundled example that can have a STEP file gets one, each written by
# its own `fabmesh run` process, and FreeCAD's command line (freecadcmd, with
# OpenCASCADE's reader inside) imports each: a valid shape; for a countertop
# or a vessel one closed solid of positive volume; for a curve a wireframe;
# for a mould (`mould_step`, every example with a `mould:`) one closed solid
# per part, as many as the mould's STL parts; for an open surface one open
# shell of B-spline faces, one per patch, of positive area.
# A casting master (`master_step`, every example with a `mould:`) is one
# closed solid of the exact volume its report gives (vessel and spare).
# The golden solid, designed in cm, must come in at 46.171424531125 cm^3
# (FreeCAD works in mm): the file's unit is read as written.
# A kitchen (an example with `slab:`) writes one STEP file per piece (and per
# backsplash strip): each is one closed solid, and the top's pieces' volumes
# add up to that of the whole top (the same design without its kitchen keys
# and router cut) within 1e-9.
# The island's profiled top (a half bullnose, filleted by OpenCASCADE) must
# have its exact volume within 1e-9. The U kitchen's pieces with a half
# bullnose and a full one (the rounds stopping on walls and seams) are
# closed solids too.
# A casting case (case_step, every example whose mould is a box) is one closed
# solid that shares with its mould part only the wedges its draft leans off
# the part's free faces (the volume its report gives) and together with it
# fills its box: plaster cast in it is that part, leaned.
# A thickened surface is one closed solid too: the bundled basin's 4 patches
# make 4 faces on each sheet and 8 walls along the rim's sides.
# Usage: freecad_step_test.sh FABMESH SOURCE_DIR
set -uo pipefail
fabmesh=$1 source=$2
command -v freecadcmd >/dev/null || { echo "FAIL: freecadcmd is not installed (scripts/install-deps.sh --test)"; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/fabmesh-freecad.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

files=()
pieces=()  # files of pieces that go together: no two may share volume
declare -A mould_parts  # a mould's STEP file name -> its number of parts
declare -A master_volume  # a casting master's STEP file name -> its exact volume in mm^3 (run --json)
# The casting master of DESIGN (with the mould's spare), written as NAME with
# the -D options that follow: one closed solid of the exact volume the report
# gives; cut for print.bed, one per section (a half, a quarter), together that
# volume plus each joint's pin minus its hole (one joint between sections,
# and one at each half-plane of a section cut through its axis).
add_master() {
  local design=$1 name=$2 step volume solids
  shift 2
  if (cd "$source/configs/examples" && "$fabmesh" run "$design" "$@" --export-format master_step \
      -o "$work/$name-master/" --json) >"$work/$name-master.json" 2>"$work/$name-master.log"; then
    step=$(compgen -G "$work/$name-master/*.master.step" | head -n 1)
    [[ -n $step ]] || { fail "$name: exit 0 but no master STEP file"; return; }
    files+=("$step")
    read -r volume solids < <(python3 -c '
import json, math, sys
d = json.load(open(sys.argv[1]))
d = d[0] if isinstance(d, list) else d
mm = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4}[d["units"]]
m = d["build"]["master"]
volume, solids = m["volume"], 1
if "sections" in m:
    sectors, pin = m["sectors"], m["pin"]
    levels = len(m["sections"]) // sectors
    joints = levels - 1 + (levels * sectors if sectors > 1 else 0)
    volume += joints * math.pi * ((pin["diameter"] / 2) ** 2 * pin["height"]
                                  - (pin["hole_diameter"] / 2) ** 2 * pin["hole_depth"])
    solids = len(m["sections"])
print(repr(volume * mm ** 3), solids)' "$work/$name-master.json")
    master_volume[$(basename "$step")]=$volume
    mould_parts[$(basename "$step")]=$solids
    ((solids == 1)) || pieces+=("$step")
  else
    cat "$work/$name-master.log"
    fail "$name: no master STEP file"
  fi
}
kitchens=()             # "WHOLE.step:PIECE-1.step:PIECE-2.step..." per kitchen example
for design in "$source"/configs/examples/*.yaml; do
  name=$(basename "$design" .yaml)
  [[ $name == batch_* ]] && continue  # manifests, not designs
  if (cd "$source/configs/examples" && "$fabmesh" run "$design" --export-format step -o "$work/$name/" -q) \
    >"$work/$name.log" 2>&1; then
    step=$(compgen -G "$work/$name/*.step" | head -n 1)
    [[ -n $step ]] || { fail "$name: exit 0 but no STEP file"; continue; }
    if grep -q '^slab:' "$design"; then
      mapfile -t pieces < <(compgen -G "$work/$name/$name.piece-*.step" | sort -V)
      ((${#pieces[@]} >= 2)) || fail "$name: a kitchen wrote ${#pieces[@]} piece STEP file(s)"
      files+=("${pieces[@]}")
      mapfile -t strips < <(compgen -G "$work/$name/$name.backsplash-*.step" | sort -V)
      files+=("${strips[@]}")  # each one closed solid too, not part of the top
      # The whole top: the same design without its slab and seams (nor its router cut).
      /usr/bin/python3 - "$design" "$work/$name-whole.yaml" <<'PY'
import os, sys, yaml
d = yaml.safe_load(open(sys.argv[1]))
for key in ("slab", "seams", "seam_clearance", "backsplash", "cnc"):
    d.pop(key, None)
for segment in d["outline"].get("segments", []):
    segment.pop("edge", None)  # walls are a kitchen's
if "dxf" in d["outline"]:  # a template's outline: the drawing beside the design, walls a kitchen's
    d["outline"]["dxf"] = os.path.join(os.path.dirname(os.path.abspath(sys.argv[1])), d["outline"]["dxf"])
    d["outline"].pop("walls", None)
d["outputs"] = ["step"]
yaml.safe_dump(d, open(sys.argv[2], "w"))
PY
      if "$fabmesh" run "$work/$name-whole.yaml" -o "$work/$name-whole/" -q >"$work/$name-whole.log" 2>&1; then
        files+=("$work/$name-whole/$name.step")
        kitchens+=("$(IFS=:; echo "$work/$name-whole/$name.step:${pieces[*]}")")
      else
        cat "$work/$name-whole.log"
        fail "$name: the whole top wrote no STEP file"
      fi
    else
      files+=("$step")
    fi
  else
    cat "$work/$name.log"
    fail "$name: no STEP file"
  fi
  grep -q '^mould:' "$design" || continue
  if (cd "$source/configs/examples" && "$fabmesh" run "$design" --export-format mould_step -o "$work/$name-mould/" -q \
      && "$fabmesh" run "$design" --export-format mould_stl -o "$work/$name-mould-stl/" -q) >"$work/$name-mould.log" 2>&1; then
    parts=$(compgen -G "$work/$name-mould-stl/*.stl" | wc -l)
    step=$(compgen -G "$work/$name-mould/*.mould.step" | head -n 1)
    [[ -n $step ]] || { fail "$name: exit 0 but no mould STEP file"; continue; }
    files+=("$step")
    mould_parts[$(basename "$step")]=$parts
  else
    cat "$work/$name-mould.log"
    fail "$name: no mould STEP file"
  fi
  add_master "$design" "$name"
done
# A master wider than the bed as well as taller: each of its 2 sections in quarters.
add_master mould_vase_production.yaml mould_vase_quarters -D name=mould_vase_quarters -D 'print.bed=[150,150,220]'
# The U kitchen's pieces with a half bullnose and with a full one (the two rounds meeting at mid-height):
# the rounds stop on the walls and at the seams they run on into tangentially, cut as the mesh stops them
# (not filleted): each piece one closed solid too.
for edges in 'half_bullnose, radius: 12' 'bullnose'; do
  out="$work/kitchen_u-${edges%%,*}"
  if (cd "$source/configs/examples" && "$fabmesh" run kitchen_u.yaml -D "edges={exposed: $edges}" \
      -D slab.spacing=40 -D 'outputs=[step]' -o "$out/" -q) >"$out.log" 2>&1; then
    mapfile -t profiled < <(compgen -G "$out/kitchen_u.piece-*.step" | sort -V)
    ((${#profiled[@]} == 3)) || fail "kitchen_u with edges $edges wrote ${#profiled[@]} piece STEP file(s), not 3"
    files+=("${profiled[@]}")
  else
    cat "$out.log"
    fail "kitchen_u with edges $edges: no STEP files"
  fi
done
# Casting cases (`case_step`, every example whose mould is a box, and the
# golden ones in three keyed parts, as a box and as a cylinder): each one
# closed solid, or two (a case and its plate, when the mesh case has a
# plate), or as many as the pieces
# the mesh case is carved in, sharing no volume; with its mould part (mould_step) the case shares
# the draft's wedges (the report's draft.volume, within its volume_error, 1e-6 of it and 1e-9 of
# the part's area, in mm) and nothing more, and fills the case's box
# (within 1e-9), but for one closed gap round each of a plate's or piece's two pins; the
# case's and the part's volumes and the gaps add up to the box's (within
# 1e-6, as FreeCAD integrates them).
cases=()
# The cases of DESIGN (named NAME, run with the -D overrides after it) written to OUT.
case_steps() {
  local design=$1 out=$2 name=$3
  shift 3
  if (cd "$source/configs/examples" && "$fabmesh" run "$design" -D 'outputs=[case_step, mould_step, case_stl]' \
      "$@" -o "$out/" --json) >"$out.json" 2>"$out.log"; then
    mapfile -t written < <(compgen -G "$out/$name.case-*.step" | sort -V)
    ((${#written[@]} >= 1)) || fail "$name: no case STEP file"
    parts=$(grep -c '^#[0-9]* = MANIFOLD_SOLID_BREP' "$out/$name.mould.step")
    for c in "${written[@]}"; do
      part=${c##*.case-}
      part=${part%.step}
      if [[ $part == base ]]; then index=$((parts - 1)); else index=$((${part#side-} - 1)); fi
      # The case, and its plate or the pieces it is carved in (one STL each).
      pieces=$((1 + $(compgen -G "$out/$name.case-$part-p*.stl" | wc -l)))
      # What the draft takes from the part as the case casts it, in mm^3 (run --json).
      draft=$(python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))[0]
mm = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4}[d["units"]]
case = next(c for c in d["build"]["mould"]["cases"] if c["part"] == sys.argv[2])
print(repr(case["draft"]["volume"] * mm ** 3) + "=" + repr(case["draft"]["volume_error"] * mm ** 3))' \
        "$out.json" "$part")
      cases+=("$c=$out/$name.mould.step=$index=$pieces=$draft")
      mould_parts[$(basename "$c")]=$pieces
      files+=("$c")
    done
  else
    cat "$out.log"
    fail "$name: no case STEP files"
  fi
}
for design in "$source"/configs/examples/*.yaml; do
  grep -q '^  block: box' "$design" || continue
  case_steps "$design" "$work/$(basename "$design" .yaml)-cases" "$(basename "$design" .yaml)"
done
# Three keyed parts on a keyed base: each side's case carved in three or four pieces.
case_steps "$source/configs/examples/mould_golden_box_base.yaml" "$work/golden_three-cases" golden_three \
  -D name=golden_three -D mould.parts=3 -D mould.key_clearance=0.1
# The golden cylinder mould (two keyed parts): each side's case lidded, its base's in one piece.
case_steps "$source/configs/examples/mould_golden.yaml" "$work/golden_cylinder-cases" golden_cylinder \
  -D name=golden_cylinder
# The golden cylinder mould in three keyed parts: each lid, the pieces beyond the slanted split faces.
case_steps "$source/configs/examples/mould_golden.yaml" "$work/golden_cylinder_three-cases" golden_cylinder_three \
  -D name=golden_cylinder_three -D mould.parts=3 -D mould.key_clearance=0.1
# The production vase's default mould: three keyed sides on a keyed base, the middle side's slice
# taken from the floor up past its base key's bump (on a bed its pieces fit whole, one STL each).
case_steps "$source/configs/examples/mould_vase_production.yaml" "$work/vase_round-cases" vase_round \
  -D name=vase_round -D 'print.bed=[400,400,400]'
((${#cases[@]} >= 3)) || fail "only ${#cases[@]} casting cases written"
FABMESH_CASES=$(IFS=:; echo "${cases[*]}") timeout 600 freecadcmd "$source/tests/io/step/freecad_case_check.py" \
  >"$work/freecad-cases.log" 2>&1
judged=0
while IFS= read -r line; do
  judged=$((judged + 1))
  verdict=$(python3 - "${line#FABMESH_CASE }" <<'PY'
import json, os, sys
f = json.loads(sys.argv[1])
name = os.path.basename(f["path"])
problems = []
if "error" in f:
    problems.append("not read: " + f["error"])
else:
    if not f["valid"] or f["solids"] != f["pieces"] or not f["closed"]:
        problems.append(f"not {f['pieces']} valid closed solid(s): {f}")
    if f["pieces_common"] > 1e-9 * f["part_area"]:
        problems.append(f"its pieces share {f['pieces_common']} mm^3")
    if not f["part_inside"]:
        problems.append("its part is not inside its box")
    # The draft leans the part's free faces: the case takes the wedges
    # beyond them, the volume the report gives within its bound (a curved
    # face meeting a leaned one, a spare's wall, is the mesh's within the
    # tolerance), and shares nothing else.
    if abs(f["common"] - f["draft"]) > f["draft_error"] + 1e-6 * f["draft"] + 1e-9 * f["part_area"]:
        problems.append(f"shares {f['common']} mm^3 with its part, not the {f['draft']} its draft leans off")
    if abs(f["fused"] / f["box_volume"] - 1) > 1e-9:
        problems.append(f"with its part fills {f['fused']} mm^3 of its box's {f['box_volume']}")
    # A plate's two pins leave a gap each in their holes (the clearance), shut in.
    if f["voids"] != 2 * (f["pieces"] - 1):
        problems.append(f"{f['voids']} voids with its part, not the {2 * (f['pieces'] - 1)} round its pins")
    # Integrated over curved faces (the cavity's B-splines) by FreeCAD at a
    # fixed order: on mould_golden_box_base's side 2 its volume of the mould
    # part is 0.059 mm^3 (1.4e-7) off OpenCASCADE's adaptive integral to
    # 1e-12, so the sum is held to 1e-6. The exact checks are the common
    # volume and the fused one above, and the STEP module's own, adaptive to
    # 1e-10, which holds each case to 1e-9 of its box.
    if abs((f["volume"] + f["part_volume"] + f["voids_volume"] - f["common"]) / f["box_volume"] - 1) > 1e-6:
        problems.append(f"case {f['volume']} + part {f['part_volume']} + gaps {f['voids_volume']} "
                        f"- in common {f['common']} is not its box's {f['box_volume']}")
print(name + (": " + "; ".join(problems) if problems else
              f": cast, it is its part less its draft's wedges (in common {f['common']:.6g} mm^3 of "
              f"{f['draft']:.6g}, together its box)"))
sys.exit(1 if problems else 0)
PY
  ) || fail "$verdict"
  echo "$verdict"
done < <(grep '^FABMESH_CASE ' "$work/freecad-cases.log")
if ((judged != ${#cases[@]})); then
  cat "$work/freecad-cases.log"
  fail "FreeCAD reported on $judged of ${#cases[@]} casting cases"
fi
((${#files[@]} >= 5)) || fail "only ${#files[@]} STEP files written"

list=$(IFS=:; echo "${files[*]}")
FABMESH_STEP_PIECES=$(IFS=:; echo "${pieces[*]}") FABMESH_STEP_FILES=$list timeout 600 freecadcmd "$source/tests/io/step/freecad_check.py" >"$work/freecad.log" 2>&1
checked=0
while IFS= read -r line; do
  json=${line#FABMESH_STEP }
  checked=$((checked + 1))
  step_name=$(python3 -c 'import json, os, sys; print(os.path.basename(json.loads(sys.argv[1])["path"]))' "$json")
  verdict=$(python3 - "$json" "${mould_parts[$step_name]:-1}" "${master_volume[$step_name]:-}" <<'PY'
import json, os, sys
f = json.loads(sys.argv[1])
solids = int(sys.argv[2])
master_volume = float(sys.argv[3]) if sys.argv[3] else None
name = os.path.basename(f["path"])
problems = []
if not f.get("read"):
    problems.append("not read: " + f.get("error", ""))
else:
    if not f["valid"]:
        problems.append("not valid")
    curve = f["solids"] == 0 and f["faces"] == 0
    sheet = f["solids"] == 0 and f["faces"] > 0
    if curve:
        if f["edges"] < 1:
            problems.append("no edges")
    elif sheet:
        if f["shells"] != 1 or f["closed"] or not f["area"] > 0:
            problems.append(f"not one open shell of positive area: {f}")
    elif f["solids"] != solids or not f["closed"] or not f["volume"] > 0:
        problems.append(f"not {solids} closed solid(s): {f}")
    if name == "surface_basin_open.step" and (not sheet or f["faces"] != 4):
        problems.append(f"not a shell of 4 faces (one per patch): {f}")
    if name == "surface_basin_shell.step" and (f["solids"] != 1 or f["faces"] != 16):
        problems.append(f"not one solid of 16 faces (4 per sheet, 8 walls): {f}")
    if name == "countertop_island.step":
        # The half bullnose's exact volume: the slab less 10 (1 - pi/4) mm^2
        # along each edge, plus the mitred corners' overlap, less the sink.
        from math import pi
        exact = (2400 * 1000 * 30 - 2 * 3400 * 100 * (1 - pi / 4) + 4 * 1000 * (5 / 3 - pi / 2)
                 - 30 * (760 * 460 - (4 - pi) * 40 ** 2))
        if abs(f["volume"] / exact - 1) > 1e-9:
            problems.append(f"volume {f['volume']} mm^3, not the exact {exact}")
    if master_volume is not None and abs(f["volume"] / master_volume - 1) > 1e-7:
        problems.append(f"volume {f['volume']} mm^3, not the master's exact {master_volume}")
    # Pieces that go together (pins in holes with their clearance, cut faces touching) share no volume.
    if "overlap" in f and f["overlap"] > 1e-9 * f["volume"]:
        problems.append(f"two of its {f['solids']} pieces share {f['overlap']} mm^3")
    if name == "vessel_golden_solid.step" and abs(f["volume"] / 46171.424531125 - 1) > 1e-7:
        problems.append(f"volume {f['volume']} mm^3, not 46171.424531125 (46.171424531125 cm^3)")
print(name + (": " + "; ".join(problems) if problems else ": ok"))
sys.exit(1 if problems else 0)
PY
  ) || fail "$verdict"
  echo "$verdict"
done < <(grep '^FABMESH_STEP ' "$work/freecad.log")
for kitchen in "${kitchens[@]}"; do
  verdict=$(python3 - "$kitchen" "$work/freecad.log" <<'PY'
import json, os, sys
paths = sys.argv[1].split(":")
volumes = {}
for line in open(sys.argv[2]):
    if line.startswith("FABMESH_STEP "):
        f = json.loads(line[len("FABMESH_STEP "):])
        volumes[f["path"]] = f.get("volume", 0.0)
whole, pieces = paths[0], paths[1:]
total = sum(volumes.get(p, 0.0) for p in pieces)
name = os.path.basename(whole)
if whole not in volumes or abs(total / volumes[whole] - 1) > 1e-9:
    print(f"{name}: pieces' volumes add up to {total}, the whole top's is {volumes.get(whole)}")
    sys.exit(1)
print(f"{name}: {len(pieces)} pieces' volumes add up to the whole top's, {volumes[whole]:.6f} mm^3")
PY
  ) || fail "$verdict"
  echo "$verdict"
done
if ((checked != ${#files[@]})); then
  cat "$work/freecad.log"
  fail "FreeCAD reported on $checked of ${#files[@]} files"
fi
if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "FreeCAD imports all ${#files[@]} STEP files: valid, each solid closed, each sheet one shell"
