#include "io/design/schema.h"

#include <stdexcept>

namespace fabmesh {
namespace {

std::vector<std::string> with_common(std::vector<std::string> keys) {
  std::vector<std::string> all{"name",       "kind",           "units",        "tolerance",
                               "outputs",    "export_units",   "purpose",      "on_output_error",
                               "parameters", "parameter_sets", "parameter_set"};
  all.insert(all.end(), keys.begin(), keys.end());
  return all;
}

std::vector<KeyGroup> make_groups() {
  return {
      {"common", with_common({})},
      {"parameters.NAME", {"value", "min", "max", "step", "choices", "description"}},
      // Kinds (the root map of a design file).
      {"curve", with_common({"curve"})},
      {"vessel", with_common({"profile", "body", "max_triangles", "shrinkage", "mould", "print", "case"})},
      {"countertop", with_common({"outline", "holes", "thickness", "max_edge", "max_triangles", "cnc", "slab",
                                  "seams", "seam_clearance", "backsplash", "edges"})},
      {"surface", with_common({"patches", "thickness", "thicken", "max_triangles"})},
      // Vessels.
      {"vessel.body", {"mode", "wall", "base", "rim"}},
      {"vessel.mould",
       {"parts", "wall", "spare", "spare_shape", "spare_taper_deg", "block", "block_radius", "base_part",
        "base_height", "keys", "key_radius", "key_clearance", "key_margin", "key_positions",
        "allow_undercuts", "plaster_ratio", "plaster_density", "slip_density"}},
      {"vessel.shrinkage", {"wet", "fired"}},
      {"vessel.case", {"wall", "clearance", "draft_deg"}},
      {"vessel.print", {"bed", "max_overhang_deg", "min_wall", "strict", "pin_diameter", "pin_clearance"}},
      // Countertops.
      {"countertop.holes[]",
       {"ellipse", "rounded_rect", "outline", "drill", "dxf", "layer", "max_gap", "tabs"}},
      {"countertop.holes[].ellipse", {"center", "a", "b", "rotation_deg"}},
      {"countertop.holes[].rounded_rect", {"center", "size", "radius", "rotation_deg"}},
      {"countertop.holes[].drill", {"center", "diameter", "tool"}},
      {"countertop.cnc", {"tool_diameter", "depth",        "breakthrough", "step_down", "feed",      "plunge",
                          "rapid",         "spindle",      "safe_z",       "lead_in",   "tabs",      "entry",
                          "ramp_angle",    "helix_radius", "arc_fit",      "finish",    "direction", "relief",
                          "min_web",       "units",        "decimals",     "tools",     "drill"}},
      {"countertop.cnc.tabs", {"count", "width", "height", "min_radius"}},
      {"countertop.cnc.tools[]", {"number", "type", "diameter"}},
      {"countertop.cnc.drill", {"peck", "retract", "feed", "spindle"}},
      {"countertop.slab", {"length", "width", "margin", "spacing", "grain", "defects"}},
      {"countertop.slab.defects[]", {"circle", "polygon"}},
      {"countertop.slab.defects[].circle", {"center", "radius"}},
      {"countertop.seams[]", {"at", "direction"}},
      {"countertop.backsplash", {"height", "thickness"}},
      {"countertop.edges", {"exposed", "radius"}},
      // Loops from a DXF drawing (an outline, or an outline hole).
      {"dxf_outline", {"dxf", "layer", "max_gap", "walls"}},
      // Surfaces.
      {"surface.patches[]", {"name", "u", "v", "points", "join"}},
      {"surface.patches[].u", {"alpha", "lambda", "mu"}},
      {"surface.patches[].join", {"to", "side", "continuity", "gamma", "k", "m"}},
      // Curves (under curve, profile, outline and holes[].outline).
      {"curve.quasi_bspline", {"family", "points", "through", "lambdas", "fair"}},
      {"curve.composite", {"family", "closed", "segments", "fair", "fair_keeps", "closing"}},
      {"curve.closing", {"continuity"}},
      {"segment.cubic", {"points", "lambda", "mu", "alpha", "join", "continuity", "family", "edge"}},
      {"segment.join.tbezier", {"continuity", "alpha", "beta"}},
      {"segment.join.hbezier", {"continuity", "k", "m"}},
      {"segment.line", {"line", "continuity", "edge"}},
      {"segment.line.line", {"from", "to"}},
      {"segment.ellipse_arc", {"ellipse_arc", "continuity", "edge"}},
      {"segment.ellipse_arc.ellipse_arc", {"center", "a", "b", "rotation_deg", "from_deg", "to_deg"}},
      {"segment.circle_arc", {"circle_arc", "continuity", "edge"}},
      {"segment.circle_arc.circle_arc", {"center", "radius", "from_deg", "to_deg"}},
      {"segment.polyline", {"polyline", "continuity", "edge"}},
      {"segment.polyline.file", {"file"}},
  };
}

}  // namespace

const std::vector<KeyGroup>& design_key_groups() {
  static const std::vector<KeyGroup> groups = make_groups();
  return groups;
}

const KeyGroup& key_group(std::string_view name) {
  for (const KeyGroup& g : design_key_groups()) {
    if (g.name == name) return g;
  }
  throw std::logic_error("design schema: no key group '" + std::string(name) + "'");
}

}  // namespace fabmesh
