// kind: surface -> patch network (joins built and measured) -> tessellation
// (proven cell bounds, the shell's sheets and side walls included) ->
// thickened shell on the chosen side, validated with the 3D
// self-intersection test (a too-thick shell is caught there and told the
// thickness its curvature allows). Without thickness: the open surface, fit
// for viewing only.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/thicken.h"
#include "geometry/surfaces/tessellate.h"
#include "pipeline/build_design.h"
#include "pipeline/validate_parts.h"

namespace fabmesh {
namespace {

std::vector<Facts> joint_facts(const PatchNetwork& network) {
  std::vector<Facts> joints;
  for (const SharedBorder& b : network.borders) {
    Facts joint;
    joint.set("patches", std::vector<std::string>{network.names[b.a], network.names[b.b]})
        .set("sides", std::vector<std::string>{to_string(b.side_a), to_string(b.side_b)})
        .set("declared", to_string(b.declared))
        .set("achieved", to_string(b.achieved))
        .set("gap", b.gap)
        .set("normal_angle", b.normal_angle)
        .set("curvature_jump", b.curvature_jump);
    joints.push_back(std::move(joint));
  }
  return joints;
}

// The shell's span along S_s x S_t for the design's side; outward and inward
// are told apart by the volume a coarse sheet encloses with its rim.
std::array<double, 2> span_of(const SurfaceDesign& design, const PatchNetwork& network) {
  double volume = 0.0;
  if (design.thicken == ThickenSide::Outward || design.thicken == ThickenSide::Inward) {
    TessellateOptions coarse;
    coarse.tolerance = 1e-2 * network.size;
    volume = enclosed_volume(tessellate(network, coarse).mesh);
  }
  return shell_span(design.thicken, design.thickness, volume, network.size);
}

// The smallest radius of curvature on the thickened side, measured at the
// grid vertices (where the sheet folds first).
struct FoldHint {
  double thickness_limit = std::numeric_limits<double>::infinity();  ///< no larger thickness passes
  double proven = std::numeric_limits<double>::infinity();           ///< no smaller one folds
  std::string where;
};

FoldHint fold_hint(const PatchNetwork& network, const SurfaceTessellation& sheet, double from, double to) {
  const double thickness = to - from, up = std::max(to, 0.0) / thickness,
               down = std::max(-from, 0.0) / thickness;
  FoldHint hint;
  for (std::size_t p = 0; p < network.patches.size(); ++p) {
    for (double s : sheet.s_breaks[p]) {
      for (double t : sheet.t_breaks[p]) {
        const PatchJet j = network.patches[p].jet(s, t);
        const Vec3 n = j.ds.cross(j.dt);
        const double det = n.squaredNorm();
        if (!(det > 0.0)) continue;
        const Vec3 unit = n / std::sqrt(det);
        const double e = j.dss.dot(unit), f = j.dst.dot(unit), g = j.dtt.dot(unit);
        const double ee = j.ds.squaredNorm(), ff = j.ds.dot(j.dt), gg = j.dt.squaredNorm();
        const double mean = (e * gg - 2.0 * f * ff + g * ee) / (2.0 * det), gauss = (e * g - f * f) / det;
        const double root = std::sqrt(std::max(0.0, mean * mean - gauss));
        // Folds toward +n where (to) k_max >= 1, toward -n where (-from) (-k_min) >= 1.
        const double limit =
            std::min(up > 0.0 && mean + root > 0.0 ? 1.0 / (up * (mean + root)) : INFINITY,
                     down > 0.0 && root - mean > 0.0 ? 1.0 / (down * (root - mean)) : INFINITY);
        if (limit < hint.thickness_limit) {
          hint.thickness_limit = limit;
          hint.where = fmt::format("patch '{}' near s {:.3g}, t {:.3g}", network.names[p], s, t);
        }
      }
    }
  }
  double kappa = 0.0;
  for_each_cell_bound(network, sheet.s_breaks, sheet.t_breaks,
                      [&](std::size_t, double, double, double, double, const CellDerivatives& d) {
                        kappa = std::max(kappa, curvature_bound(d));
                      });
  hint.proven = 1.0 / (std::max(up, down) * kappa);
  return hint;
}

[[noreturn]] void too_thick(const SurfaceDesign& design, const BuildContext& context, const Part& shell,
                            const FoldHint& hint) {
  std::string message =
      fmt::format("surface '{}': the mesh is not valid for fabrication", context.common.name);
  for (const std::string& line : describe_defects(shell.validation)) message += "; " + line;
  const std::string side = to_string(design.thicken);
  if (design.thickness >= hint.thickness_limit) {
    message += fmt::format(
        "; thickness {} ({}) is more than the surface's curvature allows: the shell folds where the radius "
        "of curvature on the thickened side is smaller than the shell ({}), so the largest thickness that "
        "could pass is below {:.4g}",
        design.thickness, side, hint.where, hint.thickness_limit);
  } else {
    message += fmt::format(
        "; the shell (thickness {}, {}) does not fold locally (its curvature allows up to "
        "{:.4g}, {}): distant parts of it meet",
        design.thickness, side, hint.thickness_limit, hint.where);
  }
  if (std::isfinite(hint.proven) && hint.proven > 0.0) {
    message += fmt::format(
        "; a thickness below {:.4g} cannot fold anywhere (curvature bounded over every cell)", hint.proven);
  }
  throw ValidationFailed(message);
}

// The sheet's tessellation options: two sheets and the rim of a shell, so
// the sheet may use a little under half the budget.
TessellateOptions sheet_options(const SurfaceDesign& design, double tolerance) {
  TessellateOptions to;
  to.tolerance = tolerance;
  to.max_triangles = design.thickness > 0.0 ? design.max_triangles / 2 : design.max_triangles;
  return to;
}

// The shell of `sheet` for the design's thickness, from the span's near side.
Mesh thickened(const SurfaceDesign& design, const SurfaceTessellation& sheet,
               const std::array<double, 2>& span) {
  ThickenOptions th;
  th.thickness = design.thickness;
  th.offset = span[0];
  th.max_triangles = design.max_triangles;
  return thicken(sheet.mesh, sheet.normals, th);
}

// The design's mesh, named as the design.
Part product_part(const std::string& name, TriangleSoup mesh) {
  Part part;
  part.name = name;
  part.mesh = std::move(mesh);
  return part;
}

}  // namespace

Result surface_draft(const SurfaceDesign& design, double tolerance) {
  Result out;
  const PatchNetwork network = build_patch_network(design.patches);
  const SurfaceTessellation sheet = tessellate(network, sheet_options(design, tolerance));
  out.max_deviation = sheet.max_deviation;
  if (design.thickness > 0.0) {
    out.parts.push_back(product_part("", to_soup(thickened(design, sheet, span_of(design, network)))));
  } else {
    out.parts.push_back(product_part("", to_soup(sheet.mesh)));
    out.purpose = MeshPurpose::Viewing;
  }
  out.products = SurfaceProducts{network, std::nullopt};
  return out;
}

Result build(const SurfaceDesign& design, const BuildContext& context) {
  const PatchNetwork network = build_patch_network(design.patches);
  context.watch.lap("patches");
  const bool thick = design.thickness > 0.0;
  const std::array<double, 2> span = thick ? span_of(design, network) : std::array<double, 2>{0.0, 0.0};
  TessellateOptions to = sheet_options(design, context.tolerance);
  to.shell_from = span[0];  // both sheets and the side walls are kept within the tolerance
  to.shell_to = span[1];
  const SurfaceTessellation sheet =
      thick ? within_share(to.max_triangles, design.max_triangles, "a sheet of the shell",
                           "the shell is two sheets and a rim", [&] { return tessellate(network, to); })
            : tessellate(network, to);
  std::size_t rim_edges = 0;
  for (const auto h : sheet.mesh.halfedges()) rim_edges += sheet.mesh.is_boundary(h) ? 1 : 0;
  Result out;
  out.facts.set("patches", network.patches.size())
      .set("joints", joint_facts(network))
      .set("sheet_triangles", sheet.mesh.n_faces())
      .set("rim_edges", rim_edges);
  out.max_deviation = sheet.max_deviation;
  SurfaceProducts products{network, std::nullopt};
  if (!thick) {
    context.watch.lap("build");
    out.parts.push_back(product_part(context.common.name, to_soup(sheet.mesh)));
    out.purpose = MeshPurpose::Viewing;
    out.facts.set("fabrication", "not valid: open surface (no thickness)");
    out.products = std::move(products);
    return out;
  }
  const Mesh solid = thickened(design, sheet, span);
  context.watch.lap("build");
  // No proof: the 3D self-intersection test catches a folding shell, and
  // its verdict is needed here to say which thickness would pass.
  Part shell = product_part(context.common.name, to_soup(solid));
  validate_part(shell);
  context.watch.lap("validate");
  if (shell.validation.self_intersecting)
    too_thick(design, context, shell, fold_hint(network, sheet, span[0], span[1]));
  out.parts.push_back(std::move(shell));
  out.facts.set("thickness", design.thickness)
      .set("thicken", to_string(design.thicken))
      .set("shell_span", std::vector<double>{span[0], span[1]});
  if (context.wants_exact) products.shell = shell_grid(sheet, span[0], span[1]);
  out.products = std::move(products);
  return out;
}

}  // namespace fabmesh
