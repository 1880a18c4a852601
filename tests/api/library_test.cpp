// The library through its public headers only (what a program that links
// fabmesh::fabmesh sees): designs, builds with the command line's proofs and
// bytes, validation of arrays, curves, errors as data, threads.

#include <fabmesh/fabmesh.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Its own small helpers, not tests/pipeline/cli_harness.h's: that harness includes the pipeline's
// headers, and this test must compile against the public headers alone.
std::string example(const std::string& name) {
  return std::string(FABMESH_SOURCE_DIR) + "/configs/examples/" + name;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(FABMESH_TEST_TMP) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs the command line; returns its exit code.
int run_cli(const std::string& arguments) {
  const std::string command = std::string("\"") + FABMESH_BINARY + "\" " + arguments + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A closed tetrahedron, outward.
fabmesh::Mesh tetrahedron() {
  fabmesh::Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

double signed_volume(const fabmesh::Result& r) {
  double six_v = 0.0;
  for (const auto& t : r.triangles) {
    const auto& a = r.vertices[t[0]];
    const auto& b = r.vertices[t[1]];
    const auto& c = r.vertices[t[2]];
    six_v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return six_v / 6.0;
}

}  // namespace

TEST_CASE("the library reports the program's version", "[api]") {
  CHECK(std::string(fabmesh::version()) == FABMESH_VERSION_STRING);
  CHECK(std::string(FABMESH_VERSION_STRING) == FABMESH_EXPECTED_VERSION);
}

TEST_CASE("the golden vessel builds valid with the exact volume within its proven bound", "[api]") {
  const fabmesh::Design design = fabmesh::read_design(example("vessel_golden_solid.yaml"));
  CHECK(design.kind() == "vessel");
  CHECK(design.units() == fabmesh::Unit::cm);
  const fabmesh::Result r = fabmesh::build(design);
  REQUIRE(r.valid);
  CHECK(r.error.empty());
  CHECK(r.validation.valid);
  CHECK(r.validation.watertight);
  CHECK(r.validation.genus == 0);
  CHECK(r.triangles.size() == r.validation.triangles);
  CHECK(r.max_deviation <= r.tolerance);
  // A surface within d of the exact one encloses a volume within area * d of the exact 46.171424531125 cm^3.
  const double exact = 46.171424531125;
  CHECK(std::abs(signed_volume(r) - exact) <= r.validation.area * r.max_deviation);
  CHECK(std::abs(r.validation.volume - signed_volume(r)) <= 1e-9 * exact);
  REQUIRE(r.curves.size() == 1);
  CHECK(r.curves[0].key == "profile");
  CHECK(r.curves[0].max_deviation <= r.tolerance);
  CHECK(r.to_json().find("\"design\":") == 1);
}

TEST_CASE("write_output and write_outputs give the command line's bytes", "[api]") {
  const fs::path dir = fresh_dir("api_write");
  const fabmesh::Design design = fabmesh::read_design(example("vessel_golden_solid.yaml"));
  fabmesh::write_output(design, dir / "lib.3mf");
  REQUIRE(run_cli("run " + example("vessel_golden_solid.yaml") + " -o " + (dir / "cli.3mf").string()) == 0);
  CHECK(bytes_of(dir / "lib.3mf") == bytes_of(dir / "cli.3mf"));

  const std::vector<fs::path> files = fabmesh::write_outputs(design, dir / "lib");
  REQUIRE(run_cli("run " + example("vessel_golden_solid.yaml") + " -o " + (dir / "cli").string() + "/") == 0);
  REQUIRE_FALSE(files.empty());
  for (const fs::path& f : files) CHECK(bytes_of(f) == bytes_of(dir / "cli" / f.filename()));

  const fabmesh::ValidationReport check = fabmesh::check_file(dir / "lib.3mf");
  CHECK(check.valid);
  CHECK(check.error.empty());
}

TEST_CASE("designs from text, overrides, and bad input as data", "[api]") {
  const std::string text = bytes_of(example("vessel_golden_solid.yaml"));
  const fabmesh::Design design = fabmesh::parse_design(text, {{"name", "cup"}}, "cup.yaml");
  CHECK(design.name() == "cup");

  try {
    fabmesh::parse_design(text, {{"body.wall", "-1"}}, "cup.yaml");
    FAIL("a negative wall was accepted");
  } catch (const fabmesh::InputError& e) {
    CHECK(e.exit_code() == 2);
    CHECK(e.key() == "body.wall");
    CHECK(e.location().override_text == "body.wall=-1");
    CHECK(std::string(e.what()).find("-D body.wall=-1") != std::string::npos);
  }
  const std::string typo =
      "name: t\nkind: vessel\nunits: cm\ntolerance: 0.01\nprofile:\n  family: quasi_bspline\n"
      "  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]\n  lambdas: [0, 0, 7]\n";
  try {
    fabmesh::parse_design(typo, {}, "typo.yaml");
    FAIL("lambda 7 was accepted");
  } catch (const fabmesh::InputError& e) {
    CHECK(e.file() == "typo.yaml");
    CHECK(e.line() == 8);
    CHECK(e.column() > 0);
    CHECK(std::string(e.what()).rfind("typo.yaml:8:", 0) == 0);
  }
  CHECK_THROWS_AS(fabmesh::read_design(example("no-such-design.yaml")), fabmesh::InputError);
  CHECK_THROWS_AS(fabmesh::read_design(example("no-such-design.yaml")), fabmesh::MissingFileError);
}

TEST_CASE("validate judges arrays as check judges files", "[api]") {
  const fabmesh::ValidationReport good = fabmesh::validate(tetrahedron());
  CHECK(good.valid);
  CHECK(good.volume == Approx(1.0 / 6.0));
  CHECK(good.to_json().find("\"valid\":true") != std::string::npos);

  fabmesh::Mesh open = tetrahedron();
  open.triangles.pop_back();
  const fabmesh::ValidationReport bad = fabmesh::validate(open);
  CHECK_FALSE(bad.valid);
  CHECK(bad.boundary_edges == 3);
  REQUIRE_FALSE(bad.defects.empty());
  CHECK(bad.defects.front().kind == fabmesh::DefectKind::BoundaryEdge);
  CHECK(std::string(fabmesh::to_string(bad.defects.front().kind)) == "boundary_edge");

  fabmesh::Mesh wrong = tetrahedron();
  wrong.triangles[1][2] = 9;
  try {
    fabmesh::validate(wrong);
    FAIL("an index out of range was accepted");
  } catch (const fabmesh::InputError& e) {
    CHECK(e.key() == "triangles");
  }
  std::vector<std::int64_t> negative = {0, 2, 1, 0, 1, -3};
  fabmesh::MeshView view;
  view.vertices = tetrahedron().vertices.front().data();
  view.vertex_count = 4;
  view.triangles = negative.data();
  view.triangle_count = 2;
  CHECK_THROWS_AS(fabmesh::validate(view), fabmesh::InputError);
}

TEST_CASE("read_mesh and write_mesh round-trip every format", "[api]") {
  const fs::path dir = fresh_dir("api_mesh_io");
  for (const char* ext : {".stl", ".obj", ".ply", ".off", ".3mf", ".glb", ".drc"}) {
    const fs::path path = dir / (std::string("tet") + ext);
    fabmesh::write_mesh(path, tetrahedron());
    const fabmesh::Mesh back = fabmesh::read_mesh(path);
    CAPTURE(ext);
    CHECK(fabmesh::validate(back).valid);
    CHECK(fabmesh::check_file(path).valid);
  }
  CHECK_THROWS_AS(fabmesh::write_mesh(dir / "tet.xyz", tetrahedron()), fabmesh::InputError);
  const fabmesh::ValidationReport unreadable = fabmesh::check_file(dir / "tet.xyz");
  CHECK_FALSE(unreadable.valid);
  CHECK_FALSE(unreadable.error.empty());
}

TEST_CASE("curves evaluate exactly and sample within the proven bound", "[api]") {
  const std::vector<fabmesh::Point2> p = {{0, 0}, {1, 2}, {3, 2}, {4, 0}, {5, -2}, {7, -2}, {8, 0}};
  const fabmesh::Curve c = fabmesh::tbezier(p, 0.5, -0.5);
  REQUIRE(c.segments() == 2);
  CHECK(c.point(0)[0] == Approx(0).margin(1e-12));
  CHECK(c.point(2)[0] == Approx(8));
  CHECK(c.point(1)[0] == Approx(4));
  // The first derivative against central differences.
  const double t = 0.37, h = 1e-5;
  const auto d = c.derivative(t);
  CHECK(d[0] == Approx((c.point(t + h)[0] - c.point(t - h)[0]) / (2 * h)).epsilon(1e-6));
  CHECK(d[1] == Approx((c.point(t + h)[1] - c.point(t - h)[1]) / (2 * h)).epsilon(1e-6));
  const fabmesh::SampledCurve s = c.sample(1e-3);
  CHECK(s.max_deviation <= 1e-3);
  CHECK(s.points.size() > 10);
  CHECK_THROWS_AS(c.point(2.5), fabmesh::InputError);
  CHECK_THROWS_AS(c.derivative(0.5, 4), fabmesh::InputError);
  CHECK_THROWS_AS(fabmesh::tbezier(p, 1.7), fabmesh::InputError);
  CHECK_THROWS_AS(fabmesh::tbezier({{0, 0}, {1, 1}}), fabmesh::InputError);

  const fabmesh::Curve b = fabmesh::quasi_bspline({{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}}, {0, 0, 0});
  CHECK(b.sample(1e-4).max_deviation <= 1e-4);
  const fabmesh::Curve hb = fabmesh::hbezier({{0, 0}, {1, 2}, {3, 2}, {4, 0}}, 2.0);
  CHECK(std::isfinite(hb.curvature(0.5)));
  CHECK_FALSE(b.through());
}

TEST_CASE("library: a quasi-B-spline through points meets them, and gives its control points", "[library]") {
  // The golden profile's own joints give back its control points.
  const fabmesh::Curve golden =
      fabmesh::quasi_bspline({{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}}, {0, 0.5, 0});
  std::vector<fabmesh::Point2> joints;
  for (std::size_t i = 0; i <= golden.segments(); ++i) joints.push_back(golden.point(static_cast<double>(i)));
  const fabmesh::Curve c = fabmesh::quasi_bspline_through(joints, {0, 0.5, 0});
  REQUIRE(c.through());
  const fabmesh::Through t = *c.through();
  CHECK(t.points == joints);
  const std::vector<fabmesh::Point2> control{{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}};
  REQUIRE(t.control_points.size() == control.size());
  for (std::size_t i = 0; i < control.size(); ++i) {
    CHECK(std::abs(t.control_points[i][0] - control[i][0]) < 1e-12);
    CHECK(std::abs(t.control_points[i][1] - control[i][1]) < 1e-12);
  }
  CHECK(t.deviation >= 0.0);
  CHECK(t.deviation < 1e-13);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const fabmesh::Point2 p = c.point(static_cast<double>(i));
    CHECK(std::hypot(p[0] - joints[i][0], p[1] - joints[i][1]) <= t.deviation + 1e-14);
  }
  // Bad input names the argument: too few points, a singular system (n = 2, lambda_1 = -8), a count.
  const auto key_of = [](const auto& call) {
    try {
      call();
    } catch (const fabmesh::InputError& e) {
      return e.key();
    }
    return std::string("no error");
  };
  CHECK(key_of([] { fabmesh::quasi_bspline_through({{0, 0}, {1, 1}}); }) == "through");
  CHECK(key_of([] { fabmesh::quasi_bspline_through({{0, 0}, {1, 1}, {2, 0}}, {-8}); }) == "through");
  CHECK(key_of([] { fabmesh::quasi_bspline_through({{0, 0}, {1, 1}, {2, 0}}, {0, 0}); }) == "lambdas");
  CHECK(key_of([] { fabmesh::quasi_bspline_through({{0, 0}, {1, 1}, {2, 0}}, {3}); }) == "lambdas");
  CHECK(key_of([] { fabmesh::quasi_bspline_through({{0, 0}, {NAN, 1}, {2, 0}}); }) == "through");
  // Fairing would move it off its points.
  CHECK(key_of([&] { fabmesh::fair(c, fabmesh::Energy::Strain); }) == "curve");
}

// The one curve of a curve design given as text.
fabmesh::Curve design_curve(const std::string& yaml) {
  const fabmesh::Result r = fabmesh::build(fabmesh::parse_design(yaml));
  REQUIRE(r.curves.size() == 1);
  return r.curves[0].curve;
}

// The two curves agree at every parameter tried (the same construction gives the same numbers).
void require_same_curve(const fabmesh::Curve& a, const fabmesh::Curve& b) {
  REQUIRE(a.segments() == b.segments());
  const double n = static_cast<double>(a.segments());
  for (int i = 0; i <= 97; ++i) {
    const double t = n * i / 97.0;
    const fabmesh::Point2 p = a.point(t), q = b.point(t);
    CHECK(p[0] == Approx(q[0]).margin(1e-12));
    CHECK(p[1] == Approx(q[1]).margin(1e-12));
  }
}

TEST_CASE("a composite mixes families with joins as a design file does", "[api]") {
  // T-Bezier, then an H-Bezier segment joined G2 (k, m), then a line.
  std::vector<fabmesh::Segment> segments(3);
  segments[0].family = fabmesh::SegmentFamily::TBezier;
  segments[0].points = {{0, 0}, {1, 2}, {3, 3}, {4, 1}};
  segments[0].lambda = 0.5;
  segments[1].family = fabmesh::SegmentFamily::HBezier;
  segments[1].points = {{8, 0}};
  segments[1].alpha = 2;
  segments[1].mu = -1;
  segments[1].join = fabmesh::Join{fabmesh::Continuity::G2, 1, 0, 1.5, 0.25};
  segments[2].family = fabmesh::SegmentFamily::Line;
  segments[2].points = {{10, -3}};
  const fabmesh::Curve c = fabmesh::composite(segments);
  REQUIRE(c.segments() == 3);
  require_same_curve(c, design_curve(R"(
name: mixed
kind: curve
tolerance: 0.01
curve:
  family: tbezier
  segments:
    - points: [[0, 0], [1, 2], [3, 3], [4, 1]]
      lambda: 0.5
    - family: hbezier
      join: {continuity: G2, k: 1.5, m: 0.25}
      points: [[8, 0]]
      alpha: 2
      mu: -1
    - line: {to: [10, -3]}
)"));
  const std::vector<fabmesh::Joint> joints = c.joints();
  REQUIRE(joints.size() == 2);
  CHECK(joints[0].declared == fabmesh::Continuity::G2);
  CHECK(joints[0].achieved == fabmesh::Continuity::G2);
  CHECK(joints[0].curvature_before == Approx(joints[0].curvature_after).epsilon(1e-9));
  CHECK(c.curvature(1.0) == Approx(joints[0].curvature_after).epsilon(1e-12));
  CHECK(joints[1].declared == fabmesh::Continuity::G0);
  CHECK(joints[1].gap <= 1e-12);
  CHECK(c.curvature(2.5) == 0.0);  // the line
  CHECK_FALSE(c.fairing().has_value());

  // A closed composite: the first segment joins the last, its points solved for.
  std::vector<fabmesh::Segment> loop(2);
  loop[0].points = {{0, 0}, {1, 0}};
  loop[0].join = fabmesh::Join{fabmesh::Continuity::G1, 1, 0, 1, 0};
  loop[1].points = {{0, 0}, {2, 3}, {3, 1}};
  loop[1].join = fabmesh::Join{fabmesh::Continuity::G0, 1, 0, 1, 0};
  const fabmesh::Curve closed = fabmesh::composite(loop, true);
  CHECK(closed.closed());
  const std::vector<fabmesh::Joint> closing = closed.joints();
  REQUIRE(closing.size() == 2);
  CHECK(closing[1].closing);
  CHECK(closing[1].achieved >= fabmesh::Continuity::G1);
}

TEST_CASE("a composite's bad segments are errors at their keys", "[api]") {
  auto key_of = [](const std::vector<fabmesh::Segment>& segments, bool closed = false) {
    try {
      fabmesh::composite(segments, closed);
    } catch (const fabmesh::InputError& e) {
      return e.location().key;
    }
    return std::string("(no error)");
  };
  std::vector<fabmesh::Segment> s(2);
  s[0].points = {{0, 0}, {1, 2}, {3, 3}, {4, 1}};
  s[1].points = {{5, 0}, {6, 1}};  // two points need a G1 join
  CHECK(key_of(s) == "segments[1]");
  s[1].join = fabmesh::Join{};
  CHECK(key_of(s) == "(no error)");
  s[1].lambda = 1.5;  // outside [-2, 1]
  CHECK(key_of(s).rfind("segments[1]", 0) == 0);
  s[1].lambda = 0;
  s[1].family = fabmesh::SegmentFamily::Line;
  CHECK(key_of(s) == "segments[1].join");
  // An explicit segment that declares G1 where the tangents disagree.
  s[1] = fabmesh::Segment{};
  s[1].points = {{4, 1}, {4, 3}, {6, 3}, {7, 0}};
  s[1].continuity = fabmesh::Continuity::G1;
  CHECK(key_of(s) == "segments");
  CHECK(key_of({}) == "segments");
  CHECK(key_of(s, true) == "segments");  // does not end where it starts
}

TEST_CASE("fair lowers the energy, keeps the control points and matches the design's fair", "[api]") {
  const std::vector<fabmesh::Point2> p = {{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}};
  const fabmesh::Curve b = fabmesh::quasi_bspline(p, {0.5, 0.5, 0.5});
  for (const fabmesh::Energy energy : {fabmesh::Energy::Strain, fabmesh::Energy::CurvatureVariation}) {
    const fabmesh::Curve f = fabmesh::fair(b, energy);
    REQUIRE(f.fairing().has_value());
    CHECK(f.fairing()->energy == energy);
    CHECK(f.fairing()->energy_after < f.fairing()->energy_before);
    CHECK(f.point(0)[0] == Approx(b.point(0)[0]).margin(1e-12));
    CHECK(f.point(4)[1] == Approx(b.point(4)[1]).margin(1e-12));
    // Fairing the faired curve again finds nothing better.
    const fabmesh::Curve again = fabmesh::fair(f, energy);
    CHECK(again.fairing()->energy_after == Approx(f.fairing()->energy_after).epsilon(1e-9));
    CHECK(again.fairing()->energy_before == Approx(f.fairing()->energy_after).epsilon(1e-9));
  }
  require_same_curve(fabmesh::fair(b, fabmesh::Energy::Strain), design_curve(R"(
name: faired
kind: curve
tolerance: 0.005
curve:
  family: quasi_bspline
  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]
  lambdas: [0.5, 0.5, 0.5]
  fair: strain
)"));

  // A T-Bezier composite: G1 joins survive; its points stay.
  std::vector<fabmesh::Segment> s(2);
  s[0].points = {{1, 0.2}, {0.2, 0.4}, {1.6, 1.4}, {1, 0.2}};
  s[0].lambda = 1;
  s[0].mu = 1;
  s[1].points = {{3, 1}, {4, 0}};
  s[1].lambda = -1;
  s[1].join = fabmesh::Join{fabmesh::Continuity::G1, 2, 0, 1, 0};
  const fabmesh::Curve c = fabmesh::composite(s);
  const fabmesh::Curve f = fabmesh::fair(c);
  CHECK(f.fairing()->energy_after < f.fairing()->energy_before);
  CHECK(f.joints()[0].achieved >= fabmesh::Continuity::G1);
  CHECK(f.point(1)[0] == Approx(c.point(1)[0]).margin(1e-12));
  CHECK(fabmesh::fair(f).fairing()->energy_after == Approx(f.fairing()->energy_after).epsilon(1e-9));

  auto key_of = [](auto&& call) {
    try {
      call();
    } catch (const fabmesh::InputError& e) {
      return e.location().key;
    }
    return std::string("(no error)");
  };
  CHECK(key_of([&] { fabmesh::fair(c, fabmesh::Energy::Strain); }) == "energy");
  const fabmesh::Curve h = fabmesh::hbezier({{0, 0}, {1, 2}, {3, 2}, {4, 0}});
  CHECK(key_of([&] { fabmesh::fair(h); }) == "energy");

  // A G2 join that fairing lowers to G1 is refused unless the caller accepts G1.
  s[1].points = {{4, 0}};
  s[1].join = fabmesh::Join{fabmesh::Continuity::G2, 1, 0, 1, 0};
  const fabmesh::Curve g2 = fabmesh::composite(s);
  REQUIRE(g2.joints()[0].achieved == fabmesh::Continuity::G2);
  CHECK(key_of([&] { fabmesh::fair(g2); }) == "keeps");
  const fabmesh::Curve kept = fabmesh::fair(g2, fabmesh::Energy::CurvatureVariation, fabmesh::Continuity::G1);
  CHECK(kept.joints()[0].achieved == fabmesh::Continuity::G1);
  CHECK(kept.joints()[0].declared == fabmesh::Continuity::G2);
}

TEST_CASE("optimize gives the command line's document", "[api]") {
  const std::string json = fabmesh::optimize(fabmesh::read_design(example("example4_profile.yaml")));
  CHECK(json.rfind("[{\"design\":", 0) == 0);
  CHECK(json.find("\"curve\":") != std::string::npos);
}

TEST_CASE("distinct builds run in parallel threads with the serial results", "[api]") {
  const fabmesh::Design a = fabmesh::read_design(example("vessel_golden_solid.yaml"));
  const fabmesh::Design b = fabmesh::read_design(example("countertop_g1.yaml"));
  const fabmesh::Result serial_a = fabmesh::build(a);
  const fabmesh::Result serial_b = fabmesh::build(b);
  auto fa = std::async(std::launch::async, [&] { return fabmesh::build(a); });
  auto fb = std::async(std::launch::async, [&] { return fabmesh::build(b); });
  const fabmesh::Result pa = fa.get();
  const fabmesh::Result pb = fb.get();
  CHECK(pa.vertices == serial_a.vertices);
  CHECK(pa.triangles == serial_a.triangles);
  CHECK(pb.vertices == serial_b.vertices);
  CHECK(pb.triangles == serial_b.triangles);
}
