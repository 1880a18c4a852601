#pragma once
// Design files as plain, validated data (docs/design-files.md).

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/core/limits.h"
#include "geometry/core/units.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/kitchen/nest.h"
#include "geometry/kitchen/pieces.h"
#include "geometry/mesh/edge_profile.h"
#include "geometry/mesh/thicken.h"
#include "geometry/mould/casting_case.h"
#include "geometry/mould/mould_options.h"
#include "geometry/section/print_checks.h"
#include "geometry/section/vessel_section.h"
#include "geometry/surfaces/patch_network.h"
#include "geometry/toolpath/cnc_options.h"

namespace fabmesh {

/// One entry of a design's `outputs:` list, with where it was written: the
/// pipeline's output table decides whether the format exists and applies.
struct OutputRequest {
  std::string format;  ///< e.g. "stl"
  std::string where;   ///< "path:line:column: outputs[1]" (or the -D override), for messages
  int line = 0;        ///< 1-based, 0 when not from the file
  int column = 0;
};

/// What a design's mesh is for.
enum class Purpose {
  Fabrication,  ///< every mesh must be valid for fabrication (closed, manifold, embedded)
  View,         ///< an open surface may be written for viewing (its only defect its border)
};

/// What a job does when one output cannot be made as asked (e.g. Draco cannot
/// hold the tolerance at these coordinates).
enum class OutputErrorPolicy {
  Skip,  ///< write the others, report the skipped one with why (a warning)
  Fail,  ///< fail the whole job (bad input, nothing written)
};

/// Where a design gives one key.
struct KeySource {
  std::string place;          ///< "path:line:column", or "-D path=value" for an override
  bool holds_keys = false;    ///< its value is a map, a list or empty (what it does not give is a default)
  std::string file;           ///< the design's file
  int line = 0, column = 0;   ///< 1-based; 0 for an override
  std::string override_text;  ///< "body.wall=2.5" when an override gave it
};

/// What a parameter holds: a number, one of its named choices
/// (`{value: shell, choices: [shell, solid]}`), or a switch (`true`, `false`).
enum class ParameterKind { Number, Choice, Switch };

/// One of a design's named parameters (`parameters:`), its value resolved
/// (an expression evaluated, a `-D NAME=VALUE` applied).
struct DesignParameter {
  std::string name;
  ParameterKind kind = ParameterKind::Number;
  /// A number's value; a choice's index in `choices`; a switch's 1 or 0 (its value in expressions).
  double value = 0.0;
  std::string text;                      ///< a choice's value, or "true" / "false"; empty for a number
  std::vector<std::string> choices;      ///< a choice's values, in the order declared
  std::optional<double> min, max, step;  ///< as declared (resolved), when declared
  std::string description;               ///< empty when none
};

/// One of a design's named parameter sets (`parameter_sets:`): values for
/// some of its parameters, each as written (a number or an expression "=...").
struct ParameterSet {
  std::string name;
  std::vector<std::pair<std::string, std::string>> values;  ///< (parameter, value), in file order
};

/// Keys every design has.
struct DesignCommon {
  std::string path;  ///< the file it was read from
  std::string name;  ///< default: the file's stem
  std::string units = "mm";
  /// The unit of files that carry none (STL, OBJ, PLY, OFF, Draco) and of 3MF;
  /// glTF is always metres. Default mm: slicers read STL as millimetres.
  std::string export_units = "mm";
  double tolerance = 0.01;  ///< model units, > 0
  /// As given; empty when the design names none (the kind's defaults apply).
  std::vector<OutputRequest> outputs;
  Purpose purpose = Purpose::Fabrication;
  OutputErrorPolicy on_output_error = OutputErrorPolicy::Skip;
  /// Where the design gives each key, by key path ("tolerance", "body.wall",
  /// "holes[1].segments[2]"; every map entry and list element, not inside
  /// lists of lists such as points). For messages about a value that only
  /// building can judge.
  std::map<std::string, KeySource> where;
  /// Facts about how the design's files were read that change nothing but
  /// deserve a look, e.g. "points.csv:1: a header row (not numbers) was
  /// skipped, for ...". Shown in the report (`notes`).
  std::vector<std::string> notes;
  /// The design's `parameters`, in the order declared, with the values used.
  std::vector<DesignParameter> parameters;
  /// The parameter set whose values were used (`parameter_set`, `run -P`),
  /// "" when none; `-D NAME=VALUE` still wins over a set's value.
  std::string parameter_set;
  /// Every set the design declares (`parameter_sets`), in file order.
  std::vector<ParameterSet> parameter_sets;
  /// The other files the design reads (DXF drawings, CSV point lists), as
  /// opened (relative to the working folder or absolute), in reading order:
  /// what `run --watch` watches besides the design.
  std::vector<std::string> inputs;
};

/// `location` placed in the design: `place` is where the design gives its key
/// (or, for a key inside a value the design gives, e.g. "mould.keys[1]" of
/// `keys: 4`, that value's place); a key the design does not write is
/// `is_default`, placed at the design's path. A location without a key, or
/// already placed, is returned as it is.
ErrorLocation placed(const DesignCommon& common, ErrorLocation location);

/// "place: key" for a message about `key`'s value (location_text of the
/// placed key): "path:line:column: key", "-D path=value: key", or
/// "path: key (default)" when the design does not write it.
std::string key_label(const DesignCommon& common, const std::string& key);

/// kind: curve
struct CurveDesign {
  static constexpr const char* kKind = "curve";
  CurveSpec curve;
};

/// kind: vessel. The profile lies in the (radius, height) plane.
struct VesselDesign {
  static constexpr const char* kKind = "vessel";
  CurveSpec profile;
  BodyMode mode = BodyMode::Solid;
  double wall = 0.0;                                 ///< shell: > 0
  double base = 0.0;                                 ///< shell: > 0 (default: wall)
  RimCut rim = RimCut::Square;                       ///< shell: how the rim is cut (key `body.rim`)
  std::size_t max_triangles = kDefaultMaxTriangles;  ///< budget (key `max_triangles`)
  /// Clay shrinkage from wet to fired, in [0, 1): what is written (the master)
  /// is the designed (fired) vessel scaled by 1 / (1 - shrinkage).
  double shrinkage = 0.0;
  /// The test bar's lengths the shrinkage was measured from (`shrinkage:
  /// {wet, fired}`), or 0 when it was given as a fraction.
  double shrinkage_wet = 0.0, shrinkage_fired = 0.0;
  /// A slip-casting mould around the vessel (key `mould`); its options in
  /// model units, tolerance and shrinkage filled from the design.
  std::optional<MouldOptions> mould;
  /// What a potter weighs for the mould (keys `mould.plaster_ratio`,
  /// `mould.plaster_density`, `mould.slip_density`): plaster to water by
  /// weight, and the dry plaster's and the slip's densities in g/ml.
  double plaster_ratio = 1.4;
  double plaster_density = 2.63;
  double slip_density = 1.75;
  /// Printing the vessel upright (key `print`): its limits turn the print
  /// checks into warnings (or, strict, bad input). Without it the checks are
  /// reported only.
  std::optional<PrintOptions> print;
  /// The casting cases of the mould's parts (key `case`; outputs case_stl,
  /// case_3mf): the wall in model units (default 5 mm).
  CaseOptions casting_case;
};

/// A tap hole (`drill: {center, diameter, tool}`): drilled with a drill
/// cycle, not routed round.
struct HoleDrill {
  Vec2 center{0.0, 0.0};
  double diameter = 0.0;
  /// The drill's number: the one given, else a drill of cnc.tools of this
  /// diameter, else the number this diameter got (2, 3, ... in order of first
  /// use); 0 without a cnc section.
  int tool = 0;
};

/// One cut-out of a countertop (sink, cooktop, tap hole).
struct CountertopHole {
  std::string shape;  ///< ellipse | rounded_rect | outline | drill (for messages)
  CurveSpec
      curve;  ///< closed; ellipse, rounded_rect and drill expanded into exact ellipse-arc and line segments
  /// The hole entry's `tabs` (the router leaves them on this cut-out; width,
  /// height and min_radius default to cnc.tabs'); count 0 when not given.
  TabOptions tabs = no_tabs();
  std::optional<HoleDrill> drill;  ///< a tap hole: a circle the program drills
};

/// A CNC router cut of a countertop (key `cnc`): the cut, and how its G-code is written.
struct CncDesign {
  CncOptions options;                ///< model units; depth defaults to the slab's thickness
  std::string program_units = "mm";  ///< mm (G21) or in (G20)
  int decimals = 0;                  ///< digits in the program; 0: from the tolerance
};

/// A kitchen: the top cut from stone slabs (keys `slab`, `seams`,
/// `seam_clearance`), model units.
struct KitchenDesign {
  SlabStock slab;
  bool auto_seams = false;      ///< `seams: auto`
  std::vector<SeamSpec> seams;  ///< the seams given (none with auto)
  double seam_clearance = 0.0;  ///< least distance from a seam to a cut-out (default 100 mm)
  /// Strips along the wall edges (`backsplash: {height, thickness}`), cut
  /// from the same slabs; height 0: none.
  double backsplash_height = 0.0;
  double backsplash_thickness = 0.0;  ///< default: the top's thickness
};

/// kind: countertop. Outline and holes in the plane; the slab spans z in [0, thickness].
struct CountertopDesign {
  static constexpr const char* kKind = "countertop";
  CurveSpec outline;  ///< closed
  std::vector<CountertopHole> holes;
  double thickness = 0.0;                            ///< > 0, model units
  double max_edge = 0.0;                             ///< > 0 refines the triangulation; 0: not given
  std::size_t max_triangles = kDefaultMaxTriangles;  ///< budget (key `max_triangles`)
  std::optional<CncDesign> cnc;
  std::optional<KitchenDesign> kitchen;  ///< with a `slab`: the top is cut into pieces and nested
  /// The exposed top edges' profile (key `edges: {exposed, radius}`):
  /// every outline edge of a plain top, the pieces' exposed edges of a
  /// kitchen; cut-outs are cut square. Square: none.
  EdgeProfile edges;
};

/// kind: surface. Patches of a G0/G1/G2-joined network of generalized
/// bicubic H-Bézier patches, in file order.
struct SurfaceDesign {
  static constexpr const char* kKind = "surface";
  std::vector<PatchSpec> patches;
  double thickness = 0.0;                     ///< > 0: a solid shell along the normals; 0: an open surface
  ThickenSide thicken = ThickenSide::Normal;  ///< which side the shell goes to (key `thicken`)
  std::size_t max_triangles = kDefaultMaxTriangles;  ///< budget (key `max_triangles`)
};

/// The kinds of design. Adding one: an alternative here (with its kKind),
/// its reader (io/design/yaml) and its builder (pipeline/build_*): every
/// std::visit over a DesignBody then names what is missing at compile time.
using DesignBody = std::variant<CurveDesign, VesselDesign, CountertopDesign, SurfaceDesign>;

struct Design {
  DesignCommon common;
  DesignBody body;
};

namespace detail {
template <std::size_t... I>
std::vector<std::string> kind_names(std::index_sequence<I...>) {
  return {std::variant_alternative_t<I, DesignBody>::kKind...};
}
}  // namespace detail

/// Every kind's name, in the order of DesignBody's alternatives.
inline std::vector<std::string> kind_names() {
  return detail::kind_names(std::make_index_sequence<std::variant_size_v<DesignBody>>{});
}

/// The kind's name as design files write it ("vessel", ...).
inline const char* kind_name(const DesignBody& body) {
  return std::visit([](const auto& b) { return std::decay_t<decltype(b)>::kKind; }, body);
}
inline const char* kind_name(const Design& design) { return kind_name(design.body); }

/// Whether `key` is a key path ("holes[1].segments[2]": names, each followed
/// by any [index]) whose first name is a top-level key of `design`'s kind.
bool is_design_key(const Design& design, const std::string& key);

}  // namespace fabmesh
