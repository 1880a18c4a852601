#pragma once
// What a builder hands to the job: the result of one design, in memory,
// validated (pipeline/validate_built.h) before any file is encoded or written.

#include <cstddef>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geometry/core/stage_timer.h"
#include "geometry/core/tolerance_budget.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/mesh/soup.h"
#include "geometry/sampling/cut_loop.h"
#include "geometry/sampling/offset_bezier.h"
#include "geometry/surfaces/bspline_shell.h"
#include "geometry/surfaces/patch_network.h"
#include "geometry/toolpath/toolpath.h"
#include "geometry/validation/validate.h"
#include "io/cutting/gcode.h"
#include "io/design/design.h"

namespace fabmesh {

/// A further mesh of a design, validated like the main one (a mould part).
struct NamedSoup {
  std::string name;  ///< used in file names: "side-1", "base"
  TriangleSoup soup;
  ValidationReport validation;  ///< validate_built's report of `soup`, with its builder's proof
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
    std::string name;  ///< as in the mesh outputs' file names: "side-1", "base"
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

/// The design's own curves and patches as built, before any mesh: what its
/// plot draws. The curves are in the design's order (design_curves).
struct BuiltShape {
  std::vector<NamedBuiltCurve> curves;
  std::optional<PatchNetwork> patches;  ///< a surface's patch network
  /// A thickened surface's sheets as proven by its tessellation, when an
  /// output needs the exact shape (BuildContext::wants_exact).
  std::optional<ShellGrid> shell;
  /// The exact solid, when the design's kind has one fabmesh can write
  /// exactly (countertops, solid vessels).
  std::optional<ExactSolid> solid;
  std::optional<ExactMould> mould;  ///< a vessel's mould, when it has one
  /// A vessel: the curves are profiles in the (radius, height) half-plane, revolved about x = 0.
  bool revolved = false;
  /// A vessel's section as its builder made it: closed loops (the profile,
  /// the rim, a shell's inner wall and base, the axis) in the design's units,
  /// at the fired size (before shrinkage's scaling). Empty when not built.
  std::vector<std::vector<Vec2>> section;
};

/// One design built and validated. The soup is what the writers encode
/// (vertices and triangles as validated); a curve design has none.
struct BuiltMesh {
  TriangleSoup soup;
  /// What the builder proved about `soup` (topology, embedding), for
  /// validate_built; empty: everything is analysed and tested.
  ValidationOptions checks;
  ValidationReport validation;  ///< validate_built(soup, checks)
  MeshPurpose purpose = MeshPurpose::Fabrication;
  double max_deviation = 0.0;  ///< proven bound of the mesh (or the curves) against the exact shape
  /// How the geometry builders divided the build's tolerance, each stage
  /// named by what it builds ("section", "mould: revolution", "cnc: G-code rounding").
  std::vector<ToleranceShare> tolerance_shares;
  nlohmann::json facts;  ///< builder facts for the report, e.g. {"angular_segments": 128}
  /// Drawing of the design's curves at true size: a countertop's cutting
  /// outline (outline first, then holes), a vessel's profile template, a curve.
  std::vector<CutLoop> cutting;
  std::vector<NamedSoup> mould_parts;  ///< a vessel's mould, each part validated (validate_built)
  std::optional<Toolpath> toolpath;    ///< a countertop's router path (key `cnc`)
  std::optional<GcodeOptions> gcode;   ///< how its program is written (with `toolpath`)
  BuiltShape shape;                    ///< the curves and patches the mesh was built from
  /// What the builder did other than asked and the user should know (tabs
  /// left out for want of room), for the report's `warnings`.
  std::vector<std::string> warnings;
};

/// What every builder gets besides its design.
struct BuildContext {
  const DesignCommon& common;
  double tolerance = 0.0;      ///< the share of the design's tolerance the mesh may use
  bool wants_cutting = false;  ///< an output needs the cutting outline
  StageTimer& watch;           ///< stage timings of the job
  /// Memory this process can use, bytes (process_memory_limit()); builders
  /// that know their arrays' size in advance refuse larger meshes with it.
  std::size_t memory_limit = std::numeric_limits<std::size_t>::max();
  bool wants_exact = false;  ///< an output writes the exact shape (step)
};

/// The smaller of this machine's physical memory and the process's address
/// space limit (RLIMIT_AS), bytes.
std::size_t process_memory_limit();

/// Appends `shares` to `to`, each stage named after `prefix` ("mould: section").
inline void append_shares(std::vector<ToleranceShare>& to, const std::string& prefix,
                          const std::vector<ToleranceShare>& shares) {
  for (ToleranceShare s : shares) {
    s.stage = prefix + s.stage;
    to.push_back(std::move(s));
  }
}

}  // namespace fabmesh
