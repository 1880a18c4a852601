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
    f.fail(
        n, field,
        "a hole is a map with one key: ellipse, rounded_rect, outline or drill (or dxf with its layer), and "
        "optionally its tabs");
  }
  f.require_map(n, field, key_group("countertop.holes[]"));
  if (dxf) {
    for (const char* shape : {"ellipse", "rounded_rect", "outline", "drill"}) {
      if (n[shape].IsDefined())
        f.fail(n[shape], field + "." + shape, fmt::format("a hole with dxf has no {}", shape));
    }
    std::vector<CountertopHole> holes;
    std::vector<CurveSpec> loops = read_dxf_source(f, n, field, common, WallsHere::No);
    for (std::size_t i = 0; i < loops.size(); ++i) {
      CountertopHole hole;
      hole.shape = fmt::format("dxf loop {} of {}", i + 1, loops.size());
      hole.curve = std::move(loops[i]);
      holes.push_back(std::move(hole));
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
  } else if (n["drill"].IsDefined()) {
    const YAML::Node d = n["drill"];
    const std::string df = field + ".drill";
    f.require_map(d, df, key_group("countertop.holes[].drill"));
    HoleDrill drill;
    drill.center = f.point2(f.required(d, "center", df), df + ".center");
    const YAML::Node diameter = f.required(d, "diameter", df);
    drill.diameter = f.number(diameter, df + ".diameter");
    if (!(drill.diameter > 0.0)) {
      f.fail(diameter, df + ".diameter", fmt::format("diameter = {} must be > 0", drill.diameter));
    }
    // The number is checked against cnc.tools once the cnc section is read (resolve_drills).
    if (d["tool"].IsDefined()) drill.tool = static_cast<int>(f.integer(d["tool"], df + ".tool", 1, 999));
    if (n["tabs"].IsDefined()) {
      f.fail(n["tabs"], field + ".tabs",
             "a drilled hole has no tabs: the drill takes its core out in one cycle, with nothing to hold");
    }
    hole.shape = "drill";
    const double r = 0.5 * drill.diameter;
    f.checked(d, df, [&] { hole.curve = ellipse_curve(drill.center, r, r, 0.0); });
    hole.drill = drill;
  } else {
    hole.shape = "outline";
    hole.curve = read_closed_curve(f, n["outline"], field + ".outline", common, WallsHere::No);
  }
  hole.curve.key = field;
  return {hole};
}

// `cnc.tools`: the machine's tool table: numbers given once, at most one end
// mill (the router bit), diameters > 0; with no end mill, number 1 is the
// router bit's.
std::vector<CncTool> read_tools(const yaml::Fields& f, const YAML::Node& list) {
  f.require_list(list, "cnc.tools", 1);
  std::vector<CncTool> tools;
  std::size_t end_mill = list.size();
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string field = fmt::format("cnc.tools[{}]", i);
    const YAML::Node t = list[i];
    f.require_map(t, field, key_group("countertop.cnc.tools[]"));
    CncTool tool;
    const YAML::Node number = f.required(t, "number", field);
    tool.number = static_cast<int>(f.integer(number, field + ".number", 1, 999));
    for (std::size_t j = 0; j < tools.size(); ++j) {
      if (tools[j].number == tool.number) {
        f.fail(number, field + ".number",
               fmt::format("number = {}: cnc.tools[{}] has that number already", tool.number, j));
      }
    }
    const YAML::Node type = f.required(t, "type", field);
    const std::string kind = f.choice(type, field + ".type", {"end_mill", "drill", "profile"});
    tool.type = kind == "drill" ? ToolType::Drill : kind == "profile" ? ToolType::Profile : ToolType::EndMill;
    for (std::size_t j = 0; j < tools.size() && tool.type == ToolType::Profile; ++j) {
      if (tools[j].type == ToolType::Profile)
        f.fail(type, field + ".type", fmt::format("cnc.tools[{}] is the profile bit already", j));
    }
    if (tool.type == ToolType::EndMill && end_mill < list.size()) {
      f.fail(type, field + ".type",
             fmt::format("cnc.tools[{}] is the end mill already: the router cut uses one bit", end_mill));
    }
    if (tool.type == ToolType::EndMill) end_mill = i;
    const YAML::Node diameter = f.required(t, "diameter", field);
    tool.diameter = f.number(diameter, field + ".diameter");
    if (!(tool.diameter > 0.0)) {
      f.fail(diameter, field + ".diameter", fmt::format("diameter = {} must be > 0", tool.diameter));
    }
    tools.push_back(tool);
  }
  if (end_mill == list.size()) {
    for (std::size_t i = 0; i < tools.size(); ++i) {
      if (tools[i].number != 1) continue;
      f.fail(list[i]["number"], fmt::format("cnc.tools[{}].number", i),
             "number = 1: with no end_mill in cnc.tools the router bit is tool 1; list it (type: end_mill) "
             "or number the drill otherwise");
    }
  }
  return tools;
}

// `cnc.drill: {peck, retract, feed, spindle}`: how the tap holes are drilled.
DrillCycle read_drill_cycle(const yaml::Fields& f, const YAML::Node& n, const CncOptions& o) {
  f.require_map(n, "cnc.drill", key_group("countertop.cnc.drill"));
  DrillCycle d;
  d.peck = f.number_or(n, "peck", "cnc.drill.peck", 0.0);
  if (!(d.peck >= 0.0)) f.fail(n["peck"], "cnc.drill.peck", fmt::format("peck = {} must be >= 0", d.peck));
  if (n["retract"].IsDefined()) {
    d.retract = f.number(n["retract"], "cnc.drill.retract");
    if (!(*d.retract > 0.0 && *d.retract <= o.safe_z)) {
      f.fail(n["retract"], "cnc.drill.retract",
             fmt::format("retract = {} must be in (0, {}]: above the top, at most cnc.safe_z", *d.retract,
                         o.safe_z));
    }
  }
  for (const char* key : {"feed", "spindle"}) {
    if (!n[key].IsDefined()) continue;
    const std::string field = std::string("cnc.drill.") + key;
    const double v = f.number(n[key], field);
    if (!(v > 0.0)) f.fail(n[key], field, fmt::format("{} = {} must be > 0", key, v));
    (std::string(key) == "feed" ? d.feed : d.spindle) = v;
  }
  return d;
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
  if (n["tools"].IsDefined()) o.tools = read_tools(f, n["tools"]);
  const auto end_mill = std::find_if(o.tools.begin(), o.tools.end(),
                                     [](const CncTool& t) { return t.type == ToolType::EndMill; });
  o.tool_diameter = length("tool_diameter", o.tool_diameter);
  if (end_mill != o.tools.end()) {
    // The table's end mill is the router bit: its diameter when the design gives none.
    const std::size_t i = static_cast<std::size_t>(end_mill - o.tools.begin());
    if (!n["tool_diameter"].IsDefined()) {
      o.tool_diameter = end_mill->diameter;
    } else if (end_mill->diameter != o.tool_diameter) {
      f.fail(n["tools"][i]["diameter"], fmt::format("cnc.tools[{}].diameter", i),
             fmt::format("diameter = {}: the end mill is the router bit, and cnc.tool_diameter = {}",
                         end_mill->diameter, o.tool_diameter));
    }
  }
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
  if (n["drill"].IsDefined()) o.drill = read_drill_cycle(f, n["drill"], o);
  d.program_units = common.units == "in" ? "in" : "mm";
  if (n["units"].IsDefined()) d.program_units = f.choice(n["units"], "cnc.units", {"mm", "in"});
  if (n["decimals"].IsDefined())
    d.decimals = static_cast<int>(f.integer(n["decimals"], "cnc.decimals", 0, 9));
  o.tolerance = common.tolerance;
  f.checked(n, "cnc", [&] { validate_cnc_options(o); });
  return d;
}

// Each tap hole's drill number, once the cnc section (and its tool table) is
// read: the one given (a drill of cnc.tools, of the hole's diameter), or the
// table's lowest-numbered drill of that diameter, or without a table the
// next number from 2 for each diameter in order of first use.
void resolve_drills(const yaml::Fields& f, const YAML::Node& entries, std::vector<CountertopHole>& holes,
                    const std::vector<std::size_t>& entry_of, const std::optional<CncDesign>& cnc) {
  std::vector<std::pair<double, int>> numbered;  // without a table: diameter -> number
  for (std::size_t k = 0; k < holes.size(); ++k) {
    if (!holes[k].drill) continue;
    HoleDrill& d = *holes[k].drill;
    const YAML::Node node = entries[entry_of[k]]["drill"];
    const std::string field = fmt::format("holes[{}].drill", entry_of[k]);
    if (!cnc) {
      if (d.tool != 0) {
        f.fail(node["tool"], field + ".tool",
               "tool numbers a drill of cnc.tools; the design has no cnc section (a tap hole without one "
               "is a cut-out of the drawings and solids only)");
      }
      continue;
    }
    const std::vector<CncTool>& tools = cnc->options.tools;
    if (tools.empty()) {
      if (d.tool != 0) {
        f.fail(node["tool"], field + ".tool",
               "tool numbers a drill of cnc.tools, and the cnc section gives no tools: list them there, or "
               "leave the number out (each drill diameter gets the next from 2)");
      }
      auto it = std::find_if(numbered.begin(), numbered.end(),
                             [&](const std::pair<double, int>& e) { return e.first == d.diameter; });
      if (it == numbered.end()) {
        numbered.emplace_back(d.diameter, static_cast<int>(numbered.size()) + 2);
        it = numbered.end() - 1;
      }
      d.tool = it->second;
      continue;
    }
    std::string drills;
    for (const CncTool& t : tools) {
      if (t.type == ToolType::Drill)
        drills += fmt::format("{}T{} {}", drills.empty() ? "" : ", ", t.number, t.diameter);
    }
    if (drills.empty()) drills = "none";
    if (d.tool != 0) {
      const auto t =
          std::find_if(tools.begin(), tools.end(), [&](const CncTool& c) { return c.number == d.tool; });
      if (t == tools.end()) {
        f.fail(node["tool"], field + ".tool",
               fmt::format("tool = {}: cnc.tools has no tool {} (drills: {})", d.tool, d.tool, drills));
      }
      if (t->type != ToolType::Drill) {
        f.fail(node["tool"], field + ".tool",
               fmt::format("tool = {}: tool {} is the {}, not a drill", d.tool, d.tool,
                           t->type == ToolType::Profile ? "profile bit" : "end mill, the router bit"));
      }
      if (t->diameter > d.diameter) {
        f.fail(node["tool"], field + ".tool",
               fmt::format("tool = {}: a drill of diameter {}, larger than the hole it drills ({})", d.tool,
                           t->diameter, d.diameter));
      }
      if (t->diameter < d.diameter) {
        f.fail(
            node["tool"], field + ".tool",
            fmt::format("tool = {}: a drill of diameter {}, smaller than the hole ({}): the hole would come "
                        "out {}",
                        d.tool, t->diameter, d.diameter, t->diameter));
      }
      continue;
    }
    for (const CncTool& t : tools) {
      if (t.type == ToolType::Drill && t.diameter == d.diameter && (d.tool == 0 || t.number < d.tool))
        d.tool = t.number;
    }
    if (d.tool == 0) {
      f.fail(node["diameter"], field + ".diameter",
             fmt::format("diameter = {}: cnc.tools has no drill of that diameter (drills: {}); add one, or "
                         "give the hole a drill's diameter",
                         d.diameter, drills));
    }
  }
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

// The exposed edges' profile (key `edges`): the kind, and its radius,
// defaulting to what shops cut (eased 3 mm, bevel 6 mm, the bullnoses half
// the thickness), at most what the thickness holds.
EdgeProfile read_edges(const yaml::Fields& f, const YAML::Node& root, const DesignCommon& common,
                       double thickness, bool refined) {
  const YAML::Node e = root["edges"];
  f.require_map(e, "edges", key_group("countertop.edges"));
  EdgeProfile p;
  const std::string kind = f.choice(f.required(e, "exposed", "edges"), "edges.exposed",
                                    {"square", "eased", "half_bullnose", "bullnose", "bevel"});
  for (const EdgeProfileKind k :
       {EdgeProfileKind::Square, EdgeProfileKind::Eased, EdgeProfileKind::HalfBullnose,
        EdgeProfileKind::Bullnose, EdgeProfileKind::Bevel}) {
    if (kind == to_string(k)) p.kind = k;
  }
  const double mm_per_unit = millimetres_per_unit(common.units);
  const double fallback = p.kind == EdgeProfileKind::Eased   ? 3.0 / mm_per_unit
                          : p.kind == EdgeProfileKind::Bevel ? std::min(6.0 / mm_per_unit, thickness)
                                                             : max_profile_radius(p.kind, thickness);
  p.radius = f.number_or(e, "radius", "edges.radius", fallback);
  if (p.kind == EdgeProfileKind::Square) {
    if (e["radius"].IsDefined()) f.fail(e["radius"], "edges.radius", "a square edge has no radius");
    p.radius = 0.0;
    return p;
  }
  const double most = max_profile_radius(p.kind, thickness);
  if (!(p.radius > 0.0) || p.radius > most) {
    f.fail(e["radius"].IsDefined() ? e["radius"] : e, "edges.radius",
           fmt::format("radius = {} must be > 0 and at most {} for a {} edge on a top {} thick{}", p.radius,
                       most, kind, thickness,
                       most < thickness ? " (its top and bottom rounds may meet, not cross)" : ""));
  }
  if (refined) {
    f.fail(root["max_edge"], "max_edge",
           fmt::format("max_edge refines the faces of a square-edged slab; a top with {} edges is meshed "
                       "from its profile's rings and is not refined: leave max_edge out",
                       kind));
  }
  return p;
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
  if (root["edges"].IsDefined()) d.edges = read_edges(f, root, common, d.thickness, d.max_edge > 0.0);
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
  resolve_drills(f, root["holes"], d.holes, entry_of, d.cnc);
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
