// kind: surface -> patch network (joins built and measured) -> tessellation
// -> thickened shell, validated with the 3D self-intersection test (a
// too-thick shell is caught there). Without thickness: the open surface,
// fit for viewing only.

#include "geometry/mesh/thicken.h"
#include "geometry/surfaces/tessellate.h"
#include "pipeline/build_design.h"

namespace fabmesh {
namespace {

nlohmann::json joints_json(const PatchNetwork& network) {
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
  return joints;
}

}  // namespace

BuiltMesh build(const SurfaceDesign& design, const BuildContext& context) {
  const PatchNetwork network = build_patch_network(design.patches);
  context.watch.lap("patches");
  const bool thick = design.thickness > 0.0;
  TessellateOptions to;
  to.tolerance = context.tolerance;
  to.offset = design.thickness;  // the offset sheet is kept within the tolerance too
  // Two sheets and the rim: the sheet may use a little under half the budget.
  to.max_triangles = thick ? design.max_triangles / 2 : design.max_triangles;
  const SurfaceTessellation sheet = tessellate(network, to);
  std::size_t rim_edges = 0;
  for (const auto h : sheet.mesh.halfedges()) rim_edges += sheet.mesh.is_boundary(h) ? 1 : 0;
  nlohmann::json facts = {{"patches", network.patches.size()},
                          {"joints", joints_json(network)},
                          {"sheet_triangles", sheet.mesh.n_faces()},
                          {"rim_edges", rim_edges}};
  if (!thick) {
    context.watch.lap("build");
    BuiltMesh out = validated(sheet.mesh, std::nullopt, context);
    out.purpose = MeshPurpose::Viewing;
    out.max_deviation = sheet.max_deviation;
    facts["fabrication"] = "not valid: open surface (no thickness)";
    out.facts = std::move(facts);
    return out;
  }
  ThickenOptions th;
  th.thickness = design.thickness;
  th.max_triangles = design.max_triangles;
  const Mesh solid = thicken(sheet.mesh, sheet.normals, th);
  context.watch.lap("build");
  BuiltMesh out = validated(solid, std::nullopt, context);
  out.max_deviation = sheet.max_deviation;
  facts["thickness"] = design.thickness;
  out.facts = std::move(facts);
  return out;
}

}  // namespace fabmesh
