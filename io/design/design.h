#pragma once
// Design files as plain, validated data (product.md "Design files").

#include <string>
#include <variant>
#include <vector>

#include "geometry/curves/curve_spec.h"
#include "geometry/section/vessel_section.h"
#include "geometry/surfaces/patch_network.h"

namespace fabmesh {

/// Keys every design has.
struct DesignCommon {
  std::string path;  ///< the file it was read from
  std::string name;  ///< default: the file's stem
  std::string kind;  ///< curve | vessel | countertop | surface
  std::string units = "mm";
  double tolerance = 0.01;           ///< model units, > 0
  std::vector<std::string> outputs;  ///< default: stl, drc
};

/// kind: curve
struct CurveDesign {
  CurveSpec curve;
};

/// kind: vessel. The profile lies in the (radius, height) plane.
struct VesselDesign {
  CurveSpec profile;
  BodyMode mode = BodyMode::Solid;
  double wall = 0.0;                     ///< shell: > 0
  double base = 0.0;                     ///< shell: > 0 (default: wall)
  std::size_t max_triangles = 20000000;  ///< budget (key `max_triangles`)
};

/// One cut-out of a countertop (sink, cooktop).
struct CountertopHole {
  std::string shape;  ///< ellipse | rounded_rect | outline (for messages)
  CurveSpec curve;    ///< closed; ellipse and rounded_rect expanded into exact ellipse-arc and line segments
};

/// kind: countertop. Outline and holes in the plane; the slab spans z in [0, thickness].
struct CountertopDesign {
  CurveSpec outline;  ///< closed
  std::vector<CountertopHole> holes;
  double thickness = 0.0;                ///< > 0, model units
  double max_edge = 0.0;                 ///< > 0 refines the triangulation; 0: not given
  std::size_t max_triangles = 20000000;  ///< budget (key `max_triangles`)
};

/// kind: surface (h-bezier.md). Patches of a G0/G1/G2-joined network, in file order.
struct SurfaceDesign {
  std::vector<PatchSpec> patches;
  double thickness = 0.0;                ///< > 0: a solid shell along the normals; 0: an open surface
  std::size_t max_triangles = 20000000;  ///< budget (key `max_triangles`)
};

using DesignBody = std::variant<CurveDesign, VesselDesign, CountertopDesign, SurfaceDesign>;

struct Design {
  DesignCommon common;
  DesignBody body;
};

}  // namespace fabmesh
