#pragma once
// `check --mark OUT.glb|OUT.ply`: the checked mesh written with its
// defective faces coloured by defect kind, and the legend of the colours.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/validation/validate.h"
#include "pipeline/check_mesh.h"

namespace fabmesh {

/// One colour of a marked mesh: a defect kind's faces, or the faces without a defect.
struct MarkColour {
  std::string key;    ///< the defect kind's key (to_key), or "none"
  std::string words;  ///< "faces on a boundary edge", ... for the legend
  std::string name;   ///< the colour's name: "red", "orange", ...
  std::array<std::uint8_t, 3> rgb;
  std::size_t faces = 0;  ///< faces drawn in it
};

/// A checked file's mesh with each face assigned a colour.
struct MarkedMesh {
  TriangleSoup soup;                       ///< every object's welded mesh, one after the other
  std::vector<std::uint32_t> face_colour;  ///< per face: index into colours
  std::vector<MarkColour> colours;         ///< the defect kinds in Defect order, then "none"
  std::string units;                       ///< the file's, or empty
};

/// The faces of `check`'s objects coloured by the first defect kind (in
/// Defect order) that lists them: faces on a boundary, non-manifold or
/// inconsistently oriented edge, around a non-manifold vertex, degenerate,
/// duplicated, intersecting another, or of an inverted or wrongly nested
/// component; the rest light grey. Needs a check made with
/// CheckOptions::keep_for_marking (every location and the welded meshes).
/// \pre check.readable
MarkedMesh marked_mesh(const FileCheck& check);

/// Writes `marked` to `path` (atomically): `.glb` with one primitive and
/// material per colour (in metres, Y up, from the file's unit or mm), or
/// `.ply` with per-face red, green and blue.
/// \throw InputError when `path` ends in neither .glb nor .ply; FileError
///        or MachineError when it cannot be written.
void write_marked(const MarkedMesh& marked, const std::string& path);

/// The legend: "red: 12 self-intersecting faces" per colour with faces.
std::vector<std::string> legend_lines(const MarkedMesh& marked);

}  // namespace fabmesh
