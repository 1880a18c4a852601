#include "pipeline/build_kitchen.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "geometry/mesh/edge_profile.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/slab.h"
#include "geometry/sampling/cut_loop.h"
#include "geometry/sampling/offset_bezier.h"
#include "geometry/toolpath/toolpath.h"

namespace fabmesh {
namespace {

// A closed chain of line segments through `points`.
CompositeCurve polygon_curve(const std::vector<Vec2>& points) {
  std::vector<Segment> segments;
  segments.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    segments.push_back(Segment::line(points[k], points[(k + 1) % points.size()]));
  return CompositeCurve(std::move(segments), true);
}

// A piece as a region of its own: its loops are the top's (proven within
// `deviation` of the exact curves) and chords of seams (exact lines).
Region2 piece_region(const KitchenPiece& piece, const Region2& top, const std::string& proof) {
  Region2 r;
  r.outer = piece.outer;
  r.holes = piece.holes;
  r.max_deviation = piece.strip ? 0.0 : top.max_deviation;
  r.area = piece.area;
  r.reversed.assign(1 + piece.holes.size(), false);
  r.proof = piece.strip ? "a backsplash strip: a rectangle" : proof;
  return r;
}

// The kind of the piece's edge nearest `p` (a point of its exact outline,
// which the edges follow within the build's deviation).
EdgeKind kind_near(const KitchenPiece& piece, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  EdgeKind kind = EdgeKind::Exposed;
  const std::size_t n = piece.outer.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = piece.outer[i];
    const Vec2 ab = piece.outer[(i + 1) % n] - a;
    const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    const double d = (a + t * ab - p).squaredNorm();
    if (d < best) {
      best = d;
      kind = piece.edges[i];
    }
  }
  return kind;
}

// Appends `from`'s loops and moves to `into` (one program for several pieces).
void append_program(Toolpath& into, const Toolpath& from) {
  if (into.moves.empty()) {
    into = from;
    return;
  }
  const std::size_t loops = into.loops.size();
  into.loops.insert(into.loops.end(), from.loops.begin(), from.loops.end());
  into.roughing.insert(into.roughing.end(), from.roughing.begin(), from.roughing.end());
  for (ToolMove m : from.moves) {
    m.loop += loops;
    into.moves.push_back(m);
  }
  into.warnings.insert(into.warnings.end(), from.warnings.begin(), from.warnings.end());
  into.deviation = std::max(into.deviation, from.deviation);
  into.clearance = std::min(into.clearance, from.clearance);
  into.fit_replaced += from.fit_replaced;
  into.fit_arcs += from.fit_arcs;
  into.fit_lines += from.fit_lines;
  into.fit_deviation = std::max(into.fit_deviation, from.fit_deviation);
}

// The router program of slab `slab`: the tap holes of every piece on it
// drilled first, then each piece routed, in slab coordinates, its cut-outs
// before its outline. `design_holes`: the design's holes (which are drilled).
Toolpath slab_program(const KitchenSplit& split, const SlabNesting& nesting, std::size_t slab,
                      const CncOptions& cnc, const std::vector<CountertopHole>& design_holes,
                      const ProfilePasses& profile) {
  Toolpath program;
  std::vector<DrillHole> drills;
  for (const Placement& p : nesting.placements) {
    if (p.slab != slab) continue;
    const KitchenPiece& piece = split.pieces[p.piece];
    std::vector<RegionHole> holes;
    CncOptions options = cnc;
    options.hole_tabs.clear();
    for (std::size_t h = 0; h < piece.holes.size(); ++h) {
      const std::size_t index = piece.hole_index[h];
      if (index < design_holes.size() && design_holes[index].drill) {
        // A tap hole is drilled at its placed centre, not routed.
        const HoleDrill& d = *design_holes[index].drill;
        drills.push_back({place_point(d.center, p.rotation_deg, p.offset), d.diameter, d.tool,
                          fmt::format("{} holes[{}] (drill)", piece.name, index)});
        continue;
      }
      // A hole's curve may run either way; given counter-clockwise.
      std::vector<Vec2> placed = place_loop(piece.holes[h], p);
      std::reverse(placed.begin(), placed.end());
      holes.push_back({polygon_curve(placed), fmt::format("{} holes[{}]", piece.name, index),
                       fmt::format("holes[{}]", index)});
      options.hole_tabs.push_back(index < cnc.hole_tabs.size() ? cnc.hole_tabs[index] : no_tabs());
    }
    try {
      append_program(program, plan_toolpath(polygon_curve(p.outer), holes, options));
    } catch (const GeometryError& e) {
      // Name the piece: its loops are in slab coordinates, not the design's.
      throw GeometryError(ErrorLocation{e.location().key, {}, e.location().point},
                          fmt::format("{} (on slab {}, turned {} degrees, in slab coordinates): {}",
                                      piece.name, slab + 1, p.rotation_deg, e.what()));
    }
  }
  program.drills = drilling_order(std::move(drills), cnc);
  if (profile.depth > 0.0) {
    // The profile bit along each placed piece's exposed edges (strips are square).
    program.profiling = profile;
    for (const Placement& p : nesting.placements) {
      const KitchenPiece& piece = split.pieces[p.piece];
      if (p.slab != slab || piece.strip) continue;
      std::vector<bool> exposed;
      for (const EdgeKind e : piece.edges) exposed.push_back(e == EdgeKind::Exposed);
      if (std::none_of(exposed.begin(), exposed.end(), [](bool e) { return e; })) continue;
      for (ProfileRun& run :
           profile_runs(p.outer, exposed, 0.5 * profile.diameter, cnc.tolerance, piece.name))
        program.profiling.runs.push_back(std::move(run));
    }
  }
  return program;
}

// A piece's lead arcs (and a helix entry's circle) lie in the waste round
// it, where its neighbours are: the tool must not reach them. The tool's
// edge lies at most 2r + finish + the loops' deviation from the piece on the
// path, and the lead's start sqrt(2) R_lead farther (a quarter circle's
// chord; R_lead = 2 lead_in / pi), a helix's circle 2 h farther still. The
// lead is shortened to fit `spacing` (with a warning); a helix that cannot
// fit is bad input.
void limit_entry(CncOptions& cnc, double spacing, double deviation, std::vector<std::string>& warnings) {
  const double r = 0.5 * cnc.tool_diameter;
  const double room = spacing - 2.0 * r - cnc.finish - deviation - cnc.tolerance;
  const double helix = cnc.entry == EntryKind::Helix ? 2.0 * cnc.helix_radius.value_or(0.5 * r) : 0.0;
  if (helix > room) {
    throw GeometryError(
        ErrorLocation{"slab.spacing"},
        fmt::format("slab.spacing = {:.6g}: a helix entry of radius {:.6g} beside a piece needs "
                    "at least {:.6g} between pieces (the tool's diameter, the helix's, the "
                    "finishing allowance); space the pieces wider or enter by plunge or ramp",
                    spacing, 0.5 * helix, spacing - room + helix));
  }
  const double longest =
      std::floor(std::max(0.0, (room - helix) / std::sqrt(2.0)) * M_PI / 2.0 * 100.0) / 100.0;
  if (cnc.lead_in <= longest) return;
  warnings.push_back(fmt::format(
      "cnc.lead_in = {:.6g} shortened to {:.6g} on the slabs: a longer lead arc would reach the next piece, "
      "{:.6g} away (slab.spacing)",
      cnc.lead_in, longest, spacing));
  cnc.lead_in = longest;
}

}  // namespace

std::vector<EdgeKind> top_edge_kinds(const CountertopDesign& design, const Region2& region,
                                     const CompositeCurve& outline) {
  std::vector<bool> wall_segment;
  if (design.kitchen && design.outline.segments.size() == outline.size()) {
    for (const SegmentSpec& s : design.outline.segments) wall_segment.push_back(s.wall);
  }
  return outline_edge_kinds(region, wall_segment);
}

TriangleSoup profiled_mesh(const CountertopDesign& design, const ProfiledPlan& plan, double thickness,
                           double deviation, const BuildContext& context, Result& out) {
  // The rings are the sampled plan eroded exactly; between rings the wall
  // is a chord of the profile's arcs, within the sagitta of them: the
  // profile gets what the loops left of the tolerance (half or more).
  ProfiledSlab slab = build_profiled_slab(plan, design.edges, thickness,
                                          std::max(context.tolerance - deviation, 0.5 * context.tolerance),
                                          design.max_triangles);
  out.max_deviation = std::max(out.max_deviation, deviation + slab.sagitta);
  if (!out.facts.contains("edges")) {
    Facts f;
    f.set("exposed", to_string(design.edges.kind))
        .set("radius", design.edges.radius)
        .set("rings", slab.levels)
        .set("sagitta", slab.sagitta);
    out.facts.set("edges", std::move(f));
  }
  return std::move(slab.mesh);
}

ProfilePasses profile_passes(const CountertopDesign& design, const CncOptions& cnc, double spacing,
                             double deviation, std::vector<std::string>& warnings) {
  ProfilePasses p;
  const ProfileEdges e = profile_edges(design.edges);
  if (e.top <= 0.0) return p;
  p.depth = e.top;
  p.profile = fmt::format("{}, radius {:.6g}", to_string(design.edges.kind), design.edges.radius);
  p.diameter = cnc.tool_diameter;
  int highest = end_mill_number(cnc);
  for (const CncTool& t : cnc.tools) {
    highest = std::max(highest, t.number);
    if (t.type != ToolType::Profile) continue;
    p.tool = t.number;
    p.diameter = t.diameter;
  }
  for (const CountertopHole& h : design.holes) {
    if (h.drill) highest = std::max(highest, h.drill->tool);
  }
  if (p.tool == 0) p.tool = highest + 1;
  const TabOptions& tabs = cnc.tabs;
  if (tabs.count > 0 && p.depth > cnc.depth - tabs.height) {
    throw GeometryError(
        ErrorLocation{"edges.radius"},
        fmt::format(
            "edges.radius = {:.6g}: the profile bit's tip would run {:.6g} below the top, through the "
            "holding tabs ({:.6g} high on a cut {:.6g} deep); lower the tabs (cnc.tabs.height) or take "
            "a smaller radius",
            design.edges.radius, p.depth, tabs.height, cnc.depth));
  }
  // The bit's widest part (its tip's radius plus the round) reaches that far
  // beyond the tool's centre path, which keeps its tip's radius off the piece.
  const double reach = p.diameter + e.top + deviation + cnc.tolerance;
  if (spacing > 0.0 && reach > spacing) {
    throw GeometryError(
        ErrorLocation{"slab.spacing"},
        fmt::format(
            "slab.spacing = {:.6g}: the profile bit (diameter {:.6g} at its tip, {} above it) reaches "
            "{:.6g} from a piece's edge, into its neighbour; space the pieces at least {:.6g} apart",
            spacing, p.diameter, p.profile, reach, std::ceil(reach * 100.0) / 100.0));
  }
  if (e.bottom > 0.0) {
    warnings.push_back(fmt::format(
        "edges: the program profiles the top edges; the bottom edges' round (radius {:.6g}) is cut with the "
        "piece turned over",
        e.bottom));
  }
  return p;
}

std::vector<Facts> tool_facts(const Toolpath& t) {
  std::vector<Facts> tools;
  Facts bit;
  bit.set("number", end_mill_number(t.options))
      .set("type", to_string(ToolType::EndMill))
      .set("diameter", t.options.tool_diameter);
  tools.push_back(std::move(bit));
  for (std::size_t k = 0; k < t.drills.size(); ++k) {
    if (k > 0 && t.drills[k].tool == t.drills[k - 1].tool) continue;
    Facts drill;
    drill.set("number", t.drills[k].tool)
        .set("type", to_string(ToolType::Drill))
        .set("diameter", t.drills[k].diameter);
    tools.push_back(std::move(drill));
  }
  if (!t.profiling.runs.empty()) {
    Facts profile;
    profile.set("number", t.profiling.tool)
        .set("type", to_string(ToolType::Profile))
        .set("diameter", t.profiling.diameter)
        .set("depth", t.profiling.depth)
        .set("runs", t.profiling.runs.size());
    tools.push_back(std::move(profile));
  }
  return tools;
}

KitchenProducts build_kitchen(const CountertopDesign& design, const Region2& region,
                              const CompositeCurve& outline, const std::vector<RegionHole>& holes,
                              const BuildContext& context, Result& out) {
  const KitchenDesign& kitchen = *design.kitchen;
  KitchenProducts k;
  k.stock = kitchen.slab;
  SplitOptions so;
  so.seam_clearance = kitchen.seam_clearance;
  so.deviation = region.max_deviation;
  so.outline = &outline;
  // The exact outline lies within the deviation of the loops: keep the
  // stock's margins and spacing for the exact pieces.
  // Rounded up to a hundredth of the unit, so that positions stay readable.
  const auto widened = [](double v, double by) { return std::ceil((v + by) * 100.0) / 100.0; };
  SlabStock nest_stock = kitchen.slab;
  nest_stock.margin = widened(kitchen.slab.margin, region.max_deviation);
  nest_stock.spacing = widened(kitchen.slab.spacing, 2.0 * region.max_deviation);
  SlabFit fit{nest_stock.length - 2.0 * nest_stock.margin, nest_stock.width - 2.0 * nest_stock.margin,
              nest_stock.grain_along};
  fit.no_inside_corners = design.cnc && design.cnc->options.relief == CornerRelief::None;
  const std::vector<EdgeKind> kinds = top_edge_kinds(design, region, outline);
  k.split =
      kitchen.auto_seams ? auto_split(region, fit, so, kinds) : split_top(region, kitchen.seams, so, kinds);
  if (kitchen.backsplash_height > 0.0) {
    std::vector<std::string> curved;
    std::vector<KitchenPiece> strips =
        backsplash_strips(k.split.pieces, kitchen.backsplash_height, region.max_deviation, curved);
    for (const std::string& c : curved)
      out.warnings.push_back("backsplash: no strip along the curved wall edge of " + c);
    k.split.pieces.insert(k.split.pieces.end(), std::make_move_iterator(strips.begin()),
                          std::make_move_iterator(strips.end()));
  }
  context.watch.lap("seams");
  SlabOptions slab_options;
  slab_options.thickness = design.thickness;
  slab_options.max_edge = design.max_edge;
  slab_options.max_triangles = design.max_triangles;
  std::vector<NestPiece> nest;
  for (const KitchenPiece& piece : k.split.pieces) {
    SlabOptions options = slab_options;
    if (piece.strip) options.thickness = kitchen.backsplash_thickness;
    Part part;
    part.name = piece.name;
    part.role = PartRole::Piece;
    if (design.edges.kind != EdgeProfileKind::Square && !piece.strip) {
      ProfiledPlan plan{piece.outer, {}, piece.holes, piece.name};
      for (const EdgeKind e : piece.edges) plan.exposed.push_back(e == EdgeKind::Exposed);
      part.mesh = profiled_mesh(design, plan, options.thickness, region.max_deviation, context, out);
    } else {
      const SlabMesh slab = build_slab(piece_region(piece, region, k.split.proof), options);
      part.mesh = to_soup(slab.mesh);
      part.proofs.embedding = slab.proof;
      part.proofs.topology = slab.topology;
    }
    out.parts.push_back(std::move(part));
    nest.push_back({piece.name, piece.outer});
  }
  // Each piece's exact shape: its stretches of the exact outline, its seams
  // as exact lines, its cut-outs' exact curves.
  for (const KitchenPiece& piece : k.split.pieces) {
    KitchenProducts::Exact exact;
    try {
      const CompositeCurve boundary =
          piece.strip ? polygon_curve(piece.outer) : exact_piece_outline(piece, outline, region.reversed[0]);
      ExactSolid solid;
      solid.form = ExactSolid::Form::Extrusion;
      solid.height = piece.strip ? kitchen.backsplash_thickness : design.thickness;
      solid.loops.push_back(exact_pieces(boundary));
      if (!piece.strip) {
        solid.edges = design.edges;
        for (const ExactPiece& p : solid.loops.front())
          solid.profiled.push_back(kind_near(piece, p.segment.point(0.5)) == EdgeKind::Exposed);
      }
      for (const std::size_t h : piece.hole_index) solid.loops.push_back(exact_pieces(holes[h].curve));
      exact.solid = std::move(solid);
      if (context.wants_cutting) {
        CutLoopOptions co;
        co.tolerance = context.tolerance;
        co.reverse = !piece.strip && region.reversed[0];
        exact.drawing.push_back(cut_loop(boundary, piece.name, true, co));
        for (const std::size_t h : piece.hole_index) {
          co.reverse = region.reversed[h + 1];
          exact.drawing.push_back(cut_loop(holes[h].curve, holes[h].label, false, co));
        }
      }
    } catch (const GeometryError& e) {
      exact.why_not = fmt::format("{}: {}", piece.name, e.what());
    }
    k.exact.push_back(std::move(exact));
  }
  context.watch.lap("pieces");
  k.nesting = nest_pieces(nest, nest_stock);
  context.watch.lap("nesting");
  if (design.cnc) {
    CncOptions cnc = design.cnc->options;
    cnc.tolerance = context.tolerance;
    limit_entry(cnc, kitchen.slab.spacing, region.max_deviation, out.warnings);
    const ProfilePasses profile =
        profile_passes(design, cnc, kitchen.slab.spacing, region.max_deviation, out.warnings);
    for (std::size_t s = 0; s < k.nesting.slabs; ++s)
      k.slab_toolpaths.push_back(slab_program(k.split, k.nesting, s, cnc, design.holes, profile));
    context.watch.lap("toolpath");
  }
  // Facts: the pieces, the seams and the layout.
  std::vector<Facts> pieces;
  for (std::size_t i = 0; i < k.split.pieces.size(); ++i) {
    const KitchenPiece& piece = k.split.pieces[i];
    const Placement& at = k.nesting.placements[i];
    const std::array<double, 3> lengths = edge_lengths(piece);
    std::vector<double> cutouts;
    for (const std::size_t h : piece.hole_index) cutouts.push_back(static_cast<double>(h));
    Facts f;
    f.set("name", piece.name)
        .set("area", piece.area)
        .set("holes", std::move(cutouts))
        .set("slab", at.slab + 1)
        .set("position", std::vector<double>{at.offset.x(), at.offset.y()})
        .set("rotation_deg", at.rotation_deg)
        .set("exposed_length", lengths[0])
        .set("wall_length", lengths[1])
        .set("seam_length", lengths[2]);
    pieces.push_back(std::move(f));
  }
  std::vector<Facts> seams;
  for (const SeamCut& s : k.split.seams) {
    Facts f;
    f.set("key", s.key)
        .set("from", std::vector<double>{s.from.x(), s.from.y()})
        .set("to", std::vector<double>{s.to.x(), s.to.y()})
        .set("length", (s.to - s.from).norm());
    if (s.clearance < std::numeric_limits<double>::infinity()) f.set("clearance", s.clearance);
    seams.push_back(std::move(f));
  }
  std::vector<Facts> programs;
  for (std::size_t s = 0; s < k.slab_toolpaths.size(); ++s) {
    const Toolpath& t = k.slab_toolpaths[s];
    const ToolpathTotals totals = toolpath_totals(t);
    Facts f;
    f.set("slab", s + 1)
        .set("moves", t.moves.size())
        .set("deviation", t.deviation)
        .set("clearance", t.clearance)
        .set("drills", t.drills.size())
        .set("tools", tool_facts(t))
        .set("cutting_length", totals.cutting)
        .set("estimated_minutes", totals.minutes);
    programs.push_back(std::move(f));
    for (const std::string& w : t.warnings) out.warnings.push_back(fmt::format("slab {}: {}", s + 1, w));
    if (s == 0) append_shares(out.tolerance_shares, "cnc: ", t.tolerance_shares);
  }
  Facts facts;
  facts.set("pieces", std::move(pieces))
      .set("seams", std::move(seams))
      .set("slabs", k.nesting.slabs)
      .set("lower_bound", k.nesting.lower_bound)
      .set("utilisation", k.nesting.utilisation)
      .set("partition", k.split.proof)
      .set("nesting", k.nesting.proof);
  if (!programs.empty()) facts.set("programs", std::move(programs));
  out.facts.set("kitchen", std::move(facts));
  return k;
}

}  // namespace fabmesh
