#pragma once
// The casting case of a mould part: the open-topped solid into which plaster
// is poured to cast that part again. Its cavity is the part itself, open
// through one flat outer face of the part (the pour face), inside a box whose
// walls are `wall` thick; the part leaves the case by a straight pull out of
// that face. Built by construction from the part's own closed mesh: the
// part's triangles but the pour face's, turned inside out, and the box's
// floor, walls and rim. Nothing is approximated beyond the part's mesh.
//
// Where keys on one flat side face of the part (a side part's bottom, with
// the sockets of the base part's keys) would catch on a one-piece case, that
// side of the case is a separate plate: the box's slab beyond that face,
// with the face's keys, which comes off first, straight away from the face.
// Two pins on the plate, in the case's walls either side of the face, stand
// in holes of the main piece, so that the plate goes on in one place and
// one way round.

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/core/types.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mould/mould_part.h"

namespace fabmesh {

struct CaseOptions {
  double wall = 5.0;  ///< the case's floor and walls around the part (> 0), model units (designs: 5 mm)
  /// How much wider (all round) and deeper a plate pin's hole is than the
  /// pin (>= 0, below wall / 4), model units (designs: 0.2 mm).
  double clearance = 0.2;
  /// Largest distance between a pin's (or hole's) circle and its polygon
  /// (> 0), model units: the design's tolerance.
  double tolerance = 0.01;
  /// How far the part's free faces that run along the pull lean, degrees
  /// (0 to 10): each such face is moved back onto the plane through its edge
  /// on the pour face, leaning into the part by this angle from the pull, so
  /// that the cast part separates from the case at once as it is pulled
  /// rather than sliding along it. A face is free when it lies on `outside`.
  double draft_deg = 1.0;
  /// The mould's outside (its bounding box): a flat face of the part on a side
  /// of it touches no other part, so leaning it changes no joint. None: no
  /// face leans.
  std::optional<BoundingBox> outside;
  /// The radius of the mould's cylinder block about the z axis, when the
  /// part is a part of such a mould (none: a box block). Its back is then
  /// that cylinder, which plaster poured level cannot form: a side part's
  /// case is poured through the part's flat top (or bottom), its back held by
  /// a lid that comes off first (CasePlate::hollow), and the part then
  /// leaves the main piece along its split face's normal.
  std::optional<double> cylinder_radius;
};

/// A face of the part leaned by the draft: the part less the prism swept
/// from the quadrilateral `section` (in a plane across the face, its first
/// edge the face's edge on the pour face) along `along` (the face's other
/// axis, past the part both ways); or, `about_axis`, less the ring that
/// `section` (in the half-plane y = 0, x > 0; its first edge on the pour
/// face) sweeps in a whole turn about the z axis: a cylinder mould's base
/// part, its wall leaned into a cone.
/// A prism: the polygon `ring` swept along `along`.
struct CasePrism {
  std::vector<Vec3> ring;
  Vec3 along{0.0, 0.0, 0.0};
};

struct CaseDraft {
  std::string face;  ///< "its face across +x", "its cylinder"
  std::array<Vec3, 4> section{};
  Vec3 along{0.0, 0.0, 0.0};
  bool about_axis = false;
};

/// A registration pin of a plate: a cylinder standing on the plate's face
/// along the way the plate goes on (its pull reversed), into a hole of the
/// main piece `clearance` wider all round and deeper. Both are polygons
/// inscribed in their circles (`sides` sides, within the tolerance).
struct CasePin {
  Vec3 base{0.0, 0.0, 0.0};  ///< the centre of its foot, on the plate's face
  Vec3 axis{0.0, 0.0, 0.0};  ///< unit axis direction, from the foot to its top (minus the plate's pull)
  double radius = 0.0, height = 0.0;
  double hole_radius = 0.0, hole_depth = 0.0;
  std::size_t sides = 0;
  /// A carved case's pin runs on `buried` back into its own piece from the
  /// seam (its hole as far into the piece's side), so that it joins the piece.
  double buried = 0.0;
};

/// A flat face of a mould part that a piece of its case may be carved
/// beyond (a side part's split face, with its keys): the plane through
/// `point` across `normal`.
struct CaseFace {
  std::string name;  ///< for the report and messages: "its split face at 120 degrees"
  Vec3 point{0.0, 0.0, 0.0};
  Vec3 normal{0.0, 0.0, 0.0};  ///< unit, out of the part
  double depth = 0.0;          ///< how far its features (key sockets) reach behind it into the part
  std::size_t features = 0;    ///< its sockets and bumps
};

/// A side part's two split faces, with their keys (none for the base part).
std::vector<CaseFace> split_faces(const MouldPart& part);

/// A piece of a case taken off before the part leaves it. A two-piece case's
/// plate: the slab of the case's box beyond one flat side face of the part
/// (lying on the part's bounding box), filling what lies behind that face
/// (the keys' sockets in it). A case carved in several pieces: what lies in
/// the case beyond a plane near a face of the part (on a side of its box
/// exactly, with the sockets behind it; along a given face `wall / 4` beyond
/// its features into the part), less the pieces before it.
struct CasePlate {
  TriangleSoup soup;  ///< closed, outward, sharing vertices
  /// Unit direction the piece comes off the part along: the face's
  /// outward normal. It is printed standing on its outer side (the side of
  /// the case's box this points most toward).
  Vec3 pull{0.0, 0.0, 0.0};
  std::string face;  ///< the face it lies beyond: "its face across -z"
  /// A carved case's piece: the region it was cut by, `corner` + a u + b v +
  /// c d for a, b, c in [0, 1] (d along its pull; on a side of the part's
  /// box `face_axis` >= 0, the sockets behind that face filled).
  Vec3 corner{0.0, 0.0, 0.0}, u{0.0, 0.0, 0.0}, v{0.0, 0.0, 0.0}, d{0.0, 0.0, 0.0};
  int face_axis = -1;
  double face_at = 0.0;  ///< that face's coordinate along face_axis
  /// A lid over a cylinder block's back: its region less the prism over the
  /// polygon `hollow` (in the plane across the case's opening through the
  /// region's corner, inscribed in the block's circle and holding all of the
  /// part but its back; out along a side's split face off the split plane
  /// past the region) swept along `hollow_along` through the region.
  std::vector<Vec3> hollow;
  Vec3 hollow_along{0.0, 0.0, 0.0};
  /// A piece that also takes the vessel's slice between a cylinder part's
  /// split faces: its region with these prisms added (over polygons across
  /// the opening round the axis, swept along it; over a base part, a
  /// narrower one below the base keys' bumps and the full one above them).
  std::vector<CasePrism> cores;
  Vec3 lo{0.0, 0.0, 0.0}, hi{0.0, 0.0, 0.0};  ///< the slab's box (carved: the piece's bounding box)
  std::size_t features = 0;                   ///< the regions behind the face it fills (sockets)
  /// Its two pins (in the case's walls beside the face, a third of the way
  /// from the floor to the opening, so that it fits one way round).
  std::vector<CasePin> pins;
  /// Why the plate comes off: every face of the part on it faces its pull or
  /// runs along it (exact orientation signs).
  std::string release_proof;
};

struct CastingCase {
  /// The case (with a plate: its main piece, without the slab), closed,
  /// outward, sharing vertices.
  TriangleSoup soup;
  /// Unit axis direction the part leaves the case along; the case's opening
  /// faces it and the case stands on its opposite face (printed that side down).
  Vec3 pull{0.0, 0.0, 0.0};
  /// Unit axis direction of the case's opening, through which plaster is
  /// poured (the case's box is open on that side): the pull, but for a
  /// lidded case (a cylinder mould's side part), poured through the part's
  /// flat top and pulled along its split face's normal once the lid is off.
  Vec3 opening{0.0, 0.0, 0.0};
  Vec3 lo{0.0, 0.0, 0.0}, hi{0.0, 0.0, 0.0};  ///< the case's box (with its plate's slab)
  double pour_area = 0.0;                     ///< the opening: the part's pour face's area
  /// Why the part leaves the case: no face of the part but the pour face
  /// (and the plate's, the plate off first) faces the pull (decided by exact
  /// orientation signs).
  std::string release_proof;
  /// The pieces taken off before the part leaves the case, in order (none:
  /// the case is one piece; one on a side of the part's box: a two-piece
  /// case built by construction; otherwise carved by exact booleans).
  std::vector<CasePlate> plates;
  bool carved = false;  ///< cut by exact booleans (rather than built face by face)
  /// The faces of the part leaned by the draft (its cavity is the part less
  /// their prisms: the faces' points moved onto the leaned planes), and the
  /// volume they take from it.
  std::vector<CaseDraft> drafts;
  double draft_volume = 0.0;
  /// How far draft_volume may lie from the exact part's: only a curved face
  /// meeting a leaned face (a spare's wall) makes them differ, by at most
  /// the tolerance over the triangles that meet it and lie in no plane
  /// across an axis (every other point of the part lies beyond the leaned
  /// planes by more than the tolerance).
  double draft_volume_error = 0.0;
  /// The free faces along the pull that do not lean, and why ("its face
  /// across +x does not lean: ..."): a face meeting it that is not flat
  /// across it, or a point of the part within the tolerance of the leaned plane.
  std::vector<std::string> undrafted;
};

/// The casting case of the mould part `part` (a closed, outward, embedded
/// mesh; `name` for messages). The pull is the first of the six axis
/// directions, taken nearest `outward` first, along which the part's extreme
/// face is one flat rectangle covering its bounding box's face (the pour face)
/// and out of which it can be pulled: no other face of the part faces that
/// direction, or every one that does lies on a plate (the part's flat face on
/// one side of its bounding box, with what lies only behind it: the keys'
/// sockets there) none of whose faces faces away from that side.
/// \throw GeometryError (where "case") naming the part and, for the direction
///        nearest `outward`, what holds it: no flat face to pour through, or
///        the first face that would catch on the case, with its position.
/// `what_is_at`, when given, names the feature of the part at a point (" (a
/// key's socket)") for those messages.
/// A plate carries two pins (CasePin), `wall / 4` in radius and `wall / 2`
/// tall, centred in the case's walls on either side of the face.
/// \throw RangeError (key "case.wall") unless wall > 0; (key
///        "case.clearance") unless 0 <= clearance < wall / 4 (the hole then
///        keeps material all round in the wall); (key "case.draft_deg")
///        unless 0 <= draft_deg <= 10.
///
/// With a draft and `options.outside`, once the pull is found, each flat
/// face of the part on a side of `outside` that runs along the pull leans
/// (CaseDraft): its points move into the part in their planes, by the
/// draft's tangent times their depth behind the pour face, onto the plane
/// through the face's edge on the pour face, and the case is built around
/// that. A face is left as it is (named in `undrafted`) when a face of the
/// part meeting it is not flat across it, or another point of the part lies
/// within the tolerance of (or beyond) its leaned plane: the moved mesh
/// would then not be the part less the prism beyond that plane.
/// A cylinder mould's base part (`options.cylinder_radius`, no `faces`)
/// leans its wall on the block's cylinder into a cone narrowing away from
/// its pour face, by the same tangent times the height, its points moved
/// toward the axis along their radii; under the same conditions, the faces
/// meeting the wall level. A side part's faces do not lean: its back is the
/// block's cylinder and its bottom stands on the table or the base part.
///
/// When no such case exists, the case is carved in several pieces by exact
/// booleans (CGAL's corefinement): the main piece and, taken off before it
/// in order, a piece beyond each side of the part's box whose plate takes a
/// face that would catch and one beyond each face in `faces` (vertical
/// planes across no axis) that does, each with two pins in holes of the
/// main piece; every face of the part a piece touches is proved to face its
/// way off, and every piece is validated in full.
CastingCase build_casting_case(const TriangleSoup& part, const std::string& name, const Vec3& outward,
                               const CaseOptions& options,
                               const std::function<std::string(const Vec3&)>& what_is_at = {},
                               const std::vector<CaseFace>& faces = {});

/// The sides of a pin's and its hole's polygons: a multiple of 4 (8 to 512)
/// keeping the hole's circle of `radius` within `tolerance` of its polygon.
std::size_t pin_sides(double radius, double tolerance);

/// The solid o + a u + b v + c d for a, b, c over the given ranges (u, v, d
/// right-handed), closed and outward.
TriangleSoup block_of(const Vec3& o, const Vec3& u, const Vec3& v, const Vec3& d,
                      const std::array<double, 2>& a, const std::array<double, 2>& b,
                      const std::array<double, 2>& c);

/// A pin or its hole: the prism over the ring of `sides` points about
/// `centre` of `radius` across d (in the plane of the unit vectors e1, e2;
/// the points on the 2^-30 grid), running `length` along d, so that its
/// walls run exactly along d; closed and outward.
TriangleSoup pin_prism(const Vec3& centre, const Vec3& e1, const Vec3& e2, const Vec3& d, double radius,
                       double length, std::size_t sides);

/// The indices of the two of `points` (at least two) farthest apart: the
/// first such pair in their order.
template <class Point>
std::array<std::size_t, 2> farthest_pair(const std::vector<Point>& points) {
  std::array<std::size_t, 2> best{0, 1};
  for (std::size_t a = 0; a < points.size(); ++a) {
    for (std::size_t b = a + 1; b < points.size(); ++b) {
      if ((points[a] - points[b]).norm() > (points[best[0]] - points[best[1]]).norm()) best = {a, b};
    }
  }
  return best;
}

/// `soup` as it is printed: turned by quarter turns (exact) so that the axis
/// direction `up` is +z, then moved so that its bounding box's lowest corner
/// is at `corner`.
TriangleSoup standing(const TriangleSoup& soup, const Vec3& up, const Vec3& corner);

/// The case as it is printed: its opening up, standing on its floor.
TriangleSoup standing(const CastingCase& c, const Vec3& corner);

/// The plate as it is printed: standing on its outer face.
TriangleSoup standing(const CasePlate& p, const Vec3& corner);

}  // namespace fabmesh
