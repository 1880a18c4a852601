// The one model of a report's item: the facts of a job, of a failure and of
// a mesh file checked, and what the JSON reports make of them.

#include "pipeline/report.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

using namespace fabmesh;

namespace {

// A validation with no defects and its self-intersection test run: valid.
ValidationReport valid_validation() {
  ValidationReport v;
  v.vertices = 8;
  v.triangles = 12;
  v.volume = 1.5;
  v.area = 7.25;
  v.self_intersection = IntersectionCheck::Tested;
  return v;
}

// A job of a closed mesh, valid for fabrication.
Result valid_job() {
  Result r;
  r.name = "cup";
  r.kind = "vessel";
  r.units = "cm";
  Part cup;
  cup.name = "cup";
  cup.validation = valid_validation();
  cup.validated = true;
  r.parts.push_back(cup);
  r.purpose = MeshPurpose::Fabrication;
  r.max_deviation = 0.017;
  r.tolerance = 0.02;
  r.bbox_min = Vec3(-2.5, -2.5, 0.0);
  r.bbox_max = Vec3(2.5, 2.5, 6.0);
  r.files = {{"out/cup.stl", "stl", "mm", 0.0, true, {}}, {"out/cup.drc", "drc", "mm", 0.0, true, {}}};
  r.timings_ms = {{"build", 12.0}, {"write", 1.0}};
  return r;
}

}  // namespace

TEST_CASE("report: a job's mesh facts are its validation's, box, deviation and tolerance",
          "[pipeline][report]") {
  const MeshFacts m = mesh_facts(valid_job());
  CHECK(m.kind == "vessel");
  CHECK(m.units == "cm");
  CHECK(m.measured);
  CHECK(m.vertices == 8);
  CHECK(m.triangles == 12);
  CHECK(m.volume == 1.5);
  CHECK(m.area == 7.25);
  CHECK(m.valid);
  CHECK(m.bbox_min == Vec3(-2.5, -2.5, 0.0));
  CHECK(m.bbox_max == Vec3(2.5, 2.5, 6.0));
  CHECK(m.max_deviation == 0.017);
  CHECK(m.tolerance == 0.02);
}

TEST_CASE("report: a valid job is ok, a surface for viewing invalid, a drawing ok and not measured",
          "[pipeline][report]") {
  const ItemFacts ok = item_facts(valid_job());
  CHECK(ok.name == "cup");
  CHECK(ok.status == ItemStatus::Ok);
  CHECK(ok.message == "valid for fabrication");
  CHECK(ok.files == std::vector<std::string>{"out/cup.stl", "out/cup.drc"});
  CHECK(ok.timings_ms == valid_job().timings_ms);

  Result viewing = valid_job();
  viewing.purpose = MeshPurpose::Viewing;
  viewing.parts[0].validation.defects.push_back({Defect::BoundaryEdge, 4, {}, {}});
  const ItemFacts view = item_facts(viewing);
  CHECK(view.status == ItemStatus::Invalid);
  CHECK(view.message == "written for viewing only: not valid for fabrication");
  CHECK_FALSE(view.mesh->valid);

  Result drawing = valid_job();
  drawing.purpose = MeshPurpose::Drawing;
  drawing.parts.clear();
  const ItemFacts drawn = item_facts(drawing);
  CHECK(drawn.status == ItemStatus::Ok);
  CHECK(drawn.message == "drawing written");
  CHECK_FALSE(drawn.mesh->measured);
}

TEST_CASE("report: a failed item has its exit code's status, its message and no facts",
          "[pipeline][report]") {
  const ItemFacts failed = failed_facts("cup", kExitBadInput, "cup.yaml:3:1: bad");
  CHECK(failed.name == "cup");
  CHECK(failed.status == ItemStatus::BadInput);
  CHECK(failed.message == "cup.yaml:3:1: bad");
  CHECK_FALSE(failed.mesh);
  CHECK(failed.files.empty());
  CHECK(failed_facts("cup", kExitEnvironment, "").status == ItemStatus::Environment);
}

TEST_CASE("report: a checked file is valid when every object is, with the facts of its one object",
          "[pipeline][report]") {
  const MeshFacts good = mesh_facts(valid_validation(), "mm");
  CHECK(good.units == "mm");
  CHECK(good.valid);
  CHECK(good.kind.empty());
  const ItemFacts one = check_facts("a.stl", {good});
  CHECK(one.name == "a.stl");
  CHECK(one.status == ItemStatus::Ok);
  CHECK(one.message == "valid");
  REQUIRE(one.mesh);
  CHECK(one.mesh->triangles == 12);

  MeshFacts bad = good;
  bad.valid = false;
  const ItemFacts several = check_facts("b.3mf", {good, bad});
  CHECK(several.status == ItemStatus::Invalid);
  CHECK(several.message == "INVALID");
  CHECK_FALSE(several.mesh);
}

TEST_CASE("report: run --json and summary rows write the box of the mesh facts", "[pipeline][report]") {
  const Result job = valid_job();
  const nlohmann::ordered_json box = bounding_box_json(mesh_facts(job));
  CHECK(box.dump() == R"({"min":[-2.5,-2.5,0.0],"max":[2.5,2.5,6.0],"size":[5.0,5.0,6.0],"units":"cm"})");
  const nlohmann::ordered_json j = to_json(job);
  CHECK(j.at("bounding_box") == box);
  CHECK(j.at("kind") == "vessel");
  CHECK(j.at("max_deviation") == 0.017);
  CHECK(j.at("tolerance") == 0.02);
  CHECK(j.at("volume") == 1.5);
}
