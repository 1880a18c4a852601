#include "pipeline/job.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "geometry/core/errors.h"
#include "geometry/core/stage_timer.h"
#include "geometry/fairing/fair_curve.h"
#include "geometry/mesh/constructed_validation.h"
#include "geometry/mesh/slab.h"
#include "geometry/mesh/soup.h"
#include "geometry/mesh/vessel.h"
#include "geometry/surfaces/surface_mesh.h"
#include "io/cutting/cutting_outline.h"
#include "io/cutting/dxf.h"
#include "io/cutting/svg.h"
#include "io/mesh/atomic_file.h"
#include "io/mesh/draco.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/stl.h"

namespace fabmesh {
namespace {

// Share of the tolerance kept for output quantization (Draco, float32 STL).
constexpr double kOutputShare = 0.1;

// What a builder hands on: the validated mesh as a soup (OpenMesh meshes
// cannot be moved, so the halfedge mesh never leaves its builder's branch).
struct BuiltMesh {
  TriangleSoup soup;
  ValidationReport validation;
  double max_deviation = 0.0;
  std::string embedding_proof;
  nlohmann::json build;
  std::vector<CutLoop> cutting;  ///< countertops: the cutting outline (outline first, then the holes)
  bool open_surface = false;     ///< a surface without thickness: written for viewing, not for fabrication
};

// An open surface is fit for viewing when the only defect is its own border.
bool only_open_border(const ValidationReport& r) {
  return r.self_intersection_checked && !r.defects.empty() &&
         std::all_of(r.defects.begin(), r.defects.end(),
                     [](const DefectReport& d) { return d.kind == Defect::BoundaryEdge; });
}

// Validates `mesh` (by its builder's embedding proof when it has one) and
// converts it to the soup the writers take.
BuiltMesh validated(const Mesh& mesh, double max_deviation, std::string proof, nlohmann::json facts,
                    StageTimer& watch) {
  BuiltMesh out;
  out.soup = to_soup(mesh);
  out.validation = proof.empty() ? validate(mesh, out.soup) : validate_constructed(mesh, out.soup, proof);
  watch.lap("validate");
  out.max_deviation = max_deviation;
  out.embedding_proof = std::move(proof);
  out.build = std::move(facts);
  return out;
}

bool wants(const Design& design, const char* format) {
  const auto& outs = design.common.outputs;
  return std::find(outs.begin(), outs.end(), format) != outs.end();
}

// Outline and holes -> region (proven simple) -> CDT -> slab; the exact curves also give the cutting outline.
BuiltMesh build_countertop(const Design& design, const CountertopDesign& c, double tolerance,
                           StageTimer& watch) {
  const BuiltCurve outline = build_curve(c.outline);
  std::vector<RegionHole> holes;
  for (std::size_t i = 0; i < c.holes.size(); ++i) {
    holes.push_back(
        {build_curve(c.holes[i].curve).curve, fmt::format("holes[{}] ({})", i, c.holes[i].shape)});
  }
  watch.lap("curve");
  RegionOptions ro;
  ro.tolerance = tolerance;
  ro.max_points = c.max_triangles;
  const Region2 region = build_region(outline.curve, holes, ro);
  watch.lap("region");
  SlabOptions so;
  so.thickness = c.thickness;
  so.max_edge = c.max_edge;
  so.max_triangles = c.max_triangles;
  const SlabMesh slab = build_slab(region, so);
  watch.lap("build");
  std::vector<CutLoop> cutting;
  if (wants(design, "dxf") || wants(design, "svg")) {
    CutLoopOptions co;
    co.tolerance = tolerance;
    co.reverse = region.reversed[0];
    cutting.push_back(cut_loop(outline.curve, "outline", true, co));
    for (std::size_t i = 0; i < holes.size(); ++i) {
      co.reverse = region.reversed[i + 1];
      cutting.push_back(cut_loop(holes[i].curve, holes[i].label, false, co));
    }
    watch.lap("cutting_outline");
  }
  std::size_t boundary_points = 0;
  for (const auto& loop : slab.triangulation.boundary) boundary_points += loop.size();
  nlohmann::json facts = {{"holes", holes.size()},
                          {"outline_points", region.outer.size()},
                          {"boundary_points", boundary_points},
                          {"planar_triangles", slab.triangulation.triangles.size()},
                          {"steiner_points", slab.triangulation.steiner_points},
                          {"region_area", region.area},
                          {"thickness", c.thickness}};
  if (c.max_edge > 0.0) facts["max_edge"] = c.max_edge;
  BuiltMesh out = validated(slab.mesh, region.max_deviation, slab.embedding_proof, std::move(facts), watch);
  out.cutting = std::move(cutting);
  return out;
}

// Patches -> network (joins built and measured) -> tessellation -> thickened shell, validated with the
// 3D self-intersection test (a too-thick shell is caught there). Without thickness: the open surface.
BuiltMesh build_surface(const SurfaceDesign& s, double tolerance, StageTimer& watch) {
  const PatchNetwork network = build_patch_network(s.patches);
  watch.lap("patches");
  SurfaceMeshOptions options;
  options.tolerance = tolerance;
  options.thickness = s.thickness;
  options.max_triangles = s.max_triangles;
  const SurfaceMesh surface = build_surface_mesh(network, options);
  watch.lap("build");
  nlohmann::json joints = nlohmann::json::array();
  for (const SharedBorder& b : network.borders) {
    joints.push_back({{"patches", {network.names[b.a], network.names[b.b]}},
                      {"sides", {to_string(b.side_a), to_string(b.side_b)}},
                      {"declared", to_string(b.declared)},
                      {"achieved", to_string(b.achieved)},
                      {"gap", b.gap},
                      {"normal_angle", b.normal_angle},
                      {"curvature_jump", b.curvature_jump}});
  }
  nlohmann::json facts = {{"patches", network.patches.size()},
                          {"joints", joints},
                          {"sheet_triangles", surface.sheet.mesh.n_faces()},
                          {"rim_edges", surface.rim_edges}};
  if (surface.thickened) {
    facts["thickness"] = s.thickness;
  } else {
    facts["fabrication"] = "not valid: open surface (no thickness)";
  }
  BuiltMesh out = validated(surface.mesh(), surface.max_deviation, "", std::move(facts), watch);
  out.open_surface = !surface.thickened;
  return out;
}

BuiltMesh build_mesh(const Design& design, double tolerance, StageTimer& watch) {
  if (const auto* v = std::get_if<VesselDesign>(&design.body)) {
    const BuiltCurve profile = build_curve(v->profile);
    watch.lap("curve");
    VesselOptions options;
    options.mode = v->mode;
    options.wall = v->wall;
    options.base = v->base;
    options.tolerance = tolerance;
    options.max_triangles = v->max_triangles;
    const VesselMesh vessel = build_vessel(profile.curve, options);
    watch.lap("build");
    std::size_t section_points = 0;
    for (const auto& loop : vessel.section.loops) section_points += loop.size();
    nlohmann::json facts = {{"angular_segments", vessel.segments},
                            {"section_loops", vessel.section.loops.size()},
                            {"section_points", section_points},
                            {"max_radius", vessel.section.max_radius}};
    return validated(vessel.mesh, vessel.max_deviation, vessel.embedding_proof, std::move(facts), watch);
  }
  if (const auto* c = std::get_if<CountertopDesign>(&design.body))
    return build_countertop(design, *c, tolerance, watch);
  if (const auto* s = std::get_if<SurfaceDesign>(&design.body)) return build_surface(*s, tolerance, watch);
  throw InputError(fmt::format("a {} design has no mesh to run; use `fabmesh sample` or `fabmesh optimize`",
                               design.common.kind));
}

// Draco bytes whose decoded mesh moves no vertex more than `tolerance` and is
// still valid: quantization may not collapse or fold faces, so the decoded
// soup is validated, with more bits until it passes.
std::string draco_bytes(const TriangleSoup& soup, double tolerance, const std::string& what,
                        bool open_surface) {
  DracoOptions options;
  options.tolerance = tolerance;
  for (int attempt = 0; attempt < 24; ++attempt) {
    std::string bytes = encode_draco(soup, options);
    const ValidationReport decoded = validate(parse_draco(bytes, what));
    if (decoded.valid() || (open_surface && only_open_border(decoded))) return bytes;
    options.tolerance *= 0.5;  // one more bit of quantization
  }
  throw ValidationFailed(what + ": no Draco quantization keeps the decoded mesh valid");
}

}  // namespace

JobReport run_job(const Design& design, const JobOptions& options) {
  JobReport report;
  report.name = design.common.name;
  report.kind = design.common.kind;
  report.tolerance = design.common.tolerance;
  StageTimer watch(report.timings_ms);
  const double build_tolerance = (1.0 - kOutputShare) * design.common.tolerance;
  BuiltMesh built = build_mesh(design, build_tolerance, watch);
  report.max_deviation = built.max_deviation;
  report.embedding_proof = built.embedding_proof;
  report.build = built.build;
  report.validation = std::move(built.validation);
  const TriangleSoup& soup = built.soup;
  if (!(built.open_surface && only_open_border(report.validation))) {
    require_valid(report.validation, fmt::format("{} '{}'", design.common.kind, design.common.name));
  }

  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec)
    throw FileError(options.out_dir, 0, 0,
                    fmt::format("{}: cannot create output folder: {}", options.out_dir, ec.message()));
  // The Draco encoding gets the tolerance the build left unused.
  const double output_tolerance = design.common.tolerance - built.max_deviation;
  std::vector<std::pair<std::string, std::string>> files;  // path, bytes: all encoded before any is written
  for (const std::string& format : design.common.outputs) {
    const std::string path =
        (std::filesystem::path(options.out_dir) / (design.common.name + "." + format)).string();
    if (format == "stl") {
      files.emplace_back(path, encode_stl(soup));
    } else if (format == "drc") {
      files.emplace_back(path, draco_bytes(soup, output_tolerance, path, built.open_surface));
    } else if (format == "obj") {
      files.emplace_back(path, encode_obj(soup));
    } else if (format == "ply") {
      files.emplace_back(path, encode_ply(soup));
    } else if (format == "off") {
      files.emplace_back(path, encode_off(soup));
    } else if (format == "dxf" && !built.cutting.empty()) {
      DxfOptions dxf;
      dxf.units = design.common.units;
      files.emplace_back(path, encode_dxf(built.cutting, dxf));
    } else if (format == "svg" && !built.cutting.empty()) {
      SvgOptions svg;
      svg.units = design.common.units;
      files.emplace_back(path, encode_svg(built.cutting, svg));
    } else {
      throw InputError(fmt::format("{}: unknown output format '{}'", design.common.path, format));
    }
    watch.lap("encode_" + format);
  }
  for (const auto& [path, bytes] : files) {
    write_file_atomically(path, bytes);
    report.outputs.push_back(path);
  }
  watch.lap("write");
  return report;
}

nlohmann::json to_json(const JobReport& r) {
  const ValidationReport& v = r.validation;
  nlohmann::json timings = nlohmann::json::object();
  for (const auto& [stage, ms] : r.timings_ms) timings[stage] = ms;
  for (const auto& [stage, ms] : v.timings_ms) timings["validate." + stage] = ms;
  nlohmann::json j = {{"name", r.name},
                      {"kind", r.kind},
                      {"outputs", r.outputs},
                      {"vertices", v.vertices},
                      {"triangles", v.triangles},
                      {"volume", v.volume},
                      {"area", v.area},
                      {"watertight", v.boundary_edges == 0 && v.non_manifold_edges == 0},
                      {"manifold", v.non_manifold_edges == 0 && v.non_manifold_vertices == 0},
                      {"self_intersecting", v.self_intersecting},
                      {"max_deviation", r.max_deviation},
                      {"tolerance", r.tolerance},
                      {"genus", v.genus ? nlohmann::json(*v.genus) : nlohmann::json(nullptr)},
                      {"components", v.components},
                      {"valid", v.valid()},
                      {"timings_ms", timings}};
  if (!r.embedding_proof.empty()) j["self_intersection_proof"] = r.embedding_proof;
  if (r.build.contains("fabrication")) j["fabrication"] = r.build["fabrication"];
  if (!r.build.is_null()) j["build"] = r.build;
  return j;
}

}  // namespace fabmesh
