// Outputs are byte-for-byte deterministic: two separate runs of the real
// executable (different processes, so different addresses and uninitialised
// memory) write identical files, for every format of every bundled example.
// And every mesh file so written is judged valid by `fabmesh check` and, object
// by object, by CGAL Polygon Mesh Processing (closed, free of
// self-intersections, outward) where CGAL's notion is the same.

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/read_mesh.h"
#include "pipeline/output_table.h"
#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/limited_run.h"
#include "tests/pipeline/pmp_verdict.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// The file names in `dir`, sorted.
std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  if (!fs::exists(dir)) return names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Whether `name` is a mesh file (not a drawing, a toolpath or a picture).
bool mesh_file(const std::string& name) {
  for (const char* ext : {".stl", ".obj", ".ply", ".off", ".drc", ".3mf", ".glb"}) {
    const std::string e(ext);
    if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0) return true;
  }
  return false;
}

// Whether a report is valid, or open only at its border (an open surface
// made for viewing, as fit_for(Viewing) accepts it).
bool fit(const ValidationReport& r) {
  return r.valid() || (r.self_intersection != IntersectionCheck::NotRun &&
                       std::all_of(r.defects.begin(), r.defects.end(),
                                   [](const DefectReport& d) { return d.kind == Defect::BoundaryEdge; }));
}

// `fabmesh check` accepts every one of `files` (one process for all; an open
// surface with boundary edges as its only defect), and CGAL PMP agrees with
// validate object by object: closed exactly when it has no boundary edge,
// free of self-intersections, outward for a closed one-component object.
void require_checked(const std::vector<std::string>& files) {
  std::vector<std::string> args{"check", "--json"};
  args.insert(args.end(), files.begin(), files.end());
  const LimitedRun r = run_limited(args, 600.0, 4096 * kMiB);
  INFO(r.describe());
  const auto reports = nlohmann::json::parse(r.out);
  REQUIRE(reports.size() == files.size());
  for (const auto& j : reports) {
    INFO(j["file"].get<std::string>());
    const auto& kinds = j["defect_kinds"];
    CHECK((j["valid"] == true || (kinds.size() == 1 && kinds[0] == "boundary_edge")));
  }
  for (const std::string& path : files) {
    const MeshFile file = read_mesh_file(path);
    std::vector<TriangleSoup> objects;
    for (const MeshObject& o : file.objects) objects.push_back(o.soup);
    if (objects.empty()) objects.push_back(file.soup);
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const TriangleSoup soup = weld(objects[i]).soup;
      const ValidationReport report = validate(soup);
      const PmpVerdict pmp = pmp_verdict(soup);
      INFO(path << " object " << i);
      CHECK(fit(report));
      REQUIRE(pmp.polygon_mesh);
      CHECK(pmp.closed == (report.boundary_edges == 0));
      CHECK(pmp.self_intersecting == report.self_intersecting);
      if (pmp.outward) CHECK(*pmp.outward == report.oriented_outward);
    }
  }
}

}  // namespace

TEST_CASE("run: two runs write byte-identical files for every format of every example",
          "[pipeline][run][determinism]") {
  // The examples `run` accepts, grouped by the formats they can make (their kind's, with the
  // content each needs: a mould, a router path): one invocation per group asks for all of them.
  std::map<std::string, std::vector<std::string>> by_formats;
  std::set<std::string> kinds_seen;
  std::vector<std::string> paths;
  for (const auto& e : fs::directory_iterator(std::string(FABMESH_SOURCE_DIR) + "/configs/examples"))
    if (e.path().extension() == ".yaml") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  const std::vector<std::string> kinds = kind_names();
  for (const std::string& path : paths) {
    Design design;
    try {
      design = read_design(path);
    } catch (const FileError&) {
      continue;  // not a runnable design (a batch manifest): `run` refuses it, there is nothing to compare
    }
    if (std::holds_alternative<CurveDesign>(design.body)) continue;  // drawings are compared by the DXF test
    kinds_seen.insert(kind_name(design));
    std::string formats;
    for (const OutputFormat& f : output_formats()) {
      if (!applies_to(f, design)) continue;
      formats += (formats.empty() ? "" : ",") + std::string(f.name);
    }
    by_formats[formats].push_back(path);
  }
  for (const char* kind : {"vessel", "countertop", "surface"}) CHECK(kinds_seen.count(kind) == 1);

  const fs::path dir = fresh_dir("determinism");
  std::size_t compared = 0, group = 0;
  std::vector<std::string> meshes;  // every mesh file of the first round
  for (const auto& [formats, designs] : by_formats) {
    const std::string sub = "group" + std::to_string(group++);
    const auto format_count = static_cast<std::size_t>(std::count(formats.begin(), formats.end(), ',') + 1);
    for (const char* round : {"a", "b"}) {
      std::vector<std::string> args{"run", "-q",
                                    "-o",  (dir / round / sub).string(),
                                    "-D",  "outputs=[" + formats + "]",
                                    "-D",  "on_output_error=fail"};
      args.insert(args.end(), designs.begin(), designs.end());
      const LimitedRun r = run_limited(args, 600.0, 4096 * kMiB);
      INFO(formats << " round " << round << ": " << r.describe());
      REQUIRE(r.code == 0);
    }
    const std::vector<std::string> a = files_in(dir / "a" / sub), b = files_in(dir / "b" / sub);
    INFO(designs.size() << " designs, formats " << formats);
    CHECK(a.size() >= designs.size() * format_count);  // a mould writes a file per part
    REQUIRE(a == b);
    for (const std::string& name : a) {
      INFO(name);
      CHECK(read_file((dir / "a" / sub / name).string()) == read_file((dir / "b" / sub / name).string()));
      if (mesh_file(name)) meshes.push_back((dir / "a" / sub / name).string());
      ++compared;
    }
  }
  CHECK(compared > 0);
  CHECK(meshes.size() > 100);
  require_checked(meshes);
}
