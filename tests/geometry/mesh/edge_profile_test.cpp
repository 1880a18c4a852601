#include "geometry/mesh/edge_profile.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/validation/validate.h"

using namespace fabmesh;

namespace {

const std::vector<EdgeProfileKind> kRounded = {EdgeProfileKind::Eased, EdgeProfileKind::HalfBullnose,
                                               EdgeProfileKind::Bullnose, EdgeProfileKind::Bevel};

std::vector<Vec2> rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// The area and the length of the profiled faces' cross-section curve (the
// arcs' and the bevel's length), per unit length of edge.
double section_length(const EdgeProfile& p) {
  const ProfileEdges e = profile_edges(p);
  if (e.chamfer) return std::sqrt(2.0) * e.top;
  return 0.5 * M_PI * (e.top + e.bottom);
}

ValidationReport checked(const TriangleSoup& mesh) {
  ValidationReport r = validate(mesh);
  CHECK(r.self_intersection == IntersectionCheck::Tested);
  return r;
}

}  // namespace

TEST_CASE("edge profile: levels climb, follow the profile and keep their chords within the tolerance",
          "[geometry][edge_profile]") {
  for (const EdgeProfileKind kind : kRounded) {
    INFO(to_string(kind));
    const double t = 30.0;
    const EdgeProfile p{kind, kind == EdgeProfileKind::Eased ? 3.0 : 12.0};
    double sagitta = -1.0;
    const std::vector<ProfileLevel> levels = profile_levels(p, t, 0.01, &sagitta);
    REQUIRE(levels.size() >= 3);
    CHECK(levels.front().z == 0.0);
    CHECK(levels.back().z == t);
    CHECK(sagitta >= 0.0);
    CHECK(sagitta <= 0.01);
    for (std::size_t k = 0; k < levels.size(); ++k) {
      if (k > 0) CHECK(levels[k].z > levels[k - 1].z);
      CHECK(std::abs(levels[k].inset - profile_inset(p, t, levels[k].z)) <= 1e-12 * t);
    }
    CHECK(levels.back().inset == p.radius);  // every profile takes the radius off the top face
  }
  // The full bullnose: its two rounds meet half way, at one level.
  const std::vector<ProfileLevel> full = profile_levels({EdgeProfileKind::Bullnose, 15.0}, 30.0, 0.01);
  std::size_t at_middle = 0;
  for (const ProfileLevel& l : full) at_middle += l.z == 15.0 ? 1 : 0;
  CHECK(at_middle == 1);
  CHECK(max_profile_radius(EdgeProfileKind::Bullnose, 30.0) == 15.0);
  CHECK(max_profile_radius(EdgeProfileKind::HalfBullnose, 30.0) == 30.0);
}

TEST_CASE("edge profile: a profiled rectangle is valid, and its volume is the exact one less its chords'",
          "[geometry][edge_profile]") {
  const double L = 1200.0, W = 600.0, t = 30.0, tolerance = 0.01;
  for (const EdgeProfileKind kind : kRounded) {
    for (const double radius : {3.0, 10.0, 15.0}) {
      if (radius > max_profile_radius(kind, t)) continue;
      INFO(to_string(kind) << " radius " << radius);
      const EdgeProfile p{kind, radius};
      const ProfiledSlab slab =
          build_profiled_slab({rectangle(0, 0, L, W), {true, true, true, true}, {}, "top"}, p, t, tolerance);
      const ValidationReport r = checked(slab.mesh);
      CHECK(r.valid());
      CHECK(r.genus == std::optional<long>(0));
      // Each level is the rectangle shrunk by d(z) on every side: the exact
      // volume is the integral of (L - 2d)(W - 2d).
      const ProfileMoments m = profile_moments(p, t);
      const double exact = L * W * t - 2.0 * (L + W) * m.area + 4.0 * m.square;
      // Chords of a convex round lie inside it, within the sagitta.
      const double bound = slab.sagitta * 2.0 * (L + W) * section_length(p) * 1.001;
      CHECK(r.volume <= exact + 1e-9 * exact);
      CHECK(exact - r.volume <= bound + 1e-9 * exact);
      if (kind == EdgeProfileKind::Bevel) CHECK(std::abs(r.volume - exact) <= 1e-9 * exact);  // flat: exact
    }
  }
}

TEST_CASE("edge profile: an L with a reflex corner, a cut-out and walls stays valid",
          "[geometry][edge_profile]") {
  // An L: the inside corner (1000, 600) is reflex, rolled round on an arc.
  const std::vector<Vec2> l = {{0, 0}, {2000, 0}, {2000, 600}, {1000, 600}, {1000, 1600}, {0, 1600}};
  const std::vector<Vec2> hole = {{300, 300}, {300, 500}, {700, 500}, {700, 300}};  // clockwise
  for (const EdgeProfileKind kind : kRounded) {
    INFO(to_string(kind));
    const EdgeProfile p{kind, kind == EdgeProfileKind::Eased ? 3.0 : 12.0};
    // Every edge exposed.
    const ProfiledSlab all = build_profiled_slab({l, std::vector<bool>(6, true), {hole}, "L"}, p, 30.0, 0.01);
    const ValidationReport r = checked(all.mesh);
    CHECK(r.valid());
    CHECK(r.genus == std::optional<long>(1));
    // Walls along the back (edges 4 and 5 of the L): the profile ends
    // square on them; and an exposed edge continuing straight into a wall
    // (edge 0 split at x = 1000) ends on a quarter circle.
    const std::vector<Vec2> split = {{0, 0},      {1000, 0},    {2000, 0}, {2000, 600},
                                     {1000, 600}, {1000, 1600}, {0, 1600}};
    const ProfiledSlab walls = build_profiled_slab(
        {split, {false, true, true, true, true, false, false}, {hole}, "L"}, p, 30.0, 0.01);
    const ValidationReport w = checked(walls.mesh);
    CHECK(w.valid());
    CHECK(w.genus == std::optional<long>(1));
    CHECK(w.volume > r.volume);  // less is taken off
  }
}

TEST_CASE("edge profile: a cut-out within the profile's reach is bad input at edges.radius",
          "[geometry][edge_profile]") {
  // The sink's front edge 8 mm from the top's front edge: a 10 mm half bullnose reaches it.
  const std::vector<Vec2> hole = {{300, 8}, {300, 400}, {700, 400}, {700, 8}};
  try {
    build_profiled_slab({rectangle(0, 0, 1200, 600), std::vector<bool>(4, true), {hole}, "top"},
                        {EdgeProfileKind::HalfBullnose, 10.0}, 30.0, 0.01);
    FAIL("no error");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "edges.radius");
    const std::string what = e.what();
    CHECK(what.find("top: the half_bullnose profile does not fit") != std::string::npos);
    CHECK(what.find("meets a cut-out") != std::string::npos);
  }
  // A square edge there is fine, and a 5 mm one.
  CHECK_NOTHROW(build_profiled_slab({rectangle(0, 0, 1200, 600), std::vector<bool>(4, true), {hole}, "top"},
                                    {EdgeProfileKind::HalfBullnose, 5.0}, 30.0, 0.01));
  // A piece narrower than two radii: the ring crosses itself.
  CHECK_THROWS_AS(build_profiled_slab({rectangle(0, 0, 1200, 16), std::vector<bool>(4, true), {}, "strip"},
                                      {EdgeProfileKind::HalfBullnose, 10.0}, 30.0, 0.01),
                  GeometryError);
}
