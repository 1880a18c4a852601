#include <catch2/catch.hpp>
#include <cstring>
#include <functional>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/file.h"
#include "io/mesh/draco.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/read_mesh.h"
#include "io/mesh/stl.h"
#include "io/mesh/threemf.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/io/mesh/external_tool.h"
#include "tests/io/mesh/temp_dir.h"

using namespace fabmesh;
using test::TempDir;

namespace {

/// The soup with every coordinate rounded to float32, as STL stores it.
TriangleSoup as_float(TriangleSoup s) {
  for (Vec3& p : s.vertices) {
    for (int a = 0; a < 3; ++a) {
      // volatile: GCC 12's -O2 vectorizer drops a double -> float -> double round trip.
      const volatile float rounded = static_cast<float>(p[a]);
      p[a] = rounded;
    }
  }
  return s;
}

/// Largest distance from a vertex of `a` to the nearest vertex of `b` (brute force).
double max_nearest_distance(const TriangleSoup& a, const TriangleSoup& b) {
  double worst = 0.0;
  for (const Vec3& p : a.vertices) {
    double best = INFINITY;
    for (const Vec3& q : b.vertices) best = std::min(best, (p - q).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

void require_valid_torus(const TriangleSoup& read, std::size_t triangles) {
  const WeldResult w = weld(read);
  const ValidationReport r = validate(w.soup);
  CHECK(r.valid());
  CHECK(r.genus == 1);
  CHECK(r.triangles == triangles);
}

}  // namespace

TEST_CASE("mesh files: OBJ, double PLY and OFF round-trip vertices and faces exactly", "[mesh][io]") {
  const TempDir dir;
  const TriangleSoup torus = test::rotated(test::torus(3.0, 1.0, 24, 12), Vec3(1, 1, 0), 0.3);
  using Writer = std::function<void(const TriangleSoup&, const std::string&)>;
  const std::vector<std::pair<std::string, Writer>> writers = {
      {"t.obj", [](const TriangleSoup& s, const std::string& p) { write_obj(s, p); }},
      {"t.ply",
       [](const TriangleSoup& s, const std::string& p) {
         write_ply(s, p, PlyOptions{true, {}});
       }},
      {"t.off", [](const TriangleSoup& s, const std::string& p) { write_off(s, p); }}};
  for (const auto& [name, write] : writers) {
    INFO(name);
    write(torus, dir.file(name));
    const TriangleSoup back = read_mesh(dir.file(name));
    CHECK(back.vertices == torus.vertices);
    CHECK(back.triangles == torus.triangles);
    require_valid_torus(back, torus.triangles.size());
  }
}

TEST_CASE("mesh files: PLY is float32 by default, round-trips float32 exactly and draco_encoder takes it",
          "[mesh][io][ply]") {
  const TempDir dir;
  const TriangleSoup torus = test::rotated(test::torus(3.0, 1.0, 24, 12), Vec3(1, 1, 0), 0.3);
  const std::string bytes = encode_ply(torus);
  CHECK(bytes.find("property float x") != std::string::npos);
  const TriangleSoup back = parse_ply(bytes, "t.ply");
  CHECK(back.vertices == as_float(torus).vertices);
  CHECK(back.triangles == torus.triangles);
  require_valid_torus(back, torus.triangles.size());
  CHECK(encode_ply(torus, PlyOptions{true, {}}).find("property double x") != std::string::npos);

  // draco_encoder refuses double coordinates ("x, y, and z properties must be
  // of type float32 or int32") and takes fabmesh's default PLY.
  REQUIRE_PROGRAM("draco_encoder");
  write_ply(torus, dir.file("float.ply"));
  write_ply(torus, dir.file("double.ply"), PlyOptions{true, {}});
  const auto encode = [&](const std::string& ply) {
    return test::run_tool("draco_encoder -qp 20 -i " + test::quoted(dir.file(ply)) + " -o " +
                          test::quoted(dir.file(ply + ".drc")));
  };
  const test::ToolRun ok = encode("float.ply");
  INFO(ok.output);
  REQUIRE(ok.code == 0);
  const TriangleSoup decoded = read_mesh(dir.file("float.ply.drc"));
  CHECK(decoded.triangles.size() == torus.triangles.size());
  CHECK(max_nearest_distance(decoded, torus) <= 1e-4);
  CHECK(encode("double.ply").code != 0);
  TriangleSoup overflow = test::box();
  overflow.vertices[0].x() = 1e300;
  CHECK_THROWS_AS(encode_ply(overflow), InputError);
  CHECK(encode_ply(overflow, PlyOptions{true, {}}).size() > 0);
}

TEST_CASE("mesh files: binary STL round-trips float32 coordinates and welds back to the mesh", "[mesh][io]") {
  const TempDir dir;
  const TriangleSoup torus = test::torus(3.0, 1.0, 24, 12);
  write_stl(torus, dir.file("t.stl"));
  CHECK(std::filesystem::file_size(dir.file("t.stl")) == 84 + 50 * torus.triangles.size());
  const TriangleSoup back = read_mesh(dir.file("t.stl"));
  CHECK(back.vertices.size() == 3 * torus.triangles.size());
  const WeldResult w = weld(back);
  // Welding numbers vertices by first use in the file: compare corner by corner.
  const TriangleSoup expected = as_float(torus);
  CHECK(w.soup.vertices.size() == expected.vertices.size());
  REQUIRE(w.soup.triangles.size() == expected.triangles.size());
  for (std::size_t f = 0; f < expected.triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      REQUIRE(w.soup.vertices[w.soup.triangles[f][k]] == expected.vertices[expected.triangles[f][k]]);
    }
  }
  require_valid_torus(back, torus.triangles.size());
}

TEST_CASE("mesh files: Draco keeps every vertex within the tolerance and the mesh valid",
          "[mesh][io][draco]") {
  const TempDir dir;
  const TriangleSoup torus = test::torus(30.0, 10.0, 48, 24);
  for (double tolerance : {0.5, 0.01, 1e-4}) {
    INFO("tolerance " << tolerance);
    DracoOptions options;
    options.tolerance = tolerance;
    write_draco(torus, dir.file("t.drc"), options);
    const TriangleSoup back = read_mesh(dir.file("t.drc"));
    CHECK(back.triangles.size() == torus.triangles.size());
    CHECK(max_nearest_distance(back, torus) <= tolerance);
    CHECK(max_nearest_distance(torus, back) <= tolerance);
    require_valid_torus(back, torus.triangles.size());
  }
}

TEST_CASE("draco_quantization: the fewest bits whose error bound meets the tolerance", "[mesh][io][draco]") {
  const Vec3 lo(-5, 0, 2);
  const Vec3 hi(5, 4, 3);
  for (double tolerance : {1.0, 0.1, 1e-3, 1e-4}) {
    const DracoQuantization q = draco_quantization(lo, hi, tolerance);
    CHECK(q.bits >= 1);
    CHECK(q.bits <= 30);
    CHECK(q.max_error <= tolerance);
    CHECK(q.max_error == draco_max_error(lo, hi, q.bits));
    if (q.bits > 1) CHECK(draco_max_error(lo, hi, q.bits - 1) > tolerance);
    CHECK(q.max_error >= 10.0 / std::ldexp(1.0, q.bits + 1));  // at least half a grid step
  }
  CHECK_THROWS_AS(draco_quantization(lo, hi, 0.0), RangeError);
  CHECK_THROWS_AS(draco_quantization(lo, hi, 1e-9), RangeError);  // beyond float32
}

TEST_CASE("mesh files: ASCII STL, with polygons and any whitespace, is read", "[mesh][io][stl]") {
  const std::string text =
      "solid cube part\r\n"
      "  facet normal 0 0 -1\r\n    outer loop\r\n      vertex 0 0 0\r\n      vertex 0 1 0\r\n"
      "      vertex 1 0 0\r\n    endloop\r\n  endfacet\r\n"
      "facet normal 0 0 1\n outer loop\n vertex 0 0 1\n vertex 1 0 1\n vertex 1 1 1\n vertex 0 1 1\n"
      " endloop\n endfacet\nendsolid cube part\n";
  const TriangleSoup s = parse_stl(text, "cube.stl");
  CHECK(s.triangles.size() == 3);
  CHECK(s.vertices.size() == 7);
  CHECK(s.vertices[1] == Vec3(0, 1, 0));
  CHECK(detect_format(text, "x.dat") == MeshFormat::Stl);
}

TEST_CASE("mesh files: a binary STL whose header starts with 'solid' is binary", "[mesh][io][stl]") {
  std::string bytes = encode_stl(test::box());
  std::memcpy(bytes.data(), "solid but binary", 16);
  const TriangleSoup s = parse_stl(bytes, "b.stl");
  CHECK(s.triangles.size() == 12);
  CHECK(weld(s).soup.vertices.size() == 8);
}

TEST_CASE("mesh files: a truncated or lying binary STL is a FileError", "[mesh][io][stl]") {
  const std::string good = encode_stl(test::box());
  CHECK_THROWS_AS(parse_stl(good.substr(0, good.size() - 1), "t.stl"), FileError);
  CHECK_THROWS_AS(parse_stl(good.substr(0, 50), "t.stl"), FileError);
  CHECK_THROWS_AS(parse_stl(good + "xx", "t.stl"), FileError);
  std::string lying = good;
  lying[80] = static_cast<char>(0xff);  // claims 255 triangles
  lying[83] = static_cast<char>(0x7f);  // ... and far more
  try {
    parse_mesh(lying, "lying.stl");
    FAIL("no exception");
  } catch (const FileError& e) {
    CHECK(e.path() == "lying.stl");
    CHECK(std::string(e.what()).find("bytes") != std::string::npos);
  }
  std::string nan_stl = good;
  const float nan = std::nanf("");
  std::memcpy(nan_stl.data() + 84 + 12, &nan, 4);
  CHECK_THROWS_AS(parse_stl(nan_stl, "nan.stl"), FileError);
}

TEST_CASE("mesh files: a malformed ASCII STL names the line", "[mesh][io][stl]") {
  const std::string text = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 zero 0\n";
  try {
    parse_stl(text, "bad.stl");
    FAIL("no exception");
  } catch (const FileError& e) {
    CHECK(e.line() == 5);
  }
  CHECK_THROWS_AS(parse_stl("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "t.stl"), FileError);
  CHECK_THROWS_AS(
      parse_stl("solid x\nfacet\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n", "t"),
      FileError);
}

TEST_CASE("mesh files: OBJ corners v, v/vt, v//vn, v/vt/vn and negative indices, and polygons fanned",
          "[mesh][io][obj]") {
  const std::string text =
      "# a quad and a triangle\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
      "g top\nusemtl m\nf 1/1/1 2/1/1 3//1 4/1\nv 0 0 1\nf -5 -4 -1\n";
  const TriangleSoup s = parse_obj(text, "q.obj");
  CHECK(s.vertices.size() == 5);
  REQUIRE(s.triangles.size() == 3);
  CHECK(s.triangles[0] == std::array<std::uint32_t, 3>{0, 1, 2});
  CHECK(s.triangles[1] == std::array<std::uint32_t, 3>{0, 2, 3});
  CHECK(s.triangles[2] == std::array<std::uint32_t, 3>{0, 1, 4});
  CHECK(detect_format(text, "q.txt") == MeshFormat::Obj);
}

TEST_CASE("mesh files: OBJ indices that refer to no vertex are FileErrors naming the line",
          "[mesh][io][obj]") {
  for (const std::string& bad : {std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
                                 std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"),
                                 std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n"),
                                 std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n"),
                                 std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n")}) {
    INFO(bad);
    try {
      parse_obj(bad, "bad.obj");
      FAIL("no exception");
    } catch (const FileError& e) {
      CHECK(e.line() == 4);
    }
  }
  CHECK(parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "fwd.obj").triangles.size() == 1);  // forward use
  CHECK_THROWS_AS(parse_obj("v 0 0 nan\n", "nan.obj"), FileError);
}

TEST_CASE("mesh files: ASCII and big-endian PLY with extra properties and elements", "[mesh][io][ply]") {
  const std::string ascii =
      "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\n"
      "property int flags\nelement edge 1\nproperty int v1\nproperty int v2\nend_header\n"
      "0 0 0 255\n1 0 0 255\n1 1 0 255\n0 1 0 255\n4 0 1 2 3 7\n0 1\n";
  const TriangleSoup a = parse_ply(ascii, "a.ply");
  CHECK(a.vertices.size() == 4);
  CHECK(a.vertices[2] == Vec3(1, 1, 0));
  CHECK(a.triangles.size() == 2);

  std::string be =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  auto put_be = [&](std::uint64_t v, int n) {
    for (int i = n - 1; i >= 0; --i) be.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  };
  for (double d : {0.0, 0.0, 0.0, 1.5, 0.0, 0.0, 0.0, 2.5, 0.0}) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, 8);
    put_be(bits, 8);
  }
  put_be(3, 1);
  for (std::uint32_t i : {0u, 1u, 2u}) put_be(i, 4);
  const TriangleSoup b = parse_ply(be, "b.ply");
  CHECK(b.vertices[1] == Vec3(1.5, 0, 0));
  CHECK(b.vertices[2] == Vec3(0, 2.5, 0));
  CHECK(b.triangles.size() == 1);
}

TEST_CASE("mesh files: malformed PLY is a FileError, huge counts fail fast", "[mesh][io][ply]") {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body(36, '\0');
  body += std::string("\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00", 13);
  CHECK(parse_ply(header + body, "ok.ply").triangles.size() == 1);
  CHECK_THROWS_AS(parse_ply(header + body.substr(0, body.size() - 2), "trunc.ply"), FileError);
  std::string bad_index = header + body;
  bad_index[bad_index.size() - 4] = 3;  // vertex 3 of 3
  CHECK_THROWS_AS(parse_ply(bad_index, "idx.ply"), FileError);
  std::string huge = header + body;
  huge.replace(huge.find("vertex 3"), 8, "vertex 4000000000");
  CHECK_THROWS_AS(parse_ply(huge, "huge.ply"), FileError);
  CHECK_THROWS_AS(parse_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "noend.ply"),
                  FileError);
  CHECK_THROWS_AS(
      parse_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n", "xy.ply"),
      FileError);
}

TEST_CASE("mesh files: OFF with comments and polygons, and lying counts are FileErrors", "[mesh][io][off]") {
  const std::string text =
      "# comment\nOFF\n# counts\n4 1 0\n0 0 0\n1 0 0\n1 1 0 # tail\n0 1 0\n4 0 1 2 3 255 0 0\n";
  const TriangleSoup s = parse_off(text, "q.off");
  CHECK(s.vertices.size() == 4);
  CHECK(s.triangles.size() == 2);
  CHECK(detect_format(text, "q.bin") == MeshFormat::Off);
  CHECK_THROWS_AS(parse_off("OFF\n4 1 0\n0 0 0\n1 0 0\n", "short.off"), FileError);
  CHECK_THROWS_AS(parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "idx.off"), FileError);
  CHECK_THROWS_AS(parse_off("OFF\n1000000000000 1 0\n0 0 0\n", "huge.off"), FileError);
  CHECK_THROWS_AS(parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "few.off"), FileError);
}

TEST_CASE("mesh files: garbage, empty and corrupt Draco files are FileErrors", "[mesh][io]") {
  CHECK_THROWS_AS(parse_mesh("", "empty.stl"), FileError);
  CHECK_THROWS_AS(parse_mesh("", "empty.xyz"), FileError);
  CHECK_THROWS_AS(parse_mesh("\x01\x02garbage", "g.bin"), FileError);
  const std::string drc = encode_draco(test::box());
  CHECK(detect_format(drc, "x") == MeshFormat::Draco);
  CHECK_THROWS_AS(parse_mesh(drc.substr(0, drc.size() / 2), "half.drc"), FileError);
  CHECK_THROWS_AS(parse_mesh("DRACO", "magic.drc"), FileError);
  CHECK_THROWS_AS(read_mesh("/nonexistent/fabmesh/none.stl"), FileError);
  const TempDir dir;
  CHECK_THROWS_AS(read_mesh(dir.file("")), FileError);  // a folder
}

TEST_CASE("mesh files: a Draco header declaring more triangles than allowed is refused before decoding",
          "[mesh][io][draco]") {
  // The count is read from the header itself: a 12-triangle box over a budget of 11.
  const std::string drc = encode_draco(test::box());
  CHECK(parse_draco(drc, "box.drc", 12).triangles.size() == 12);
  CHECK_THROWS_WITH(parse_draco(drc, "box.drc", 11),
                    Catch::Contains("declares 12 triangles, more than the 11"));
  // A fuzzer's 63-byte file whose header declares 268435447 faces: libdraco
  // reserved 3 GB for it. Refused from the header, with the count.
  const std::string path =
      std::string(FABMESH_SOURCE_DIR) + "/tests/data/fuzz-seeds/draco/regression-declares-268m-faces.drc";
  CHECK_THROWS_WITH(read_mesh(path), Catch::Contains("declares 268435447 triangles"));
}

TEST_CASE("file: writes replace the target and leave no temporary behind", "[mesh][io]") {
  const TempDir dir;
  const std::string path = dir.file("out.stl");
  write_file_atomically(path, "first");
  write_file_atomically(path, "second, longer");
  CHECK(read_file(path) == "second, longer");
  CHECK(dir.listing() == std::vector<std::string>{"out.stl"});
  CHECK_THROWS_AS(write_file_atomically(dir.file("missing/out.stl"), "x"), FileError);
  CHECK(dir.listing() == std::vector<std::string>{"out.stl"});
  CHECK_THROWS_AS(write_stl(test::box(), dir.file("missing/out.stl")), FileError);
}

TEST_CASE("mesh files: every fuzz seed parses, and fuzzer findings are clean FileErrors", "[mesh][io]") {
  const std::filesystem::path seeds = std::filesystem::path(FABMESH_SOURCE_DIR) / "tests/data/fuzz-seeds";
  int parsed = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(seeds)) {
    if (!entry.is_regular_file()) continue;
    // The design reader's seeds (design YAML, points CSV) are tested with it
    // (hostile_design_test.cpp); the batch readers' (manifest, ledger) with
    // theirs (manifest_test.cpp, ledger_test.cpp, batch_row_test.cpp); the
    // DXF loop reader's with it (dxf_loops_test.cpp).
    const std::string folder = entry.path().parent_path().filename().string();
    if (folder == "design" || folder == "csv" || folder == "manifest" || folder == "ledger" ||
        folder == "dxf")
      continue;
    const std::string path = entry.path().string();
    INFO(path);
    // A *.model seed is a 3MF model part: the 3MF fuzzer packages it (threemf_package).
    const bool model_part = entry.path().extension() == ".model";
    const auto parse = [&] {
      return model_part ? merged_soup(parse_3mf(threemf_package(read_file(path)), path)) : read_mesh(path);
    };
    if (entry.path().filename().string().rfind("regression-", 0) == 0) {
      CHECK_THROWS_AS(parse(), FileError);
    } else {
      CHECK_FALSE(parse().triangles.empty());
      ++parsed;
    }
  }
  CHECK(parsed >= 10);
}

TEST_CASE("stl: the binary STL handed over in pieces is byte for byte the one encoded whole",
          "[mesh][io][stl]") {
  const TriangleSoup torus = test::torus(3.0, 1.0, 24, 12);  // 576 triangles
  const std::string whole = encode_stl(torus);
  // Pieces smaller than a record, of one record, of an odd count, a divisor, larger than the file.
  for (const std::size_t piece :
       {std::size_t{1}, std::size_t{50}, std::size_t{350}, std::size_t{50 * 96}, std::size_t{1} << 20}) {
    std::string joined;
    std::size_t calls = 0;
    encode_stl_pieces(
        torus,
        [&](std::string_view bytes) {
          ++calls;
          CHECK(bytes.size() <= 84 + std::max<std::size_t>(piece, 50));
          joined.append(bytes);
        },
        piece);
    CHECK(joined == whole);
    CHECK(calls == (torus.triangles.size() + std::max<std::size_t>(1, piece / 50) - 1) /
                       std::max<std::size_t>(1, piece / 50));
  }
  std::string empty;
  encode_stl_pieces(TriangleSoup{}, [&](std::string_view bytes) { empty.append(bytes); });
  CHECK(empty == encode_stl(TriangleSoup{}));
  CHECK(empty.size() == 84);
  // A sink that fails stops the encoding with its error.
  CHECK_THROWS_AS(encode_stl_pieces(
                      torus, [](std::string_view) { throw FileError("t.stl", 0, 0, "disk full"); }, 100),
                  FileError);
  TriangleSoup bad = torus;
  bad.triangles[7][1] = 100000;
  CHECK_THROWS_AS(encode_stl_pieces(bad, [](std::string_view) { FAIL("no piece of a bad soup"); }),
                  InputError);
}
