#include "io/design/yaml/read_countertop.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "geometry/curves/shapes.h"
#include "geometry/section/simple_polygon.h"
#include "io/design/dxf_loops.h"
#include "io/design/yaml/read_curve.h"

namespace fabmesh {
namespace {

// Where a DXF source is read: whether its `walls` layer may mark wall edges.
enum class WallsHere { No, OutlineWithoutSlab, Kitchen };

// The loops of `{dxf: FILE, layer: NAME, max_gap: G, walls: LAYER}` (a map
// with a `dxf` key, the file relative to the design's folder), keyed at `field`.
std::vector<CurveSpec> read_dxf_source(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                                       const DesignCommon& common, WallsHere walls) {
  const YAML::Node file = n["dxf"];
  const std::filesystem::path name = f.text(file, field + ".dxf");
  const std::filesystem::path path =
      name.is_absolute() ? name : std::filesystem::path(f.path()).parent_path() / name;
  DxfLoopQuery query;
  query.layer = f.text_or(n, "layer", field + ".layer", "");
  query.max_gap = f.number_or(n, "max_gap", field + ".max_gap", common.tolerance);
  if (query.max_gap < 0.0)
    f.fail(n["max_gap"], field + ".max_gap", fmt::format("max_gap = {} must be >= 0", query.max_gap));
  query.units = common.units;
  if (n["walls"].IsDefined() && walls != WallsHere::Kitchen) {
    f.fail(n["walls"], field + ".walls",
           walls == WallsHere::No
               ? "walls mark the wall edges of a countertop's outline, not of a cut-out"
               : "walls mark the edges of a kitchen's pieces: the design needs a slab ({length, "
                 "width})");
  }
  // A kitchen's template marks its walls on layer WALLS unless it says another.
  if (walls == WallsHere::Kitchen) {
    query.walls = f.text_or(n, "walls", field + ".walls", "WALLS");
    query.walls_required = n["walls"].IsDefined();
    if (query.walls.empty()) f.fail(n["walls"], field + ".walls", "walls names a layer: it is empty");
  }
  DxfLoops loops;
  f.input(path.string());
  f.checked(file, field + ".dxf", [&] { loops = read_dxf_loops(path.string(), query); });
  for (std::string& note : loops.notes) {
    // A drawing read for the outline and again for the holes says its units once.
    const auto& seen = f.notes();
    if (std::find(seen.begin(), seen.end(), note) == seen.end()) f.note(std::move(note));
  }
  std::vector<CurveSpec> curves;
  for (DxfLoop& loop : loops.loops) {
    loop.curve.key = field;
    for (SegmentSpec& s : loop.curve.segments) s.key = field;
    curves.push_back(std::move(loop.curve));
  }
  return curves;
}

// One closed curve: a curve map, or the one loop of a DXF source.
CurveSpec read_closed_curve(const yaml::Fields& f, const YAML::Node& node, const std::string& field,
                            const DesignCommon& common, WallsHere walls) {
  if (node.IsMap() && node["dxf"].IsDefined()) {
    f.require_map(node, field, key_group("dxf_outline"));
    std::vector<CurveSpec> loops = read_dxf_source(f, node, field, common, walls);
    if (loops.size() != 1) {
      f.fail(node["dxf"], field + ".dxf",
             fmt::format("{} closed loops found{}; {} is one loop (holes take a layer of many)", loops.size(),
                         node["layer"].IsDefined() ? " on the layer" : "", field));
    }
    return std::move(loops.front());
  }
  CurveSpec spec = read_curve(f, node, field);
  if (!spec.closed)
    f.fail(node, field + ".closed", fmt::format("{} must be a closed curve (closed: true)", field));
  return spec;
}

// One entry of `holes`: one hole, or every loop of a DXF layer.
std::vector<CountertopHole> read_hole(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                                      const DesignCommon& common) {
  const bool dxf = n.IsMap() && n["dxf"].IsDefined();
  const std::size_t shape_keys = n.IsMap() ? n.size() - (n["tabs"].IsDefined() ? 1 : 0) : 0;
  if (!n.IsMap() || (!dxf && shape_keys != 1)) {
    f.fail(n, field,
           "a hole is a map with one key: ellipse, rounded_rect or outline (or dxf with its layer), and "
           "optionally its tabs");
  }
  f.require_map(n, field, key_group("countertop.holes[]"));
  if (dxf) {
    for (const char* shape : {"ellipse", "rounded_rect", "outline"}) {
      if (n[shape].IsDefined())
        f.fail(n[shape], field + "." + shape, fmt::format("a hole with dxf has no {}", shape));
    }
    std::vector<CountertopHole> holes;
    std::vector<CurveSpec> loops = read_dxf_source(f, n, field, common, WallsHere::No);
    for (std::size_t i = 0; i < loops.size(); ++i) {
      holes.push_back({fmt::format("dxf loop {} of {}", i + 1, loops.size()), std::move(loops[i])});
    }
    return holes;
  }
  CountertopHole hole;
  if (n["ellipse"].IsDefined()) {
    const YAML::Node e = n["ellipse"];
    const std::string ef = field + ".ellipse";
    f.require_map(e, ef, key_group("countertop.holes[].ellipse"));
    const Vec2 c = f.point2(f.required(e, "center", ef), ef + ".center");
    const double a = f.number(f.required(e, "a", ef), ef + ".a");
    const double b = f.number(f.required(e, "b", ef), ef + ".b");
    const double rot = f.number_or(e, "rotation_deg", ef + ".rotation_deg", 0.0);
    hole.shape = "ellipse";
    f.checked(e, ef, [&] { hole.curve = ellipse_curve(c, a, b, rot); });
  } else if (n["rounded_rect"].IsDefined()) {
    const YAML::Node r = n["rounded_rect"];
    const std::string rf = field + ".rounded_rect";
    f.require_map(r, rf, key_group("countertop.holes[].rounded_rect"));
    const Vec2 c = f.point2(f.required(r, "center", rf), rf + ".center");
    const Vec2 size = f.point2(f.required(r, "size", rf), rf + ".size");
    const double radius = f.number(f.required(r, "radius", rf), rf + ".radius");
    const double rot = f.number_or(r, "rotation_deg", rf + ".rotation_deg", 0.0);
    hole.shape = "rounded_rect";
    f.checked(r, rf, [&] { hole.curve = rounded_rect_curve(c, size.x(), size.y(), radius, rot); });
  } else {
    hole.shape = "outline";
    hole.curve = read_closed_curve(f, n["outline"], field + ".outline", common, WallsHere::No);
  }
  hole.curve.key = field;
  return {hole};
}

CncDesign read_cnc(const yaml::Fields& f, const YAML::Node& n, const DesignCommon& common, double thickness) {
  f.require_map(n, "cnc", key_group("countertop.cnc"));
  // The defaults are in millimetres: divided (not multiplied by a rounded 1/10) so that
  // 6 mm is 0.6 cm, not 0.6000000000000001.
  const double mm_per_unit = millimetres_per_unit(common.units);
  CncDesign d;
  CncOptions& o = d.options;
  auto length = [&](const char* key, double fallback_mm) {
    return f.number_or(n, key, std::string("cnc.") + key, fallback_mm / mm_per_unit);
  };
  o.tool_diameter = length("tool_diameter", o.tool_diameter);
  o.depth = f.number_or(n, "depth", "cnc.depth", thickness);
  o.breakthrough = length("breakthrough", o.breakthrough);
  o.step_down = length("step_down", o.step_down);
  o.feed = length("feed", o.feed);
  o.plunge = length("plunge", o.plunge);
  o.rapid = length("rapid", o.rapid);
  o.spindle = f.number_or(n, "spindle", "cnc.spindle", o.spindle);
  o.safe_z = length("safe_z", o.safe_z);
  o.lead_in = length("lead_in", o.lead_in);
  if (n["tabs"].IsDefined()) {
    const YAML::Node t = n["tabs"];
    f.require_map(t, "cnc.tabs", key_group("countertop.cnc.tabs"));
    if (t["count"].IsDefined())
      o.tabs.count = static_cast<std::size_t>(f.integer(t["count"], "cnc.tabs.count", 0, 1000));
    o.tabs.width = f.number_or(t, "width", "cnc.tabs.width", o.tabs.width / mm_per_unit);
    o.tabs.height = f.number_or(t, "height", "cnc.tabs.height", o.tabs.height / mm_per_unit);
    if (t["min_radius"].IsDefined()) o.tabs.min_radius = f.number(t["min_radius"], "cnc.tabs.min_radius");
  } else {
    o.tabs.width /= mm_per_unit;
    o.tabs.height /= mm_per_unit;
  }
  if (n["entry"].IsDefined()) {
    const std::string entry = f.choice(n["entry"], "cnc.entry", {"plunge", "ramp", "helix"});
    o.entry = entry == "ramp" ? EntryKind::Ramp : entry == "helix" ? EntryKind::Helix : EntryKind::Plunge;
  }
  if (n["ramp_angle"].IsDefined()) {
    if (o.entry == EntryKind::Plunge)
      f.fail(n["ramp_angle"], "cnc.ramp_angle", "ramp_angle applies to entry: ramp or entry: helix");
    o.ramp_angle_deg = f.number(n["ramp_angle"], "cnc.ramp_angle");
    if (!(o.ramp_angle_deg > 0.0 && o.ramp_angle_deg <= 45.0)) {
      f.fail(n["ramp_angle"], "cnc.ramp_angle",
             fmt::format("ramp_angle = {} must be in (0, 45] degrees", o.ramp_angle_deg));
    }
  }
  if (n["helix_radius"].IsDefined()) {
    if (o.entry != EntryKind::Helix)
      f.fail(n["helix_radius"], "cnc.helix_radius", "helix_radius applies to entry: helix");
    o.helix_radius = f.number(n["helix_radius"], "cnc.helix_radius");
    if (!(*o.helix_radius > 0.0 && *o.helix_radius <= 0.5 * o.tool_diameter)) {
      f.fail(n["helix_radius"], "cnc.helix_radius",
             fmt::format("helix_radius = {} must be in (0, {}], at most the tool radius", *o.helix_radius,
                         0.5 * o.tool_diameter));
    }
  }
  o.arc_fit = f.boolean_or(n, "arc_fit", "cnc.arc_fit", o.arc_fit);
  if (n["finish"].IsDefined()) {
    o.finish = f.number(n["finish"], "cnc.finish");
    if (!(o.finish >= 0.0 && o.finish < 0.5 * o.tool_diameter)) {
      f.fail(n["finish"], "cnc.finish",
             fmt::format("finish = {} must be in [0, {}), below the tool radius", o.finish,
                         0.5 * o.tool_diameter));
    }
  }
  if (n["direction"].IsDefined()) {
    o.direction = f.choice(n["direction"], "cnc.direction", {"climb", "conventional"}) == "conventional"
                      ? CutDirection::Conventional
                      : CutDirection::Climb;
  }
  if (n["relief"].IsDefined()) {
    o.relief = f.choice(n["relief"], "cnc.relief", {"none", "dogbone"}) == "dogbone" ? CornerRelief::Dogbone
                                                                                     : CornerRelief::None;
  }
  if (n["min_web"].IsDefined()) o.min_web = f.number(n["min_web"], "cnc.min_web");
  d.program_units = common.units == "in" ? "in" : "mm";
  if (n["units"].IsDefined()) d.program_units = f.choice(n["units"], "cnc.units", {"mm", "in"});
  if (n["decimals"].IsDefined())
    d.decimals = static_cast<int>(f.integer(n["decimals"], "cnc.decimals", 0, 9));
  o.tolerance = common.tolerance;
  f.checked(n, "cnc", [&] { validate_cnc_options(o); });
  return d;
}

// A hole entry's `tabs` ({count, width, height, min_radius}); what it does
// not give comes from the cnc section's tabs.
TabOptions read_hole_tabs(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                          const std::optional<CncDesign>& cnc) {
  f.require_map(n, field, key_group("countertop.cnc.tabs"));
  if (!cnc) {
    f.fail(n, field,
           fmt::format("{}: tabs hold a cut-out for the router; the design has no cnc section", field));
  }
  const CncOptions& o = cnc->options;
  TabOptions t = o.tabs;
  t.count = static_cast<std::size_t>(f.integer(f.required(n, "count", field), field + ".count", 0, 1000));
  t.width = f.number_or(n, "width", field + ".width", o.tabs.width);
  if (!(t.width > 0.0)) f.fail(n["width"], field + ".width", fmt::format("width = {} must be > 0", t.width));
  t.height = f.number_or(n, "height", field + ".height", o.tabs.height);
  if (!(t.height > 0.0 && t.height < o.depth)) {
    f.fail(n["height"].IsDefined() ? n["height"] : n, field + ".height",
           fmt::format("height = {} must be in (0, {}), below the depth of cut", t.height, o.depth));
  }
  if (n["min_radius"].IsDefined()) {
    t.min_radius = f.number(n["min_radius"], field + ".min_radius");
    if (!(*t.min_radius > 0.0)) {
      f.fail(n["min_radius"], field + ".min_radius",
             fmt::format("min_radius = {} must be > 0", *t.min_radius));
    }
  }
  return t;
}

// `slab: {length, width, margin, spacing, grain, defects}`, `seams`, `seam_clearance`.
KitchenDesign read_kitchen(const yaml::Fields& f, const YAML::Node& root, const DesignCommon& common,
                           const std::optional<CncDesign>& cnc, double thickness, bool has_wall) {
  const double mm_per_unit = millimetres_per_unit(common.units);
  const YAML::Node n = root["slab"];
  f.require_map(n, "slab", key_group("countertop.slab"));
  KitchenDesign k;
  SlabStock& s = k.slab;
  auto positive = [&](const char* key) {
    const std::string field = std::string("slab.") + key;
    const YAML::Node v = f.required(n, key, "slab");
    const double x = f.number(v, field);
    if (!(x > 0.0)) f.fail(v, field, fmt::format("{} = {} must be > 0", key, x));
    return x;
  };
  s.length = positive("length");
  s.width = positive("width");
  s.margin = f.number_or(n, "margin", "slab.margin", 0.0);
  if (!(s.margin >= 0.0))
    f.fail(n["margin"], "slab.margin", fmt::format("margin = {} must be >= 0", s.margin));
  if (!(2.0 * s.margin < std::min(s.length, s.width))) {
    f.fail(n["margin"], "slab.margin",
           fmt::format("margin = {} leaves no usable area on a {} x {} slab", s.margin, s.length, s.width));
  }
  const double tool = cnc ? cnc->options.tool_diameter : 0.0;
  s.spacing = f.number_or(n, "spacing", "slab.spacing", std::max(tool, 10.0 / mm_per_unit));
  if (!(s.spacing >= tool && s.spacing >= 0.0)) {
    f.fail(n["spacing"], "slab.spacing",
           fmt::format("spacing = {} must be at least the router bit's diameter ({}): the bit cuts between "
                       "the pieces",
                       s.spacing, tool));
  }
  if (n["grain"].IsDefined()) s.grain_along = f.choice(n["grain"], "slab.grain", {"along", "any"}) == "along";
  if (n["defects"].IsDefined()) {
    const YAML::Node list = n["defects"];
    f.require_list(list, "slab.defects");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string field = fmt::format("slab.defects[{}]", i);
      const YAML::Node d = list[i];
      f.require_map(d, field, key_group("countertop.slab.defects[]"));
      if (d.size() != 1)
        f.fail(d, field, "a defect is {circle: {center, radius}} or {polygon: [[x, y], ...]}");
      SlabDefect defect;
      if (d["circle"].IsDefined()) {
        const YAML::Node c = d["circle"];
        f.require_map(c, field + ".circle", key_group("countertop.slab.defects[].circle"));
        defect.center = f.point2(f.required(c, "center", field + ".circle"), field + ".circle.center");
        defect.radius = f.number(f.required(c, "radius", field + ".circle"), field + ".circle.radius");
        if (!(defect.radius > 0.0)) {
          f.fail(c["radius"], field + ".circle.radius",
                 fmt::format("radius = {} must be > 0", defect.radius));
        }
      } else {
        defect.polygon = f.points2(d["polygon"], field + ".polygon", 3);
        if (find_crossing(defect.polygon, true)) {
          f.fail(d["polygon"], field + ".polygon", "the defect's polygon crosses itself");
        }
        if (signed_area2(defect.polygon) < 0.0) std::reverse(defect.polygon.begin(), defect.polygon.end());
      }
      s.defects.push_back(std::move(defect));
    }
  }
  k.seam_clearance = f.number_or(root, "seam_clearance", "seam_clearance", 100.0 / mm_per_unit);
  if (!(k.seam_clearance >= 0.0)) {
    f.fail(root["seam_clearance"], "seam_clearance",
           fmt::format("seam_clearance = {} must be >= 0", k.seam_clearance));
  }
  if (root["seams"].IsDefined()) {
    const YAML::Node seams = root["seams"];
    if (seams.IsScalar()) {
      if (f.choice(seams, "seams", {"auto"}) == "auto") k.auto_seams = true;
    } else {
      f.require_list(seams, "seams");
      for (std::size_t i = 0; i < seams.size(); ++i) {
        const std::string field = fmt::format("seams[{}]", i);
        f.require_map(seams[i], field, key_group("countertop.seams[]"));
        SeamSpec seam;
        seam.at = f.point2(f.required(seams[i], "at", field), field + ".at");
        const YAML::Node dir = f.required(seams[i], "direction", field);
        seam.direction = f.point2(dir, field + ".direction");
        if (!(seam.direction.norm() > 0.0))
          f.fail(dir, field + ".direction", "direction must be a non-zero vector [dx, dy]");
        seam.key = field;
        k.seams.push_back(std::move(seam));
      }
    }
  }
  if (root["backsplash"].IsDefined()) {
    const YAML::Node b = root["backsplash"];
    f.require_map(b, "backsplash", key_group("countertop.backsplash"));
    const YAML::Node h = f.required(b, "height", "backsplash");
    k.backsplash_height = f.number(h, "backsplash.height");
    if (!(k.backsplash_height > 0.0))
      f.fail(h, "backsplash.height", fmt::format("height = {} must be > 0", k.backsplash_height));
    k.backsplash_thickness = f.number_or(b, "thickness", "backsplash.thickness", thickness);
    if (!(k.backsplash_thickness > 0.0)) {
      f.fail(b["thickness"], "backsplash.thickness",
             fmt::format("thickness = {} must be > 0", k.backsplash_thickness));
    }
    if (!has_wall) {
      f.fail(b, "backsplash",
             "backsplash strips stand on the outline's wall edges: mark the segments along a wall with "
             "edge: wall");
    }
  }
  return k;
}

}  // namespace

CountertopDesign read_countertop(const yaml::Fields& f, const YAML::Node& root, const DesignCommon& common) {
  CountertopDesign d;
  d.outline =
      read_closed_curve(f, f.required(root, "outline", "outline"), "outline", common,
                        root["slab"].IsDefined() ? WallsHere::Kitchen : WallsHere::OutlineWithoutSlab);
  std::vector<std::size_t> entry_of;  // the `holes` entry each hole comes from
  if (root["holes"].IsDefined()) {
    const YAML::Node holes = root["holes"];
    f.require_list(holes, "holes");
    for (std::size_t i = 0; i < holes.size(); ++i) {
      for (CountertopHole& h : read_hole(f, holes[i], fmt::format("holes[{}]", i), common)) {
        d.holes.push_back(std::move(h));
        entry_of.push_back(i);
      }
    }
  }
  const YAML::Node thickness = f.required(root, "thickness", "thickness");
  d.thickness = f.number(thickness, "thickness");
  if (d.thickness <= 0.0)
    f.fail(thickness, "thickness", fmt::format("thickness = {} must be > 0", d.thickness));
  if (root["max_edge"].IsDefined()) {
    d.max_edge = f.number(root["max_edge"], "max_edge");
    if (d.max_edge <= 0.0)
      f.fail(root["max_edge"], "max_edge", fmt::format("max_edge = {} must be > 0", d.max_edge));
  }
  d.max_triangles = f.budget_or(root, "max_triangles", d.max_triangles);
  if (root["cnc"].IsDefined()) d.cnc = read_cnc(f, root["cnc"], common, d.thickness);
  // Tabs on cut-outs, once the cnc section's tabs give their defaults.
  for (std::size_t k = 0; k < d.holes.size(); ++k) {
    const YAML::Node entry = root["holes"][entry_of[k]];
    if (!entry["tabs"].IsDefined()) continue;
    d.holes[k].tabs = read_hole_tabs(f, entry["tabs"], fmt::format("holes[{}].tabs", entry_of[k]), d.cnc);
  }
  if (d.cnc) {
    for (const CountertopHole& h : d.holes) d.cnc->options.hole_tabs.push_back(h.tabs);
  }
  if (root["slab"].IsDefined()) {
    const bool has_wall = std::any_of(d.outline.segments.begin(), d.outline.segments.end(),
                                      [](const SegmentSpec& s) { return s.wall; });
    d.kitchen = read_kitchen(f, root, common, d.cnc, d.thickness, has_wall);
  } else {
    for (const SegmentSpec& s : d.outline.segments) {
      if (s.wall) {
        f.fail(root["outline"], s.key + ".edge",
               "edge: wall marks the edges of a kitchen's pieces: the design needs a slab ({length, width})");
      }
    }
    for (const char* key : {"seams", "seam_clearance", "backsplash"}) {
      if (root[key].IsDefined()) {
        f.fail(root[key], key,
               fmt::format("{} cuts the top to fit a stone slab: the design needs a slab ({{length, width}})",
                           key));
      }
    }
  }
  return d;
}

}  // namespace fabmesh
