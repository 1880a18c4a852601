#include "pipeline/batch/batch_row.h"

#include <catch2/catch.hpp>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/errors.h"

using namespace fabmesh;
using Json = nlohmann::ordered_json;

namespace {

// A row of a written variant, every field set.
BatchRow written_row() {
  BatchRow r;
  r.index = 7;
  r.name = "cup_w0.2";
  r.design = "cup.yaml";
  r.overrides = {{"body.wall", "0.2"}};
  r.key = std::string(64, 'a');
  r.status = VariantStatus::Ok;
  r.message = "";
  MeshFacts m;
  m.kind = "vessel";
  m.units = "cm";
  m.vertices = 2928;
  m.triangles = 5852;
  m.volume = 13.74;
  m.area = 123.4;
  m.valid = true;
  m.bbox_min = Vec3(-2.5, -2.5, 2.0);
  m.bbox_max = Vec3(2.5, 2.5, 6.0);
  m.max_deviation = 0.017;
  m.tolerance = 0.02;
  r.mesh = m;
  r.files = {{"cup_w0.2/cup_w0.2.stl", "stl", "mm", 292684, std::string(64, 'b')}};
  r.skipped = {{"drc", "the quantization cannot hold the tolerance"}};
  r.timings_ms = {{"resolve", 0.4}, {"job", 93.5}};
  return r;
}

}  // namespace

TEST_CASE("batch: row_from_json reads back what row_json writes", "[pipeline][batch]") {
  const Json j = row_json(written_row());
  CHECK(row_json(row_from_json(j)) == j);
  BatchRow failed = written_row();
  failed.status = VariantStatus::BadInput;
  failed.exit_code = 2;
  failed.mesh.reset();
  failed.files.clear();
  CHECK(row_json(row_from_json(row_json(failed))) == row_json(failed));
}

TEST_CASE("batch: a row's count beyond its type's range is bad input, not undefined behaviour",
          "[pipeline][batch]") {
  // Found by fuzz_ledger: get<int> of 1e300 (a ledger row's exit code) was a
  // float-to-int conversion out of range, which UBSan reports.
  const std::pair<const char*, Json> damaged[] = {
      {"index", 1e300},
      {"index", -1},
      {"index", 1.5},
      {"index", "7"},
      {"exit_code", 1e300},
      {"exit_code", 2147483648LL},
      {"exit_code", -2147483649LL},
      {"exit_code", 2.0},
      {"vertices", -1},
      {"triangles", 1e20},
  };
  for (const auto& [key, value] : damaged) {
    Json j = row_json(written_row());
    j[key] = value;
    INFO(j.dump());
    CHECK_THROWS_AS(row_from_json(j), InputError);
  }
  Json bytes = row_json(written_row());
  bytes["files"][0]["bytes"] = -1.0e30;
  CHECK_THROWS_AS(row_from_json(bytes), InputError);
  // The ends of each range are read as they are.
  Json ends = row_json(written_row());
  ends["exit_code"] = -2147483648LL;
  ends["vertices"] = 18446744073709551615ULL;
  const BatchRow r = row_from_json(ends);
  CHECK(r.exit_code == -2147483648LL);
  CHECK(r.mesh->vertices == 18446744073709551615ULL);
}

TEST_CASE("batch: a row's facts are its status, message, mesh, files and timings", "[pipeline][batch]") {
  const BatchRow written = written_row();
  const ItemFacts item = row_facts(written);
  CHECK(item.name == "cup_w0.2");
  CHECK(item.status == ItemStatus::Ok);
  CHECK(item.message == "valid for fabrication");  // an ok row says nothing of its own
  REQUIRE(item.mesh);
  CHECK(item.mesh->triangles == 5852);
  CHECK(item.mesh->bbox_max == Vec3(2.5, 2.5, 6.0));
  CHECK(item.files == std::vector<std::string>{"cup_w0.2/cup_w0.2.stl"});
  CHECK(item.timings_ms == written.timings_ms);

  BatchRow skipped = written_row();
  skipped.message = "skipped drc: the quantization cannot hold the tolerance";
  CHECK(row_facts(skipped).message == skipped.message);

  BatchRow missing = written_row();
  missing.status = VariantStatus::Missing;
  missing.mesh.reset();
  CHECK(row_facts(missing).message == "not run yet");
  CHECK_FALSE(row_facts(missing).mesh);
}

TEST_CASE("batch: a row read back keeps its mesh facts", "[pipeline][batch]") {
  const BatchRow r = row_from_json(row_json(written_row()));
  REQUIRE(r.mesh);
  CHECK(r.mesh->measured);  // not kept in a row: read back as measured
  CHECK(r.mesh->bbox_min == Vec3(-2.5, -2.5, 2.0));
  CHECK(r.mesh->bbox_max == Vec3(2.5, 2.5, 6.0));
  CHECK(r.mesh->tolerance == 0.02);
}

TEST_CASE("batch: a written open surface and a curve say what run --report says", "[pipeline][batch]") {
  BatchRow surface = written_row();
  surface.mesh->kind = "surface";
  surface.mesh->valid = false;  // written with `purpose: view`
  const ItemFacts viewing = row_facts(surface);
  CHECK(viewing.status == ItemStatus::Invalid);
  CHECK(viewing.message == "written for viewing only: not valid for fabrication");

  BatchRow curve = written_row();
  curve.mesh->kind = "curve";
  curve.mesh->valid = false;
  const ItemFacts drawing = row_facts(row_from_json(row_json(curve)));
  REQUIRE(drawing.mesh);
  CHECK_FALSE(drawing.mesh->measured);
  CHECK(drawing.status == ItemStatus::Ok);
  CHECK(drawing.message == "drawing written");
}
