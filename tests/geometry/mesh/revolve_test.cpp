// The revolution's connectivity is proven by its construction (revolve's
// TopologyProof) and that proof replaces the connectivity analysis in the
// pipeline; these cases check it against the full analysis of the soup, which
// assumes nothing, on sections of every kind revolve accepts.

#include "geometry/mesh/revolve.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <set>

#include "geometry/core/errors.h"
#include "geometry/mesh/revolution_margin.h"
#include "geometry/validation/detail/topology.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/validation/moved_from.h"

using namespace fabmesh;

namespace {

using Loops = std::vector<std::vector<Vec2>>;
using test::validate_moved;

// Validation with the revolution's own proof of its connectivity and `embedding`.
ValidationOptions proven(const RevolvedSoup& r, const EmbeddingProof& embedding) {
  ValidationOptions options;
  options.topology = r.topology;
  options.embedding = embedding;
  return options;
}

// A star-shaped loop around `centre` (counter-clockwise, off the axis when
// the radii stay below centre.x()): it revolves into a torus.
std::vector<Vec2> star(std::mt19937& rng, Vec2 centre, int points, double r_min, double r_max) {
  std::uniform_real_distribution<double> radius(r_min, r_max);
  std::vector<Vec2> loop;
  for (int i = 0; i < points; ++i) {
    const double t = 2 * M_PI * i / points;
    const double r = radius(rng);
    loop.emplace_back(centre.x() + r * std::cos(t), centre.y() + r * std::sin(t));
  }
  return loop;
}

// A profile rising monotonically from (0, z0) to (0, z1) at random radii,
// closed down the axis: a solid whose two poles end one axis edge.
std::vector<Vec2> solid(std::mt19937& rng, double z0, double z1, int points) {
  std::uniform_real_distribution<double> radius(0.2, 2.0);
  std::vector<Vec2> loop = {{0.0, z0}};
  for (int i = 1; i <= points; ++i) loop.emplace_back(radius(rng), z0 + (z1 - z0) * i / (points + 1));
  loop.emplace_back(0.0, z1);
  return loop;
}

// What the proof states must be what analysing the soup from scratch finds.
void require_proof_holds(const Loops& loops, int segments) {
  const RevolvedSoup r = revolve(loops, RevolveOptions{segments});
  INFO(loops.size() << " loops, " << segments << " segments, " << r.soup.triangles.size() << " triangles");
  REQUIRE(r.soup.triangles.size() == revolved_triangle_count(loops, segments));
  REQUIRE(r.soup.vertices.size() == revolved_vertex_count(loops, segments));
  const Topology t = analyse_topology(r.soup);
  CHECK(t.boundary_edges.count == 0);
  CHECK(t.non_manifold_edges.count == 0);
  CHECK(t.non_manifold_vertices.count == 0);
  CHECK(t.inconsistent_edges.count == 0);
  CHECK(t.duplicate_faces.count == 0);
  CHECK(t.referenced_vertices == r.soup.vertices.size());
  CHECK(t.components == r.topology.components);
  CHECK(t.euler_characteristics == r.topology.euler_characteristics);
  for (const auto& f : r.soup.triangles) REQUIRE((f[0] != f[1] && f[1] != f[2] && f[2] != f[0]));

  // The whole report: the full validation (3D test included) against the constructed one.
  const ValidationReport full = validate(r.soup);
  const ValidationReport built = validate(r.soup, proven(r, EmbeddingProof{"simple section"}));
  CHECK(full.valid());
  CHECK(built.valid());
  CHECK(built.components == full.components);
  CHECK(built.euler_characteristics == full.euler_characteristics);
  CHECK(built.genus == full.genus);
  CHECK(built.degenerate_faces == full.degenerate_faces);
  CHECK(built.volume == full.volume);
  CHECK(built.area == full.area);
  CHECK(built.oriented_outward == full.oriented_outward);
  CHECK(built.topology_proof == r.topology.statement);
  CHECK(built.self_intersection == IntersectionCheck::ProvenByConstruction);
}

}  // namespace

TEST_CASE("revolve: the proven connectivity is what the full analysis finds", "[mesh][revolve]") {
  std::mt19937 rng(7);
  for (const int segments : {3, 4, 7, 64}) {
    SECTION("tori, " + std::to_string(segments) + " segments") {
      for (int k = 0; k < 10; ++k)
        require_proof_holds({star(rng, {3.0, 0.0}, 3 + k * 5, 0.5, 1.5)}, segments);
    }
    SECTION("solids from pole to pole, " + std::to_string(segments) + " segments") {
      for (int k = 0; k < 10; ++k) require_proof_holds({solid(rng, 0.0, 3.0, 1 + k * 4)}, segments);
    }
    SECTION("several loops in one mesh, " + std::to_string(segments) + " segments") {
      require_proof_holds({solid(rng, 0.0, 3.0, 6), star(rng, {6.0, 1.0}, 9, 0.5, 1.5), solid(rng, 4, 5, 2)},
                          segments);
    }
  }
}

TEST_CASE("revolve: a loop with two axis edges sweeps two spheres", "[mesh][revolve]") {
  // A C-shaped section (counter-clockwise) touching the axis along z in [0, 1]
  // and [4, 5]: a closed cylinder with a closed cavity inside, one arc each.
  const Loops loops = {{{0, 0}, {2, 0}, {2, 5}, {0, 5}, {0, 4}, {1, 4}, {1, 1}, {0, 1}}};
  for (const int segments : {3, 5, 32}) require_proof_holds(loops, segments);
  const RevolvedSoup r = revolve(loops, RevolveOptions{32});
  CHECK(r.topology.components == 2);
  CHECK(r.topology.euler_characteristics == std::vector<long>{2, 2});
  const double n = 32, s = std::sin(2 * M_PI / n);
  // Two prisms of regular 32-gons: outer radius 2 height 5, cavity radius 1 height 3.
  CHECK(validate(r.soup).volume == Approx(n / 2 * s * (4 * 5 - 1 * 3)).epsilon(1e-12));
}

TEST_CASE("revolve: the layout is vertices loop by loop and rings from angle 0", "[mesh][revolve]") {
  const Loops loops = {{{0, 0}, {1, 0}, {1, 2}, {0, 2}}};
  const RevolvedSoup r = revolve(loops, RevolveOptions{4});
  REQUIRE(r.soup.vertices.size() == 10);
  CHECK(r.soup.vertices[0] == Vec3(0, 0, 0));  // pole
  CHECK(r.soup.vertices[1] == Vec3(1, 0, 0));  // ring of (1, 0) at angle 0
  CHECK(r.soup.vertices[9] == Vec3(0, 0, 2));  // the top pole
  // Every triangle of a counter-clockwise section faces away from the axis or its poles.
  CHECK(validate(r.soup).oriented_outward);
}

TEST_CASE("revolve: bad sections are refused", "[mesh][revolve][errors]") {
  CHECK_THROWS_AS(revolve({{{1, 0}, {2, 0}, {1, 1}}}, RevolveOptions{2}), RangeError);
  CHECK_THROWS_AS(revolve({{{1, 0}, {-2, 0}, {1, 1}}}, RevolveOptions{8}), RangeError);
  // A single axis vertex (no axis edge): the mesh would be pinched there.
  CHECK_THROWS_WITH(revolve({{{0, 0}, {2, 1}, {1, 2}}}, RevolveOptions{8}),
                    Catch::Contains("axis neighbours"));
}

TEST_CASE("angular_segments: the fewest steps whose chord sagitta is within the tolerance",
          "[mesh][revolve]") {
  for (const double radius : {0.5, 3.0, 47.0, 1e4}) {
    for (const double tol : {1e-3, 0.05, 0.4}) {
      const int n = angular_segments(radius, tol);
      CHECK(angular_step(n) == Approx(2.0 * M_PI / n));
      CHECK(chord_sagitta(radius, angular_step(n)) <= tol * (1.0 + 1e-12));
      if (n > 3) CHECK(chord_sagitta(radius, angular_step(n - 1)) > tol);
    }
  }
  CHECK(chord_sagitta(2.0, M_PI) == Approx(2.0));  // a diameter: the chord passes through the centre
}

namespace {

// `soup` with every vertex moved by `distance` in a random direction.
TriangleSoup jittered(TriangleSoup soup, double distance, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (Vec3& p : soup.vertices) {
    const Vec3 d(g(rng), g(rng), g(rng));
    p += distance * d.normalized();
  }
  return soup;
}

// Two squares side by side, `gap` apart, the first one reaching the axis.
Loops two_blocks(double gap) {
  return {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{1 + gap, 0}, {2 + gap, 0}, {2 + gap, 1}, {1 + gap, 1}}};
}

}  // namespace

TEST_CASE("revolution_margin: vertices moved by less than it leave the revolution embedded",
          "[mesh][revolve][margin]") {
  std::mt19937 rng(11);
  const std::vector<Loops> sections = {
      {star(rng, {3.0, 0.0}, 40, 0.5, 1.5)},
      {solid(rng, 0.0, 3.0, 30)},
      {{{0, 0}, {2, 0}, {2, 5}, {0, 5}, {0, 4}, {1, 4}, {1, 1}, {0, 1}}},
      two_blocks(0.01),
  };
  for (const Loops& loops : sections) {
    // (Coarser revolutions may get 0: faces lie within r_max (1 - cos(pi / n)) of
    // their section edge, and that sagitta must stay below the section's clearance.)
    for (const int segments : {64, 128}) {
      const double margin = revolution_margin(loops, segments);
      const TriangleSoup soup = revolve(loops, RevolveOptions{segments}).soup;
      INFO(segments << " segments, margin " << margin);
      REQUIRE(margin > 0.0);
      for (int trial = 0; trial < 20; ++trial) {
        const ValidationReport moved = validate(jittered(soup, 0.999 * margin, rng));
        REQUIRE(moved.self_intersection == IntersectionCheck::Tested);
        CHECK(moved.intersecting_pairs == 0);
      }
    }
  }
}

TEST_CASE("revolution_margin: a narrow gap bounds it, and closing the gap makes faces meet",
          "[mesh][revolve][margin]") {
  const int segments = 48;
  for (const double gap : {0.1, 0.05, 0.02}) {
    // The gap's walls at r = 1 and 1 + gap; every face lies within a sagitta of its section edge.
    const double sagitta = (2 + gap) * (1 - std::cos(M_PI / segments));
    const double margin = revolution_margin(two_blocks(gap), segments);
    INFO("gap " << gap << ", margin " << margin);
    CHECK(margin <= gap / 2);
    CHECK(margin >= (gap - 2 * sagitta) / 2 - 1e-9);
    // Pushing the facing walls toward each other by a little more than gap / 2 each makes them cross.
    TriangleSoup soup = revolve(two_blocks(gap), RevolveOptions{segments}).soup;
    for (Vec3& p : soup.vertices) {
      const double r = std::hypot(p.x(), p.y());
      const double push = std::abs(r - 1) < 1e-9         ? 0.51 * gap
                          : std::abs(r - 1 - gap) < 1e-9 ? -0.51 * gap
                                                         : 0.0;
      if (push != 0.0) p *= (r + push) / r;
    }
    CHECK(validate(soup).intersecting_pairs > 0);
  }
  // With many steps the wedges are narrow: two faces of a wall two steps apart
  // are only about r sin(2 pi / n) apart, which then bounds the margin.
  const double wedge = std::cos(M_PI / 400) * std::sin(2 * M_PI / 400);
  CHECK(revolution_margin(two_blocks(0.1), 400) <= wedge / 2);
  CHECK(revolution_margin(two_blocks(0.1), 400) == Approx(wedge / 2).epsilon(1e-3));
}

TEST_CASE("revolution_margin: a vertex between two poles gets none", "[mesh][revolve][margin]") {
  // A double cone: both fans of its one ring reach the axis.
  CHECK(revolution_margin({{{0, 0}, {1, 1}, {0, 2}}}, 16) == 0.0);
}

TEST_CASE("validate_moved: within the margin the proof replaces the 3D test, beyond it the test runs",
          "[mesh][revolve][margin]") {
  std::mt19937 rng(5);
  const Loops loops = {solid(rng, 0.0, 3.0, 20)};
  const RevolvedSoup r = revolve(loops, RevolveOptions{32});
  const double margin = revolution_margin(loops, 32);
  REQUIRE(margin > 0.0);
  const ValidationReport built = validate(r.soup, proven(r, EmbeddingProof{"simple", margin}));
  CHECK(built.embedding_margin == margin);

  const TriangleSoup near = jittered(r.soup, 0.5 * margin, rng);
  const ValidationReport within = validate_moved(r.soup, built, near);
  CHECK(within.valid());
  CHECK(within.self_intersection == IntersectionCheck::ProvenByConstruction);
  CHECK_THAT(within.embedding_proof, Catch::Contains("less than its margin"));
  CHECK(within.topology_proof == r.topology.statement);
  CHECK(validate(near).valid());  // the full test agrees

  const TriangleSoup far = jittered(r.soup, 2.0 * margin, rng);
  const ValidationReport beyond = validate_moved(r.soup, built, far);
  CHECK(beyond.self_intersection == IntersectionCheck::Tested);
  CHECK(beyond.intersecting_pairs == validate(far).intersecting_pairs);
}
