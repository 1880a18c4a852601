#pragma once
// A piece of a casting case cut into sections that fit a printer's bed, in
// the frame it is printed in (standing, +z up). The piece's box is cut into
// equal cells by planes across x, y and z: along each axis the fewest that
// fit the bed with a pin on the cell's upper face, the bed turned a quarter
// about z when that takes fewer cells. Each cell is what of the piece lies in
// it, cut by CGAL's corefinement over exact constructions.
//
// Every joint (each region of the face two neighbouring cells share) is
// registered by two pins in the piece's material, as far apart as the
// region allows: a pin of the lower cell (along the cut axis) stands up into
// a hole of the upper one, as the carved pieces' pins do (a quarter of the
// case wall in radius, half of it tall, buried a quarter of it into its own
// cell; the hole wider all round and deeper by the case's clearance). Where
// a pin may stand is looked for half a wall inside the piece's box and half
// a wall inside every face the cut crosses (the middle of the case's walls):
// the hole and the pin's foot, with a sixteenth of the wall more all round,
// must meet no face of the piece and lie inside it. A cell in which the
// piece lies in several solids gives a section for each.
//
// Each cut lies near its equal share, moved within the room the bed leaves
// as far as it can from the piece's corners. Where that leaves a sliver
// (thinner than 1e-6 of the piece, which moving the section or writing it in
// single precision could fold), or a joint has no room for its pins, or a
// section no pins, the cuts are tried again at other places in that room.
//
// Proven: every section is a valid solid (validated in full) of one piece;
// the sections' volumes add up to the piece's, plus what the pins stand out
// and less the holes (each a prism of known volume), within 1e-9 of the
// piece's volume. A pin's foot or a hole reaching out of the material would
// only add to that sum, so no error hides another.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/core/types.h"
#include "geometry/mould/casting_case.h"

namespace fabmesh {

/// One section of a piece: a cell of its box.
struct CaseSection {
  std::array<int, 3> cell{0, 0, 0};           ///< its index along x, y and z
  TriangleSoup soup;                          ///< closed, outward, in the printed frame
  Vec3 lo{0.0, 0.0, 0.0}, hi{0.0, 0.0, 0.0};  ///< its cell (within the piece's box)
  std::size_t pins = 0, holes = 0;            ///< pins it carries, holes it has for its neighbours' pins
};

/// A piece cut for the bed.
struct SectionedPiece {
  std::array<int, 3> counts{1, 1, 1};  ///< cells along x, y and z
  bool turned = false;                 ///< the bed turned a quarter (its x along the piece's y)
  std::vector<CaseSection> sections;   ///< the cells the piece reaches, z, then y, then x ascending
  /// Every joint's pins: base at the centre of the pin's cross-section on
  /// the cut plane, axis the cut axis (+), `buried` below the plane.
  std::vector<CasePin> pins;
  double volume = 0.0;        ///< the piece's
  double volume_error = 0.0;  ///< |sum of the sections - (piece + pins' ends - holes)|
};

/// The piece `printed` (closed, outward, free of self-intersections; as it
/// is printed, +z up) cut into cells that fit `bed` (x, y, z) with their
/// pins. `name` names the piece in messages.
/// \throw RangeError (key "print.bed", bad input) when the bed is no
///        larger than a pin along an axis the piece exceeds.
/// \throw GeometryError (where "print.bed") when it would take more than
///        64 sections, or when no place tried for the cuts gives valid
///        sections without slivers, each with its pins or holes (the
///        reason is the first place's: a joint without room for two pins, a
///        sliver, an exact cut or volume proof that failed).
SectionedPiece cut_case_piece(const TriangleSoup& printed, const std::string& name, const Vec3& bed,
                              const CaseOptions& options);

/// Whether a box of `size` fits `bed` standing as it is, turned a quarter
/// about z if need be.
bool fits_bed(const Vec3& size, const Vec3& bed);

}  // namespace fabmesh
