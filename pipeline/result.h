#pragma once
// A job's one result: what a design made (its parts, each a mesh with the
// proofs of its construction and its validation; the exact geometry,
// drawings and programs of its kind; the facts its builder reports), what
// the design is (name, kind, units, parameters, the tolerance and how it was
// divided), and the files written from it. Every command, the studio, the
// library and Python read this one object; one serializer writes its JSON
// (pipeline/result_json.h).
//
// Parts are made by the builders (pipeline/build_*.cpp): the design's own
// mesh first (role Product), then a vessel's mould parts; a job of many
// parts (a kitchen's pieces, a ceramic set's cases) adds roles here.

#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "geometry/core/proofs.h"
#include "geometry/core/soup.h"
#include "geometry/core/stage_timer.h"
#include "geometry/core/tolerance_budget.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/kitchen/nest.h"
#include "geometry/kitchen/pieces.h"
#include "geometry/mesh/edge_profile.h"
#include "geometry/sampling/cut_loop.h"
#include "geometry/sampling/offset_bezier.h"
#include "geometry/surfaces/bspline_shell.h"
#include "geometry/surfaces/patch_network.h"
#include "geometry/toolpath/toolpath.h"
#include "geometry/validation/validate.h"
#include "io/cutting/gcode.h"
#include "io/design/design.h"
#include "pipeline/facts.h"

namespace fabmesh {

/// What a part of a job's result is.
enum class PartRole {
  Product,    ///< the design's own mesh: the vessel, the countertop, the surface
  MouldSide,  ///< a side part of a vessel's slip-casting mould
  MouldBase,  ///< the base part of a vessel's mould
  Piece,      ///< a piece of a kitchen's top, cut at its seams (the product is then the whole top)
  Master,     ///< a vessel's casting master: its outer solid as written, with the mould's spare on its rim
  Case,       ///< the casting case of a mould part: the open box plaster is poured into to cast that part
};

/// "product", "mould_side", "mould_base", "piece", "master", "case": the role as reports write it.
const char* to_string(PartRole role);

/// One mesh of a result, with what its construction proves and its verdict.
struct Part {
  std::string name;  ///< the design's name for its product; "side-1", "base" for mould parts
  PartRole role = PartRole::Product;
  TriangleSoup mesh;  ///< model units (a vessel's master size)
  /// What the builder proved about `mesh` (topology, embedding), used by
  /// validation in place of the analyses they replace; empty: none.
  ValidationOptions proofs;
  ValidationReport validation;  ///< validate_parts' verdict, with those proofs
  bool validated = false;       ///< `validation` is set (a builder that needs it early sets it)
};

/// A design's curve as built (build_curve), under its design key: "curve",
/// "profile", "outline", "holes[0]", ...
struct NamedBuiltCurve {
  std::string name;
  BuiltCurve curve;
};

/// The exact solid a design's mesh approximates, from the exact curves: what
/// outputs that carry exact geometry (step) write.
struct ExactSolid {
  enum class Form {
    Extrusion,  ///< `loops` in the xy plane (the outline, then holes) extruded by `height` along z
    /// each loop in the (radius, height) half-plane revolved about the height
    /// axis into a solid of its own (one per part of a profile that runs along the axis)
    Revolution,
  };
  Form form = Form::Extrusion;
  /// Closed, as written (a vessel's scaled for shrinkage): segments, and a
  /// shell's inner wall as arcs of the profile's offset.
  std::vector<std::vector<ExactPiece>> loops;
  double height = 0.0;
  /// Extrusion: the profile of the top (and bottom) edges over the pieces
  /// of loops[0] flagged in `profiled` (one flag per piece), as fillets or
  /// chamfers; Square or no flag set: none.
  EdgeProfile edges;
  std::vector<bool> profiled;
};

/// A vessel's slip-casting mould as exact solids (what `mould_step` writes):
/// each part is the block (a cylinder, or a square box, about the z axis)
/// between two heights and, for a side part, two split half-planes, minus
/// the cavity revolved, with its keys' hemispheres added (bumps) or taken
/// away (sockets). Master size, model units.
struct ExactMould {
  struct Key {
    Vec3 centre{0.0, 0.0, 0.0};
    Vec3 axis{0.0, 0.0, 1.0};  ///< unit normal of the split plane toward the apex
    double radius = 0.0;
    bool bump = true;
  };
  struct Part {
    std::string name;  ///< the mesh part's name: "side-1", "base"
    double z_low = 0.0, z_high = 0.0;
    double from_angle = 0.0, to_angle = 0.0;  ///< radians; the base part goes all the way round
    std::vector<Key> keys;
  };
  bool box = false;
  double block_radius = 0.0;  ///< the cylinder's radius or half the box's side
  /// The cavity's section, closed: the exact profile from the rim down to its
  /// base end, to the axis, up the axis above the block's top, and back down
  /// along the reservoir's wall to the rim (the reservoir opens at the top).
  std::vector<ExactPiece> cavity;
  std::vector<Part> parts;
  /// The parts' exact total volume: block - cavity + bumps - sockets.
  double volume = 0.0;
};

/// What a curve design makes besides its curve: the curve at true size.
struct CurveProducts {
  std::vector<CutLoop> drawing;  ///< when an output draws it
};

/// A casting master cut into sections for a printer's bed (print.bed), each
/// joined to the next by a pin on the axis into a hole, and for a bed too
/// narrow into halves or quarters through the axis, each joined to the next
/// by a pin across the joint (master_sections.h, master_sectors.h).
struct MasterSections {
  struct Section {
    std::string name;
    double z_low = 0.0, z_high = 0.0;
    bool pin = false, hole = false;
    int from_quadrant = 0, to_quadrant = 4;  ///< its quarter turns (0 .. 4: whole)
    Vec2 joint_pin{0.0, 0.0};                ///< a sector's joint pins in its caps, (radius, height)
  };
  std::vector<Section> sections;
  double pin_radius = 0.0, pin_height = 0.0, hole_radius = 0.0, hole_depth = 0.0;
  double enclosing_radius = 0.0;  ///< more than the master's largest radius
};

/// What a vessel makes besides its mesh and mould parts.
struct VesselProducts {
  /// The exact solid; none for a shell whose profile runs along the axis.
  std::optional<ExactSolid> solid;
  std::vector<CutLoop> profile_template;  ///< the profile closed along the axis, when an output draws it
  std::optional<ExactMould> mould;        ///< when the design has a mould
  /// The casting master as an exact solid of revolution (master_step), when
  /// an output asked for the master.
  std::optional<ExactSolid> master;
  std::optional<MasterSections> master_sections;  ///< when the master is cut for print.bed
  /// When an output asked for casting cases: why a mould part has none (one
  /// line per such part; its case outputs write the others).
  std::vector<std::string> case_refusals;
  /// The cases built, in the mould's frame: the box around mould part `part`
  /// (an index into mould->parts), its opening on the part's flat face.
  struct CaseBox {
    std::string name;  ///< "case-side-1"
    std::size_t part = 0;
    Vec3 lo{0.0, 0.0, 0.0}, hi{0.0, 0.0, 0.0};
    Vec3 pull{0.0, 0.0, 1.0};     ///< an axis direction: the way the part leaves the case
    Vec3 opening{0.0, 0.0, 1.0};  ///< an axis direction: the open side of the box, where plaster is poured
    /// A two-piece case's plate: the slab `lo`..`hi` of the box beyond the
    /// part's flat face across `pull` (an axis direction, the way the plate
    /// comes off), with that face's keys (it fills their sockets).
    struct Plate {
      std::string name;  ///< "case-side-1-plate"
      Vec3 lo{0.0, 0.0, 0.0}, hi{0.0, 0.0, 0.0};
      Vec3 pull{0.0, 0.0, -1.0};
      /// A registration pin: a cylinder standing on the plate's face at
      /// `base` along `axis` (into the main piece), in a hole of the main
      /// piece `hole_radius` across and `hole_depth` deep.
      struct Pin {
        Vec3 base{0.0, 0.0, 0.0}, axis{0.0, 0.0, 0.0};
        double radius = 0.0, height = 0.0, hole_radius = 0.0, hole_depth = 0.0;
      };
      std::vector<Pin> pins;
    };
    std::optional<Plate> plate;  ///< none: the case is one piece
    /// Carved in several pieces by exact booleans.
    bool carved = false;
    /// A carved case's pieces taken off before the part, in order: each what
    /// lies in the case in its region (the box `corner` + a u + b v + c d,
    /// a, b, c in [0, 1]; on a side of the part's box, across `face_axis` at
    /// `face_at`, with the sockets behind that face) and in none before it.
    struct Piece {
      std::string name;  ///< "case-side-1-piece-1"
      Vec3 corner{0.0, 0.0, 0.0}, u{0.0, 0.0, 0.0}, v{0.0, 0.0, 0.0}, d{0.0, 0.0, 0.0};
      int face_axis = -1;
      double face_at = 0.0;
      /// A lid: its region less the prism over `hollow` swept along `hollow_along` (CasePlate).
      std::vector<Vec3> hollow;
      Vec3 hollow_along{0.0, 0.0, 0.0};
      /// Its pins: `base` the centre of the cylinder's end inside the piece,
      /// `height` its whole length, and the hole's whole length `hole_depth`
      /// from the same end.
      std::vector<Plate::Pin> pins;
      /// A piece that takes the vessel's slice too: its region with these
      /// prisms added (CasePlate).
      std::vector<CasePrism> cores;
    };
    std::vector<Piece> pieces;
    /// The part's faces leaned by the draft: each prism is taken from the part.
    std::vector<CaseDraft> drafts;
  };
  std::vector<CaseBox> cases;
  /// The section as the builder made it: closed loops (the profile, the rim,
  /// a shell's inner wall and base, the axis) at the fired size (before
  /// shrinkage's scaling), for the plot.
  std::vector<std::vector<Vec2>> section;
  /// The stretches overhanging beyond overhang_limit_deg when printed
  /// upright (print checks), at the fired size, for the plot.
  std::vector<std::vector<Vec2>> overhangs;
  double overhang_limit_deg = 45.0;
};

/// A kitchen's top cut into pieces and nested on slabs (a countertop with a
/// `slab`): the pieces are the result's parts of role Piece, in this order.
struct KitchenProducts {
  KitchenSplit split;  ///< the pieces (design frame) and the seams
  SlabStock stock;     ///< as the design gives it
  /// Where each piece lies; verified exactly against the stock with the
  /// margins widened by, and the spacing by twice, the loops' deviation from
  /// their exact curves, so the exact pieces keep the stock's.
  SlabNesting nesting;
  /// With `cnc`: one program per slab (index = slab), every piece on it in
  /// slab coordinates, each piece's cut-outs before its outline.
  std::vector<Toolpath> slab_toolpaths;
  /// Each piece's exact shape, in the pieces' order: its solid (step) and its
  /// cutting drawing (dxf, svg; when an output draws it), or why it has none.
  struct Exact {
    std::optional<ExactSolid> solid;
    std::vector<CutLoop> drawing;
    std::string why_not;
  };
  std::vector<Exact> exact;
};

/// What a countertop makes besides its mesh.
struct CountertopProducts {
  ExactSolid
      solid;  ///< when an output writes the exact shape (BuildContext::wants_exact); no loops otherwise
  std::vector<CutLoop> cutting;            ///< the outline, then the holes, when an output draws them
  std::optional<Toolpath> toolpath;        ///< the router path (key `cnc`)
  std::optional<GcodeOptions> gcode;       ///< how its program is written (with `toolpath`)
  std::optional<KitchenProducts> kitchen;  ///< with a `slab`
};

/// What a surface makes besides its mesh.
struct SurfaceProducts {
  PatchNetwork patches;
  /// A thickened surface's sheets as its tessellation proved them, when an
  /// output writes the exact shape (step).
  std::optional<ShellGrid> shell;
};

/// The exact data, drawings and programs of a design's kind, one
/// alternative per DesignBody alternative (in the same order): an output
/// visits the alternative it is made from.
using KindProducts = std::variant<CurveProducts, VesselProducts, CountertopProducts, SurfaceProducts>;
static_assert(std::variant_size_v<KindProducts> == std::variant_size_v<DesignBody>,
              "one KindProducts alternative per kind of design");

/// One file a job wrote.
struct OutputFile {
  std::string path;
  std::string format;
  std::string units;         ///< the unit of its coordinates
  double added_error = 0.0;  ///< how far writing moved any vertex at most, model units
  std::optional<bool> valid_as_written = std::nullopt;  ///< mesh outputs: proven valid as stored
  std::vector<std::string> parts;                       ///< the parts it holds (empty: the design as a whole)
};

/// An output the job could not make (and skipped, by the design's policy).
struct SkippedOutput {
  std::string format;
  std::string reason;
};

/// A job's result (see the top of this file).
struct Result {
  // --- the design ---
  std::string name;
  std::string kind;         ///< "vessel", "countertop", "surface", "curve"
  std::string design_file;  ///< the file it was read from
  std::string units;        ///< model units of every length below
  std::string export_units;
  std::vector<DesignParameter> parameters;  ///< the named parameters with the values used
  std::string parameter_set;                ///< the parameter set they came from, "" for none
  double tolerance = 0.0;
  /// The share of the tolerance the build was given (the rest is kept for
  /// writing the outputs), model units.
  double build_tolerance = 0.0;
  // --- what the build made ---
  MeshPurpose purpose = MeshPurpose::Fabrication;
  double max_deviation = 0.0;  ///< proven bound of the meshes (or curves) against the exact shape
  /// How the builders divided build_tolerance, each stage named by what it
  /// builds ("section", "mould: revolution", "cnc: G-code rounding").
  std::vector<ToleranceShare> tolerance_shares;
  std::vector<Part> parts;              ///< the product first; none for a curve design
  std::vector<NamedBuiltCurve> curves;  ///< the design's curves as built, in the design's order
  KindProducts products;                ///< the kind's exact geometry, drawings and programs
  Facts facts;                          ///< what the builder reports (the report's `build`)
  Vec3 bbox_min = Vec3::Zero(), bbox_max = Vec3::Zero();  ///< of the product (or the drawing)
  /// What deserves a look: what the builder did other than asked (tabs left
  /// out), a block no output uses.
  std::vector<std::string> warnings;
  std::vector<std::string> notes;  ///< how the design's files were read
  // --- what was written ---
  std::vector<OutputFile> files;
  std::vector<SkippedOutput> skipped;
  StageTimings timings_ms;
};

/// The design's own mesh (role Product), or nullptr (a curve design).
const Part* product(const Result& result);

/// The parts of `role`, in order.
std::vector<const Part*> parts_of(const Result& result, PartRole role);

/// True when every part is valid for what the design is for (a drawing has none).
bool fit(const Result& result);

/// The paths of the files written, in order.
std::vector<std::string> written_paths(const Result& result);

/// Appends `shares` to `to`, each stage named after `prefix` ("mould: section").
void append_shares(std::vector<ToleranceShare>& to, const std::string& prefix,
                   const std::vector<ToleranceShare>& shares);

}  // namespace fabmesh
