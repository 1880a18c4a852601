// kind: countertop -> outline and holes -> region (proven simple) -> CDT ->
// slab; the exact curves also give the cutting outline.

#include <fmt/format.h>

#include <memory>
#include <string>

#include "geometry/core/error_checks.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/slab.h"
#include "geometry/toolpath/toolpath.h"
#include "pipeline/build_design.h"
#include "pipeline/build_kitchen.h"
#include "pipeline/plane_memo.h"

namespace fabmesh {
namespace {

// Runs `plan`, rethrowing a GeometryError at a loop's label ("outline",
// "holes[1] (ellipse)") at that loop's design key, so that it is reported at
// the line and column of the hole or outline; the message's leading label,
// which the location now gives, is left out.
template <class Plan>
auto at_loop_keys(const CountertopDesign& design, const std::vector<RegionHole>& holes, Plan plan)
    -> decltype(plan()) {
  try {
    return plan();
  } catch (const GeometryError& e) {
    ErrorLocation at = e.location();
    std::string label;
    if (at.key == "outline") {
      label = "outline";
      at.key = design.outline.key.empty() ? "outline" : design.outline.key;
    }
    for (std::size_t i = 0; i < holes.size() && label.empty(); ++i) {
      if (at.key != holes[i].label) continue;
      label = holes[i].label;
      at.key = holes[i].key.empty() ? fmt::format("holes[{}]", i) : holes[i].key;
      at.name = label;
    }
    if (label.empty()) throw;
    std::string message = e.what();
    for (const std::string& lead : {label + ": ", label + " "}) {
      if (message.rfind(lead, 0) == 0) {
        message.erase(0, lead.size());
        break;
      }
    }
    throw GeometryError(at, message);
  }
}

// The design's tap holes as drilled (design coordinates), each with its
// loop's label, in the design's order.
std::vector<DrillHole> drill_holes(const CountertopDesign& design, const std::vector<RegionHole>& holes) {
  std::vector<DrillHole> drills;
  for (std::size_t i = 0; i < design.holes.size(); ++i) {
    if (!design.holes[i].drill) continue;
    const HoleDrill& d = *design.holes[i].drill;
    drills.push_back({d.center, d.diameter, d.tool, holes[i].label});
  }
  return drills;
}

// The web of material round each tap hole, on the whole top's loops (seams
// keep seam_clearance from every cut-out besides).
void check_tap_hole_webs(const CountertopDesign& design, const Region2& region,
                         const std::vector<RegionHole>& holes, const CncOptions& cnc) {
  std::vector<const std::vector<Vec2>*> loops{&region.outer};
  std::vector<std::string> labels{"outline"};
  std::vector<std::size_t> own;
  for (std::size_t i = 0; i < holes.size(); ++i) {
    loops.push_back(&region.holes[i]);
    labels.push_back(holes[i].label);
    if (design.holes[i].drill) own.push_back(i + 1);
  }
  check_drill_webs(drill_holes(design, holes), own, loops, labels, region.max_deviation, cnc);
}

// The slab the design asks for.
SlabOptions slab_options(const CountertopDesign& design) {
  SlabOptions so;
  so.thickness = design.thickness;
  so.max_edge = design.max_edge;
  so.max_triangles = design.max_triangles;
  return so;
}

// The work in the plane: the curves (lap "curve"), the region ("region") and
// the slab's top, from the context's memo when it holds them for the same
// design (but its name and thickness) and tolerance, else built and kept there.
std::shared_ptr<const CountertopPlane> plane_of(const CountertopDesign& design, const BuildContext& context) {
  std::string key;
  if (context.reuse != nullptr && context.reuse->memo != nullptr && !context.reuse->key.empty()) {
    key = fmt::format("{}\ntolerance {:a}", context.reuse->key, context.tolerance);
    if (std::shared_ptr<const CountertopPlane> kept = context.reuse->memo->find(key)) {
      context.watch.lap("curve");
      context.watch.lap("region");
      return kept;
    }
  }
  auto plane = std::make_shared<CountertopPlane>();
  plane->curves.push_back({"outline", build_curve(design.outline)});
  for (std::size_t i = 0; i < design.holes.size(); ++i) {
    plane->curves.push_back({fmt::format("holes[{}]", i), build_curve(design.holes[i].curve)});
    plane->holes.push_back({plane->curves.back().curve.curve,
                            fmt::format("holes[{}] ({})", i, design.holes[i].shape),
                            design.holes[i].curve.key});
  }
  context.watch.lap("curve");
  RegionOptions ro;
  // A profiled edge's arcs are sampled too: the loops get half the tolerance.
  ro.tolerance = design.edges.kind == EdgeProfileKind::Square ? context.tolerance : 0.5 * context.tolerance;
  ro.max_points = design.max_triangles / 2;  // every loop point makes two wall triangles
  ro.outline_key = design.outline.key;
  plane->region = within_share(ro.max_points, design.max_triangles, "the loops' points",
                               "each point of a loop makes two wall triangles", [&] {
                                 return build_region(plane->curves.front().curve.curve, plane->holes, ro);
                               });
  context.watch.lap("region");
  const SlabOptions so = slab_options(design);
  require_positive("thickness", so.thickness);  // refused before the triangulation, as build_slab does
  plane->top = slab_top(plane->region, so);
  if (!key.empty()) context.reuse->memo->keep(key, plane);
  return plane;
}

}  // namespace

Result build(const CountertopDesign& design, const BuildContext& context) {
  Result out;
  const std::shared_ptr<const CountertopPlane> plane = plane_of(design, context);
  out.curves = plane->curves;
  const std::vector<RegionHole>& holes = plane->holes;
  const Region2& region = plane->region;
  const BuiltCurve& outline = out.curves.front().curve;
  const SlabMesh slab = extrude_slab(region, plane->top, slab_options(design));
  context.watch.lap("build");
  CountertopProducts products;
  if (context.wants_cutting) {
    CutLoopOptions co;
    co.tolerance = context.tolerance;
    co.reverse = region.reversed[0];
    products.cutting.push_back(cut_loop(outline.curve, "outline", true, co));
    for (std::size_t i = 0; i < holes.size(); ++i) {
      co.reverse = region.reversed[i + 1];
      products.cutting.push_back(cut_loop(holes[i].curve, holes[i].label, false, co));
    }
    context.watch.lap("cutting_outline");
  }
  std::size_t boundary_points = 0;
  for (const auto& loop : slab.triangulation.boundary) boundary_points += loop.size();
  Part product;
  product.name = context.common.name;
  product.mesh = to_soup(slab.mesh);
  product.proofs.embedding = slab.proof;    // the region is simple and the slab a prism over it
  product.proofs.topology = slab.topology;  // extrude's pairing of every face's sides
  out.max_deviation = region.max_deviation;
  if (design.edges.kind != EdgeProfileKind::Square) {
    // Edges profiled: the top is not a prism; every outline edge is exposed
    // unless the kitchen's outline marks it a wall.
    ProfiledPlan plan{region.outer, {}, region.holes, context.common.name};
    for (const EdgeKind e : top_edge_kinds(design, region, outline.curve))
      plan.exposed.push_back(e == EdgeKind::Exposed);
    product.mesh = profiled_mesh(design, plan, design.thickness, region.max_deviation, context, out);
    product.proofs = {};
  }
  out.parts.push_back(std::move(product));
  out.facts.set("holes", holes.size())
      .set("outline_points", region.outer.size())
      .set("boundary_points", boundary_points)
      .set("planar_triangles", slab.triangulation.triangles.size())
      .set("steiner_points", slab.triangulation.steiner_points)
      .set("region_area", region.area)
      .set("thickness", design.thickness);
  if (design.max_edge > 0.0) out.facts.set("max_edge", design.max_edge);
  if (!holes.empty()) {
    // Between the exact curves (a proven lower bound), not their polylines.
    out.facts.set("min_clearance", region.min_clearance).set("min_clearance_where", region.clearance_where);
  }
  if (design.cnc) {
    CncOptions cnc = design.cnc->options;
    cnc.tolerance = context.tolerance;
    at_loop_keys(design, holes, [&] { check_tap_hole_webs(design, region, holes, cnc); });
  }
  if (design.kitchen) {
    // The pieces, each cut on its slab: the whole top is not one program.
    products.kitchen = at_loop_keys(
        design, holes, [&] { return build_kitchen(design, region, outline.curve, holes, context, out); });
    if (design.cnc) {
      products.gcode = GcodeOptions{context.common.name, context.common.units, design.cnc->program_units,
                                    design.cnc->decimals};
    }
  } else if (design.cnc) {
    CncOptions cnc = design.cnc->options;
    cnc.tolerance = context.tolerance;
    // Tap holes are drilled, not routed: the router cuts the other holes.
    std::vector<RegionHole> routed;
    cnc.hole_tabs.clear();
    for (std::size_t i = 0; i < holes.size(); ++i) {
      if (design.holes[i].drill) continue;
      routed.push_back(holes[i]);
      cnc.hole_tabs.push_back(i < design.cnc->options.hole_tabs.size() ? design.cnc->options.hole_tabs[i]
                                                                       : no_tabs());
    }
    products.toolpath = at_loop_keys(design, holes, [&] {
      Toolpath t = plan_toolpath(outline.curve, routed, cnc);
      t.drills = drilling_order(drill_holes(design, holes), cnc);
      t.profiling = profile_passes(design, cnc, 0.0, region.max_deviation, out.warnings);
      if (t.profiling.depth > 0.0) {
        t.profiling.runs = profile_runs(region.outer, std::vector<bool>(region.outer.size(), true),
                                        0.5 * t.profiling.diameter, cnc.tolerance, context.common.name);
      }
      return t;
    });
    products.gcode = GcodeOptions{context.common.name, context.common.units, design.cnc->program_units,
                                  design.cnc->decimals};
    context.watch.lap("toolpath");
    const Toolpath& t = *products.toolpath;
    append_shares(out.tolerance_shares, "cnc: ", t.tolerance_shares);
    const ToolpathTotals totals = toolpath_totals(t);
    out.warnings.insert(out.warnings.end(), t.warnings.begin(), t.warnings.end());
    std::size_t hole_tabs = 0;
    for (const LoopPath& loop : t.loops) hole_tabs += loop.outer ? 0 : loop.tabs.size();
    const std::size_t outline_tabs = t.loops.empty() ? 0 : t.loops.back().tabs.size();
    Facts arc_fit;
    arc_fit.set("enabled", cnc.arc_fit)
        .set("replaced", t.fit_replaced)
        .set("arcs", t.fit_arcs)
        .set("lines", t.fit_lines)
        .set("deviation", t.fit_deviation);
    Facts facts;
    facts.set("tool_diameter", cnc.tool_diameter)
        .set("passes", t.pass_z.size())
        .set("moves", t.moves.size())
        .set("deviation", t.deviation)
        .set("clearance", t.clearance)
        .set("tabs", outline_tabs)
        .set("hole_tabs", hole_tabs)
        .set("entry", to_string(cnc.entry))
        .set("arc_fit", std::move(arc_fit))
        .set("finish", cnc.finish)
        .set("direction", to_string(cnc.direction))
        .set("relief", to_string(cnc.relief))
        .set("drills", t.drills.size())
        .set("tools", tool_facts(t))
        .set("cutting_length", totals.cutting)
        .set("plunging_length", totals.plunging)
        .set("rapid_length", totals.rapid)
        .set("drilling_length", totals.drilling)
        .set("estimated_minutes", totals.minutes);
    out.facts.set("cnc", std::move(facts));
  }
  if (context.wants_exact) {
    products.solid.form = ExactSolid::Form::Extrusion;
    products.solid.height = design.thickness;
    for (const NamedBuiltCurve& c : out.curves) products.solid.loops.push_back(exact_pieces(c.curve.curve));
    products.solid.edges = design.edges;
    for (std::size_t i = 0; i < products.solid.loops.front().size(); ++i) {
      const bool wall =
          design.kitchen && i < design.outline.segments.size() && design.outline.segments[i].wall;
      products.solid.profiled.push_back(!wall);
    }
  }
  out.products = std::move(products);
  return out;
}

}  // namespace fabmesh
