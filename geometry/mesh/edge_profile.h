#pragma once
// Edge profiles of a stone top: the exposed top edges rounded or bevelled
// (key `edges: {exposed, radius}`), and the slab mesh that carries them.
//
// The profile is a function d(z), the inset of the profiled face from the
// edge at height z (0 at the bottom, t at the top). The solid is the plan
// eroded, at each height, by d(z) from its exposed edges only: the points of
// the plan farther than d(z) from every exposed edge. That is what a router
// profile bit running along those edges leaves, and what fillets and
// chamfers of the top (and bottom) edges of the extruded plan make: mitred
// at a convex corner, rolled round a reflex one, ending square on a wall or
// a seam.

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/soup.h"
#include "geometry/core/types.h"

namespace fabmesh {

enum class EdgeProfileKind {
  Square,        ///< no profile
  Eased,         ///< top and bottom arrises rounded with a small radius (default 3 mm)
  HalfBullnose,  ///< the top edge rounded, quarter circle of `radius` (default half the thickness)
  Bullnose,      ///< top and bottom edges rounded, quarter circles (default radius: half the thickness)
  Bevel,         ///< the top edge chamfered at 45 degrees, legs of `radius` (default 6 mm)
};

/// "square", "eased", "half_bullnose", "bullnose", "bevel".
const char* to_string(EdgeProfileKind kind);

/// The profile of a top's exposed edges, model units.
struct EdgeProfile {
  EdgeProfileKind kind = EdgeProfileKind::Square;
  double radius = 0.0;  ///< the arcs' radius, or the bevel's leg
};

/// The round (or bevel) on the top edge and on the bottom edge: its size
/// (0: none), as fillets and chamfers of the extruded plan are given.
struct ProfileEdges {
  double top = 0.0;
  double bottom = 0.0;
  bool chamfer = false;  ///< a bevel: the top edge chamfered, not filleted
};
ProfileEdges profile_edges(const EdgeProfile& profile);

/// The largest radius the profile takes on a top `thickness` thick (a
/// bullnose's two rounds may meet but not cross).
double max_profile_radius(EdgeProfileKind kind, double thickness);

/// d(z): how far the profiled face lies inside the edge at height z in [0, thickness].
double profile_inset(const EdgeProfile& profile, double thickness, double z);

/// One level of the profiled wall: a height and the inset there.
struct ProfileLevel {
  double z = 0.0;
  double inset = 0.0;
};

/// The heights the mesh's wall is sampled at, bottom to top: 0, the
/// profile's corners, and the points of each quarter circle at equal angles,
/// so many that a chord lies within `tolerance` of its arc (the sagitta
/// r (1 - cos(h / 2)) <= tolerance); lines exact. `sagitta` gets the
/// largest chord's distance from its arc.
std::vector<ProfileLevel> profile_levels(const EdgeProfile& profile, double thickness, double tolerance,
                                         double* sagitta = nullptr);

/// The area of the profile's cross-section taken off the edge (the integral
/// of d(z) over the thickness), exact; and the integral of d(z)^2.
struct ProfileMoments {
  double area = 0.0;
  double square = 0.0;
};
ProfileMoments profile_moments(const EdgeProfile& profile, double thickness);

/// A plan to profile: an outer loop (counter-clockwise) with one flag per
/// edge (edge i from outer[i] to outer[i + 1]; true: exposed, profiled) and
/// holes (clockwise, cut square).
struct ProfiledPlan {
  std::vector<Vec2> outer;
  std::vector<bool> exposed;
  std::vector<std::vector<Vec2>> holes;
  std::string name;  ///< for messages: "piece-1", the design's name
};

struct ProfiledSlab {
  TriangleSoup mesh;
  std::size_t levels = 0;  ///< rings of the outer wall
  double sagitta = 0.0;    ///< the profile's chords against its arcs (profile_levels)
};

/// The plan extruded to `thickness` with its exposed edges profiled: the
/// outer wall as rings, one per level, each the plan eroded by that level's
/// inset from the exposed edges (a convex corner mitred; a reflex corner, or
/// the end of an exposed run, rolled round on an arc within `tolerance`);
/// top and bottom constrained Delaunay triangulations of the rings with the
/// holes; the holes' walls vertical. Closed and outward oriented by
/// construction; every ring is checked simple and clear of the holes (exact
/// predicates), and the whole mesh is left to the full 3D validation.
/// \throw GeometryError at key `edges.radius` naming the plan, the height and
///        a point, when the profile does not fit the plan there (a ring
///        crosses itself or a hole).
/// \throw BudgetError over `max_triangles`.
ProfiledSlab build_profiled_slab(const ProfiledPlan& plan, const EdgeProfile& profile, double thickness,
                                 double tolerance, std::size_t max_triangles = kDefaultMaxTriangles);

}  // namespace fabmesh
