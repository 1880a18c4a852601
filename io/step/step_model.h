#pragma once
// What the STEP module (io/step/step_occt.cpp, loaded only when a STEP file
// is written or read) gets and gives: plain data, no OpenCASCADE type. The
// module builds the exact curves as OpenCASCADE edges, the solids from them,
// and writes or reads the file.

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/surfaces/bspline_face.h"

namespace fabmesh {

/// An ellipse arc (a circle when major == minor): centre, semi-axes, the
/// major axis's angle from x and the arc's parameter range, radians. The arc
/// runs from `from` to `to`, clockwise when to < from.
struct StepConic {
  Vec2 center{0.0, 0.0};
  double major = 1.0, minor = 1.0;
  double axis_angle = 0.0;
  double from = 0.0, to = 0.0;
};

/// One exact piece of a planar curve, in its plane's coordinates.
struct StepCurve {
  enum class Kind { Line, Bezier, BSpline, Conic };
  Kind kind = Kind::Line;
  std::vector<Vec2> poles;      ///< Line: its two ends; Bezier and BSpline: the control points
  std::vector<double> weights;  ///< Bezier: empty (polynomial) or one per pole
  int degree = 3;               ///< BSpline
  std::vector<double> knots;    ///< BSpline: distinct knots
  std::vector<int> multiplicities;
  StepConic conic;  ///< Conic
};

/// A chain of pieces end to end (closed when its last end is its first start).
struct StepLoop {
  std::vector<StepCurve> curves;
};

enum class StepForm {
  Extrusion,   ///< loops in the xy plane (the outer one first, then holes) extruded by `height` along z
  Revolution,  ///< one closed loop in the (radius, height) half-plane revolved about the z axis
  Wireframe,   ///< the loops as curves in the xy plane, no solid
  Carved,  ///< `block` minus loops[0] (a closed (radius, height) loop) revolved about z, with `hemispheres`
  Sheet,   ///< `surfaces` as faces sewn along their shared borders into one open shell, no solid
  Closed,  ///< `surfaces` as faces sewn into one closed shell: the solid it bounds
  /// loops[0] (a closed (radius, height) loop) revolved about z and cut to
  /// the heights of `block` (a cylinder about it), with `cylinders` added or
  /// taken away, then cut to the block's angles, then `cylinders` across
  /// added or taken: a section of a master, its pin on top and its hole
  /// below, or a half or quarter of it with the pin and hole of its joints
  Slice,
  /// A casting case: the axis-aligned box `case_lo`..`case_hi` minus the
  /// Carved body the other fields describe (a mould part lying in the box,
  /// one of its flat faces on the box's side: the case's opening)
  Case,
  /// The plate of a two-piece casting case: the axis-aligned box
  /// `case_lo`..`case_hi` with `hemispheres` added to it or taken from it
  /// (the sockets of the part's face it lies under, filled; its bumps, held)
  CasePlate,
  /// A piece of a casting case carved in several: the Case (its box less the
  /// part) cut by `regions`. Piece `piece` > 0 is what lies in region
  /// `piece - 1` and in none before it, with `cylinders` (its pins) added;
  /// piece 0, the main piece, is what lies in no region, less `cylinders`
  /// (the pins' holes).
  CasePiece,
};

/// A face of a Sheet or a Closed body: a polynomial B-spline surface.
using StepSurface = BSplineFace;

/// A block about the z axis between two heights: a cylinder of `radius`, or a
/// square box of half-side `radius` with sides parallel to x and y; all of
/// it, or its part between the half-planes through the axis at `from_angle`
/// and `to_angle` (radians, to_angle - from_angle in (0, 2 pi]).
struct StepBlock {
  bool box = false;
  double radius = 0.0;
  double z_low = 0.0, z_high = 0.0;
  double from_angle = 0.0, to_angle = 0.0;
};

/// A solid hemisphere: the half-ball of `radius` about `centre` on the side
/// `axis` (a unit vector) points to; added to the body or taken from it.
struct StepHemisphere {
  Vec3 centre{0.0, 0.0, 0.0};
  Vec3 axis{0.0, 0.0, 1.0};
  double radius = 0.0;
  bool added = true;
};

/// A prism: the planar polygon `section` swept along `along`; or, with
/// `about_axis`, the ring it sweeps in a whole turn about the z axis.
struct StepPrism {
  std::vector<Vec3> section;
  Vec3 along{0.0, 0.0, 0.0};
  bool about_axis = false;
};

/// A region a casting case is cut by: the box `corner` + a u + b v + c d for
/// a, b, c in [0, 1] (u, v, d at right angles, right-handed), with the
/// half-balls `fills` added (the sockets of the part's face it lies beyond),
/// the prisms `hollows` taken away (a lid's: the cylinder block's inside)
/// and then the prisms `adds` added.
struct StepRegion {
  Vec3 corner{0.0, 0.0, 0.0};
  Vec3 u{1.0, 0.0, 0.0}, v{0.0, 1.0, 0.0}, d{0.0, 0.0, 1.0};
  std::vector<StepHemisphere> fills;
  std::vector<StepPrism> hollows;
  std::vector<StepPrism> adds;  ///< prisms added after the hollows (a piece's vessel slice)
};

/// A solid cylinder: its base circle of `radius` about `base`, extending
/// `height` along `axis` (a unit vector); added to the body or taken from it.
struct StepCylinder {
  Vec3 base{0.0, 0.0, 0.0};
  Vec3 axis{0.0, 0.0, 1.0};
  double radius = 0.0;
  double height = 0.0;
  bool added = true;
  /// Slice: a pin or hole across a joint through the axis, added or taken
  /// after the slice is cut to its block's angles (the others, on the axis,
  /// are cut with the slice: a quarter of the slice has a quarter of them).
  bool across = false;
};

/// Extrusion: the top edges (and the bottom ones) over the curves of
/// loops[0] flagged in `profiled` (one flag per curve) rounded with fillets
/// of radius `top` (`bottom`; 0: none), or chamfered with legs `top`.
///
/// Where an exposed curve runs on tangentially into an unprofiled one (a wall,
/// a seam), the round stops there on a quarter turn. A round as tall as the
/// edge (`top` + `bottom` = `height`) that stops is made `slack` smaller (its
/// two rounds, or the round and the bottom face, then leave a band of that
/// height between them), so the solid lies within `slack` of the exact one;
/// with no slack it is refused.
struct StepEdgeRounds {
  double top = 0.0;
  double bottom = 0.0;
  bool chamfer = false;
  std::vector<bool> profiled;
  double slack = 0.0;
};

struct StepBody {
  std::string name;  ///< the product's name in the file
  StepForm form = StepForm::Extrusion;
  std::vector<StepLoop> loops;
  double height = 0.0;                      ///< Extrusion: > 0
  StepEdgeRounds rounds;                    ///< Extrusion
  StepBlock block;                          ///< Carved, Slice
  std::vector<StepCylinder> cylinders;      ///< Slice; Case (holes), CasePlate (pins)
  std::vector<StepHemisphere> hemispheres;  ///< Carved, CasePlate
  std::vector<StepSurface> surfaces;        ///< Sheet, Closed
  /// Sheet, Closed: faces whose borders are closer than this are sewn (model units; > 0).
  double sewing_tolerance = 0.0;
  Vec3 case_lo{0.0, 0.0, 0.0}, case_hi{0.0, 0.0, 0.0};  ///< Case, CasePlate, CasePiece
  std::vector<StepRegion> regions;                      ///< CasePiece
  /// Case, CasePiece: prisms taken from the part before it is taken from the
  /// box (its free faces leaned by the case's draft).
  std::vector<StepPrism> drafts;
  std::size_t piece = 0;  ///< CasePiece
};

/// One file: its bodies in one unit of length (mm, cm, m or in), the file's own.
struct StepModel {
  std::string name;
  std::string unit = "mm";
  std::vector<StepBody> bodies;
};

/// A solid (a sheet, a wireframe) as the module found it in a file it wrote or read.
struct StepShapeFacts {
  bool valid = false;   ///< BRepCheck_Analyzer finds it valid
  bool closed = false;  ///< a solid whose shells are closed (no free edge)
  int solids = 0, shells = 0, faces = 0, edges = 0;
  int free_edges = 0;   ///< edges (not degenerate) that one face uses once: an open shell's border
  double volume = 0.0;  ///< BRepGProp (adaptive to 1e-10 for a file read), in the file's unit cubed (solids;
                        ///< 0 for a sheet)
  double area = 0.0;    ///< BRepGProp, the faces' area in the file's unit squared
  /// How far the solid may lie from the exact one its body describes: a
  /// stopped round as tall as the edge made smaller by StepEdgeRounds::slack.
  double added = 0.0;
  std::string problems;  ///< what BRepCheck_Analyzer objects to, when not valid
};

struct StepWritten {
  std::string bytes;
  std::string error;                   ///< empty on success
  std::vector<StepShapeFacts> bodies;  ///< per body, as built before writing
};

struct StepRead {
  std::string error;                  ///< empty on success
  std::string length_unit;            ///< as the file declares it ("MM", "CM", "INCH", ...)
  std::vector<StepShapeFacts> roots;  ///< one per root shape transferred
};

/// How far points lie from the shapes of a STEP file (BRepExtrema).
struct StepDistances {
  std::string error;  ///< empty on success
  double max_distance = 0.0;
};

/// The module's entry points (a C function returns this table; the program
/// checks `abi` against its own before calling).
struct StepModuleApi {
  int abi = 0;
  StepWritten (*write)(const StepModel& model) = nullptr;
  StepRead (*read)(const std::string& bytes) = nullptr;
  StepDistances (*distances)(const std::string& bytes, const std::vector<Vec3>& points) = nullptr;
};

/// Changes whenever StepModel, StepWritten, StepRead or StepModuleApi change.
inline constexpr int kStepModuleAbi = 8;

}  // namespace fabmesh
