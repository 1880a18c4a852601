#include "geometry/mould/mould.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/fairing/gauss_legendre.h"
#include "geometry/mould/shrinkage.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mould/mould_fixtures.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

// A part validated as the pipeline validates it: its proof of embedding in
// place of the 3D self-intersection test.
ValidationReport validated(const MouldPart& part) {
  ValidationOptions options;
  options.embedding = part.proof;
  return validate(part.soup, options);
}

struct Variant {
  std::string name;
  MouldOptions options;
};

std::vector<Variant> variants() {
  std::vector<Variant> v;
  v.push_back({"2 parts, cylinder", cm_options()});
  MouldOptions three = cm_options();
  three.parts = 3;
  three.key_clearance = 0.1;  // 3 parts pull 30 degrees off the keys' axes: >= 0.6 (1/cos 30 - 1) = 0.093
  three.base_part = true;
  three.spare_shape = SpareShape::Cone;
  three.keys = 2;  // the 45 mm cup leaves room above the cut for two 6 mm keys per plane
  v.push_back({"3 parts, base part, cone spare", three});
  MouldOptions box = cm_options();
  box.block = BlockShape::Box;
  box.base_part = true;
  box.base_height = 0.5;
  box.keys = 2;
  v.push_back({"2 parts, box, base part cut 5 mm up", box});
  MouldOptions box3 = three;
  box3.block = BlockShape::Box;
  box3.base_part = false;
  box3.keys = 3;
  v.push_back({"3 parts, box", box3});
  MouldOptions plain = cm_options();
  plain.keys = 0;
  plain.spare_shape = SpareShape::Cone;
  plain.spare_taper_deg = 30;
  v.push_back({"2 parts, no keys, wide cone spare", plain});
  return v;
}

}  // namespace

TEST_CASE("mould: every part of the golden vessel's mould is a closed outward embedded genus-0 solid",
          "[mould]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  for (const Variant& v : variants()) {
    INFO(v.name);
    const Mould m = build_mould(profile, v.options);
    CHECK(m.parts.size() == static_cast<std::size_t>(v.options.parts) + (v.options.base_part ? 1 : 0));
    for (const MouldPart& part : m.parts) {
      INFO(part.name);
      const ValidationReport full = validate(part.soup);  // the 3D self-intersection test included
      for (const std::string& d : describe_defects(full)) INFO(d);
      CHECK(full.valid());
      CHECK(full.self_intersection == IntersectionCheck::Tested);
      CHECK_FALSE(full.self_intersecting);
      CHECK(full.degenerate_faces == 0);
      CHECK(full.components == 1);
      REQUIRE(full.genus.has_value());
      CHECK(*full.genus == 0);
      CHECK(full.oriented_outward);
      const ValidationReport proven = validated(part);
      CHECK(proven.valid());
      CHECK(proven.volume == Approx(full.volume).epsilon(1e-12));
    }
  }
}

namespace {

// Lateral area of the exact cavity (the master profile's surface of revolution, Pappus by quadrature,
// and the reservoir's cylinder or cone); the floor and the opening are flat.
double exact_cavity_lateral_area(const Mould& m, const CompositeCurve& fired) {
  const CompositeCurve master = scale_curve(fired, m.sizes.factor);
  const QuadratureRule q = gauss_legendre(40);
  double area = 0.0;
  for (const Segment& s : master.segments()) {
    for (std::size_t i = 0; i < q.nodes.size(); ++i) {
      const CurveJet j = s.jet(q.nodes[i]);
      area += q.weights[i] * 2.0 * M_PI * j[0].x() * j[1].norm();
    }
  }
  const double r1 = m.section.rim_radius, r2 = m.section.opening_radius,
               h = m.section.z_top - m.section.rim_z;
  return area + M_PI * (r1 + r2) * std::hypot(h, r2 - r1);
}

}  // namespace

// Every mesh lies within max_deviation <= tolerance of its exact surface, and
// only the curved surfaces deviate: the cavity's lateral surface, a cylinder
// block's side and the keys' hemispheres (the caps, the top, the bottom, the
// cut and a box's sides are exact planes). To first order the solid between
// a mesh surface and its exact surface has volume <= deviation x area (for
// an inscribed circle or convex polyhedron it is about 2/3 of that), so
// plaster (sum of the part meshes) + exact cavity (spare included) - exact
// block - exact key volumes (domes added, pits removed) is within
// tolerance x (cavity lateral + block side + hemispheres' area).
TEST_CASE(
    "mould: the parts plus the cavity and the spare fill the block, keys aside, within tolerance x area",
    "[mould][volume]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  for (const Variant& v : variants()) {
    INFO(v.name);
    const Mould m = build_mould(profile, v.options);
    const MouldSection& s = m.section;
    double plaster = 0.0;
    for (const MouldPart& part : m.parts) plaster += validated(part).volume;
    const double block_side =
        v.options.block == BlockShape::Box ? 0.0 : 2.0 * M_PI * s.block_radius * (s.z_top - s.z_bottom);
    const double r = m.keys.radius, rs = m.keys.socket_radius;
    // Keys on every split plane and, with a base part, one on the base cut per side part.
    const std::size_t base_keys = s.has_cut && !m.keys.centres.empty() ? m.splits.size() : 0;
    const double hemispheres = static_cast<double>(m.splits.size() * m.keys.centres.size() + base_keys) *
                               2.0 * M_PI * (r * r + rs * rs);
    const double curved = exact_cavity_lateral_area(m, profile) + block_side + hemispheres;
    const double bound = v.options.tolerance * curved;
    const double error = plaster + m.cavity_volume - m.block_volume - m.key_volume;
    INFO("plaster " << plaster << " cavity " << m.cavity_volume << " block " << m.block_volume << " keys "
                    << m.key_volume << " error " << error << " bound " << bound);
    CHECK(std::abs(error) <= bound);
    CHECK(m.volume_error_bound <= bound * (1 + 1e-9));
    CHECK(std::abs(error) <= m.volume_error_bound);
    CHECK(m.plaster_volume == Approx(plaster).epsilon(1e-12));
  }
}

TEST_CASE("mould: assembled, every bump sits centred in its socket with the clearance all round",
          "[mould][keys]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  for (const Variant& v : variants()) {
    INFO(v.name);
    const Mould m = build_mould(profile, v.options);
    const double clearance = v.options.key_clearance;
    const double pit_deviation = 2.0 * m.keys.socket_radius * (1.0 - std::cos(M_PI / m.keys.segments));
    // A bump on part a in a socket of part b: the same centre and axis, the clearance all round.
    auto check_pair = [&](const MouldPart& a, const KeyFeature& bump, const MouldPart& b,
                          const KeyFeature& socket) {
      CHECK((bump.centre - socket.centre).norm() == 0.0);
      CHECK((bump.axis - socket.axis).norm() == 0.0);
      CHECK(socket.radius == Approx(bump.radius + clearance).epsilon(1e-15));
      // The pit's triangles: those whose corners are all the socket's vertices.
      std::vector<char> in_pit(b.soup.vertices.size(), 0);
      for (auto i : socket.vertices) in_pit[i] = 1;
      std::vector<std::array<Vec3, 3>> pit;
      for (const auto& t : b.soup.triangles) {
        if (in_pit[t[0]] && in_pit[t[1]] && in_pit[t[2]]) {
          pit.push_back({b.soup.vertices[t[0]], b.soup.vertices[t[1]], b.soup.vertices[t[2]]});
        }
      }
      REQUIRE(!pit.empty());
      for (auto i : bump.vertices) {
        const Vec3 p = a.soup.vertices[i] - socket.centre;
        CHECK(p.norm() <= bump.radius * (1 + 1e-12));  // on the bump's sphere, inside the socket's
        CHECK(p.dot(socket.axis) >= -1e-12);           // on the socket's side of the split plane
        double gap = std::numeric_limits<double>::infinity();
        for (const auto& t : pit)
          gap = std::min(gap, point_triangle_distance(a.soup.vertices[i], t[0], t[1], t[2]));
        CHECK(gap >= clearance - pit_deviation - 1e-12);
      }
    };
    std::size_t pairs = 0, base_pairs = 0;
    for (int k = 0; k < v.options.parts; ++k) {
      const MouldPart& a = m.parts[static_cast<std::size_t>(k)];
      const MouldPart& b = m.parts[static_cast<std::size_t>((k + 1) % v.options.parts)];
      for (const KeyFeature& bump : a.keys) {
        if (!bump.bump) continue;
        const KeyFeature* socket = nullptr;
        for (const KeyFeature& f : b.keys) {
          if (!f.bump && !f.on_base && f.key == bump.key) socket = &f;
        }
        REQUIRE(socket != nullptr);
        ++pairs;
        check_pair(a, bump, b, *socket);
      }
    }
    // With a base part: each side part has one socket in its bottom, over a bump on the base's top.
    if (m.section.has_cut && !m.keys.centres.empty()) {
      const MouldPart& base = m.parts.back();
      REQUIRE(base.kind == MouldPartKind::Base);
      for (int k = 0; k < v.options.parts; ++k) {
        const MouldPart& side = m.parts[static_cast<std::size_t>(k)];
        std::size_t sockets = 0;
        for (const KeyFeature& socket : side.keys) {
          if (!socket.on_base) continue;
          ++sockets;
          CHECK(!socket.bump);
          CHECK(socket.axis == Vec3(0.0, 0.0, 1.0));
          CHECK(socket.centre.z() == m.section.z_cut);
          const KeyFeature* bump = nullptr;
          for (const KeyFeature& f : base.keys) {
            if (f.bump && f.on_base && f.key == socket.key) bump = &f;
          }
          REQUIRE(bump != nullptr);
          ++base_pairs;
          check_pair(base, *bump, side, socket);
        }
        CHECK(sockets == 1);
      }
      CHECK(base.keys.size() == static_cast<std::size_t>(v.options.parts));
    }
    CHECK(base_pairs ==
          (m.section.has_cut && !m.keys.centres.empty() ? static_cast<std::size_t>(v.options.parts) : 0));
    CHECK(pairs == static_cast<std::size_t>(v.options.parts) * m.keys.centres.size());
  }
}

namespace {

// A bowl on a foot ring: the profile runs from the floor (1.5, 0.5) down to the foot (2, 0), then up to
// the rim (2.5, 5) through the belly (3, 2). The ring of plaster inside the foot is trapped.
CompositeCurve foot_ring_profile() { return polyline_profile({{1.5, 0.5}, {2, 0}, {3, 2}, {2.5, 5}}); }

MouldOptions small_options() {
  MouldOptions o;
  o.wall = 2.0;
  o.spare = 1.5;
  o.keys = 2;
  o.key_radius = 0.3;
  o.key_clearance = 0.02;
  o.tolerance = 0.005;
  return o;
}

bool has_point(const std::vector<Undercut>& u, Vec2 p, MouldPartKind kind) {
  for (const Undercut& x : u) {
    if ((x.point - p).norm() < 1e-12 && x.part == kind) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("mould: a profile whose cavity folds back is refused, naming the points where it cannot open",
          "[mould][release]") {
  const CompositeCurve profile = foot_ring_profile();
  MouldOptions o = small_options();
  try {
    build_mould(profile, o);
    FAIL("an undercut mould was built");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "profile");
    const std::string what = e.what();
    CHECK_THAT(what, Catch::Contains("side parts cannot be pulled horizontally"));
    CHECK_THAT(what, Catch::Contains("(r 2, z 0)"));
    CHECK_THAT(what, Catch::Contains("(r 1.5, z 0.5)"));
  }
  o.allow_undercuts = true;
  const Mould m = build_mould(profile, o);
  CHECK(has_point(m.undercuts, {2, 0}, MouldPartKind::Side));
  CHECK(has_point(m.undercuts, {1.5, 0.5}, MouldPartKind::Side));
  for (const Undercut& u : m.undercuts) CHECK(u.point.y() <= 0.5);  // only the foot is in a fold
  CHECK_FALSE(m.warnings.empty());
  CHECK_THAT(m.release_proof, Catch::StartsWith("NOT RELEASABLE"));
  for (const MouldPart& part : m.parts) CHECK(validated(part).valid());
}

TEST_CASE("mould: a cavity widening downward inside the base part is refused, not above a floor cut",
          "[mould][release]") {
  // The cavity is widest at its floor (3, 0) and narrows to (2, 1) before the rim (2.5, 5).
  const CompositeCurve profile = polyline_profile({{3, 0}, {2, 1}, {2.5, 5}});
  MouldOptions o = small_options();
  o.base_part = true;
  o.base_height = 0.0;  // the cut at the floor: the base is a plain slab, the side parts release
  CHECK(build_mould(profile, o).undercuts.empty());
  o.base_height = 0.8;
  try {
    build_mould(profile, o);
    FAIL("an undercut base part was built");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "profile");
    CHECK_THAT(std::string(e.what()), Catch::Contains("base part cannot be pulled down"));
    CHECK_THAT(std::string(e.what()), Catch::Contains("(r 3, z 0)"));
  }
  o.allow_undercuts = true;
  const Mould m = build_mould(profile, o);
  CHECK(has_point(m.undercuts, {3, 0}, MouldPartKind::Base));
  for (const Undercut& u : m.undercuts) CHECK(u.part == MouldPartKind::Base);
}

TEST_CASE("mould: base keys that do not fit the plaster of the cut are refused naming key_radius",
          "[mould][keys]") {
  // Widest at the bottom (r 3 up to z 1), narrowing to the rim (1, 5): the split planes' key sits where
  // the neck leaves room, but the cut at z 0.5 has only the 0.8 wall between the cavity and the block.
  const CompositeCurve profile = polyline_profile({{3, 0}, {3, 1}, {1, 5}});
  MouldOptions o = small_options();
  o.wall = 0.8;
  o.base_part = true;
  o.base_height = 0.5;
  o.key_positions = {{2.2, 4.0}};
  try {
    build_mould(profile, o);
    FAIL("base keys were placed in too narrow a cut");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "key_radius");
    CHECK_THAT(std::string(e.what()), Catch::Contains("base part's keys"));
    CHECK_THAT(std::string(e.what()), Catch::Contains("the block"));
  }
  // A thicker wall leaves them room: a socket in each side part's bottom over a bump on the base.
  o.wall = 2.0;
  const Mould m = build_mould(profile, o);
  REQUIRE(m.keys.base_centres.size() == 2);
  for (const MouldPart& part : m.parts) {
    std::size_t on_base = 0;
    for (const KeyFeature& k : part.keys) on_base += k.on_base ? 1 : 0;
    CHECK(on_base == (part.kind == MouldPartKind::Base ? 2u : 1u));
    CHECK(validate(part.soup).valid());  // the full 3D test, not the part's proof
  }
  CHECK_THAT(m.release_proof, Catch::Contains("the base pulls down off them first"));
}

TEST_CASE("mould: a key too close to the cavity is refused naming the key", "[mould][keys]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  MouldOptions o = cm_options();
  const Mould ok = build_mould(profile, o);
  const MouldSection& s = ok.section;
  Vec2 widest = s.cavity.front();
  for (const Vec2& p : s.cavity) widest = p.x() > widest.x() ? p : widest;
  const double mid = 0.5 * (s.z_bottom + s.z_top);
  // keys[0] in the middle of the wall well above the belly, keys[1] 0.7 out from the belly: its socket
  // (0.62) would leave 0.08 of plaster where the margin asks for 0.3.
  o.key_positions = {{0.5 * (s.cavity_radius + s.block_radius), widest.y() + 3.0},
                     {widest.x() + 0.7, widest.y()}};
  try {
    build_mould(profile, o);
    FAIL("a key touching the cavity was accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "keys[1]");
    CHECK_THAT(std::string(e.what()), Catch::Contains("keys[1] at (r"));
    CHECK_THAT(std::string(e.what()), Catch::Contains("of the cavity near (r"));
  }
  o.key_positions = {{s.block_radius - 0.5, mid}};
  try {
    build_mould(profile, o);
    FAIL("a key breaking through the block was accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "keys[0]");
    CHECK_THAT(std::string(e.what()), Catch::Contains("block's edge"));
  }
}

TEST_CASE("mould: the block is a wall thicker than the cavity everywhere, a smaller block is refused",
          "[mould]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  MouldOptions o = cm_options();
  const Mould m = build_mould(profile, o);
  const MouldSection& s = m.section;
  CHECK(s.block_radius == Approx(s.cavity_radius + o.wall).epsilon(1e-15));
  for (const Vec2& p : s.cavity) {
    CHECK(s.block_radius - (p.x() + s.max_deviation) >= o.wall * (1 - 1e-12));
    CHECK(p.y() - s.max_deviation - s.z_bottom >= o.wall * (1 - 1e-12));
  }
  o.block_radius = s.block_radius - 0.01;
  try {
    build_mould(profile, o);
    FAIL("a block thinner than the wall was accepted");
  } catch (const RangeError& e) {
    CHECK(e.field() == "block_radius");
    CHECK(e.value() == o.block_radius);
  }
  o.block_radius = s.block_radius + 1.0;
  CHECK(build_mould(profile, o).section.block_radius == o.block_radius);
}

TEST_CASE("mould: three parts with sockets too tight for their oblique pull are refused naming key_clearance",
          "[mould][keys][release]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  MouldOptions o = cm_options();
  o.parts = 3;
  o.keys = 3;
  o.key_clearance = 0.02;  // needs 0.6 (1 / cos 30 deg - 1) = 0.0928
  try {
    build_mould(profile, o);
    FAIL("binding keys were accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "key_clearance");
    CHECK_THAT(std::string(e.what()), Catch::Contains("0.0928"));
  }
  o.key_clearance = 0.6 / std::cos(M_PI / 6) - 0.6 + 1e-9;
  CHECK(build_mould(profile, o).warnings.empty());
  o.parts = 2;
  o.key_clearance = 0.0;  // straight pull: a bump the socket's size releases
  CHECK(build_mould(profile, o).warnings.empty());
}

TEST_CASE("mould: bad options are RangeErrors naming the option", "[mould]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  auto field_of = [&](MouldOptions o) {
    try {
      build_mould(profile, o);
    } catch (const RangeError& e) {
      return e.field();
    }
    return std::string("none");
  };
  MouldOptions o = cm_options();
  o.parts = 4;
  CHECK(field_of(o) == "parts");
  o = cm_options();
  o.wall = 0;
  CHECK(field_of(o) == "wall");
  o = cm_options();
  o.spare = -1;
  CHECK(field_of(o) == "spare");
  o = cm_options();
  o.shrinkage = 1.0;
  CHECK(field_of(o) == "shrinkage");
  o = cm_options();
  o.base_part = true;
  o.base_height = 10.0;
  CHECK(field_of(o) == "base_height");
}

TEST_CASE("mould: a hemispherical bowl whose bottom is on the axis, with and without a base part",
          "[mould]") {
  // The quarter circle of radius 3 about (0, 3): the bottom (0, 0) on the axis, the rim (3, 3).
  EllipseArcParams e;
  e.center = {0, 3};
  e.a = e.b = 3;
  e.from_deg = -90;
  e.to_deg = 0;
  const CompositeCurve bowl({Segment::ellipse_arc(e)}, false);
  MouldOptions o = small_options();
  for (const bool base : {false, true}) {
    INFO("base part " << base);
    o.base_part = base;
    o.base_height = base ? 1.0 : 0.0;
    const Mould m = build_mould(bowl, o);
    // The exact hemisphere and the cylindrical spare: (2/3) pi 27 + pi 9 spare.
    CHECK(m.cavity_volume == Approx(2.0 / 3.0 * M_PI * 27.0 + M_PI * 9.0 * o.spare).epsilon(1e-12));
    for (const MouldPart& part : m.parts) {
      INFO(part.name);
      const ValidationReport full = validate(part.soup);
      CHECK(full.valid());
      CHECK(full.genus == 0);
    }
    CHECK(std::abs(m.plaster_volume + m.cavity_volume - m.block_volume - m.key_volume) <=
          m.volume_error_bound);
  }
  o.base_height = 0.0;  // a cut through the bottom point would pinch the side parts there
  try {
    build_mould(bowl, o);
    FAIL("a cut through the axis point was accepted");
  } catch (const GeometryError& err) {
    CHECK(err.where() == "base_height");
  }
}

TEST_CASE("mould: a base cut the profile crosses twice names both crossings", "[mould]") {
  MouldOptions o = small_options();
  o.base_part = true;
  o.base_height = 1.0;  // the cut at z = 1: the profile goes below it, back above, and below again
  const CompositeCurve zigzag = polyline_profile({{2, 0}, {3, 2}, {3.5, 0.5}, {4, 4}});
  try {
    build_mould(zigzag, o);
    FAIL("a cut crossing the cavity twice was accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "base_height");
    const std::string message = e.what();
    INFO(message);
    const std::size_t first = message.find("(at ");
    const std::size_t again = message.find(" and again near ");
    REQUIRE(first != std::string::npos);
    REQUIRE(again != std::string::npos);
    const std::string one = message.substr(first + 4, again - first - 4);
    const std::string other = message.substr(again + 16, message.find(')', again + 16) - again - 15);
    CHECK(one != other);  // two places, not one named twice
    CHECK(one == "(r 3.5, z 0.5)");
  }
}

TEST_CASE("mould: profiles that cannot make a cavity are GeometryErrors naming what is wrong", "[mould]") {
  MouldOptions o = small_options();
  auto where_of = [&](const CompositeCurve& c) {
    try {
      build_mould(c, o);
    } catch (const GeometryError& e) {
      return e.where();
    }
    return std::string("none");
  };
  // The profile rises 1 above its rim: a 0.5 reservoir would not cover it.
  o.spare = 0.5;
  CHECK(where_of(polyline_profile({{2, 0}, {3, 6}, {2.5, 5}})) == "spare");
  o.spare = 1.5;
  CHECK(where_of(polyline_profile({{2, 0}, {3, 2}, {0, 5}})) == "profile");  // rim on the axis
  CHECK(where_of(polyline_profile({{2, 0}, {0, 2}, {2, 4}})) == "profile");  // touches the axis
  CHECK_THROWS_WITH(build_mould(polyline_profile({{2, 0}, {3, 3}, {1, 2}, {3.5, 2.5}}), o),
                    Catch::Contains("is not simple near"));  // crosses itself
  CHECK(where_of(CompositeCurve(
            {Segment::line({1, 0}, {2, 1}), Segment::line({2, 1}, {1, 2}), Segment::line({1, 2}, {1, 0})},
            true)) == "profile");  // closed
}
