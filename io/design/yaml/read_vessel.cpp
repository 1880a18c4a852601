#include "io/design/yaml/read_vessel.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/mould/mould_section.h"
#include "geometry/mould/release.h"
#include "io/design/yaml/design_tree.h"
#include "io/design/yaml/read_curve.h"

namespace fabmesh {

namespace {

MouldOptions read_mould(const yaml::Fields& f, const YAML::Node& m, const DesignCommon& common,
                        const VesselDesign& v) {
  f.require_map(m, "mould", key_group("vessel.mould"));
  // The defaults are in millimetres: divided (not multiplied by a rounded 1/10) so that
  // 6 mm is 0.6 cm, not 0.6000000000000001.
  const double mm_per_unit = millimetres_per_unit(common.units);
  MouldOptions o;
  auto length = [&](const char* key, double fallback_mm) {
    return f.number_or(m, key, std::string("mould.") + key, fallback_mm / mm_per_unit);
  };
  if (m["parts"].IsDefined()) o.parts = static_cast<int>(f.integer(m["parts"], "mould.parts", 2, 3));
  o.wall = length("wall", o.wall);
  o.spare = length("spare", o.spare);
  if (m["spare_shape"].IsDefined()) {
    o.spare_shape = f.choice(m["spare_shape"], "mould.spare_shape", {"cylinder", "cone"}) == "cone"
                        ? SpareShape::Cone
                        : SpareShape::Cylinder;
  }
  o.spare_taper_deg = f.number_or(m, "spare_taper_deg", "mould.spare_taper_deg", o.spare_taper_deg);
  if (m["block"].IsDefined()) {
    o.block = f.choice(m["block"], "mould.block", {"cylinder", "box"}) == "box" ? BlockShape::Box
                                                                                : BlockShape::Cylinder;
  }
  o.block_radius = f.number_or(m, "block_radius", "mould.block_radius", 0.0);
  o.base_part = f.boolean_or(m, "base_part", "mould.base_part", false);
  o.base_height = f.number_or(m, "base_height", "mould.base_height", 0.0);
  if (m["keys"].IsDefined()) o.keys = static_cast<int>(f.integer(m["keys"], "mould.keys", 0, 64));
  o.key_radius = length("key_radius", o.key_radius);
  // The default clearance lets the keys release for every `parts`: 0.2 mm, or with 3 parts (pulled
  // 30 degrees off the keys' axes) the least that releases, rounded up to a hundredth of a millimetre.
  double clearance_mm = o.key_clearance;
  const double release_mm = o.key_radius * mm_per_unit * (1.0 / std::cos(key_pull_angle(o.parts)) - 1.0);
  if (release_mm > clearance_mm) clearance_mm = std::ceil(release_mm * 100.0) / 100.0;
  o.key_clearance = length("key_clearance", clearance_mm);
  o.key_margin = f.number_or(m, "key_margin", "mould.key_margin", 0.0);
  if (m["key_positions"].IsDefined()) o.key_positions = f.points2(m["key_positions"], "mould.key_positions");
  o.allow_undercuts = f.boolean_or(m, "allow_undercuts", "mould.allow_undercuts", false);
  o.shrinkage = v.shrinkage;
  o.tolerance = common.tolerance;
  o.max_triangles = v.max_triangles;
  f.checked(m, "mould", [&] { check_mould_options(o); });
  return o;
}

// A density or ratio of the mould's materials: a number > 0, or the default.
double positive_or(const yaml::Fields& f, const YAML::Node& m, const char* key, double fallback) {
  const double v = f.number_or(m, key, std::string("mould.") + key, fallback);
  if (!(v > 0.0)) f.fail(m[key], std::string("mould.") + key, fmt::format("{} = {} must be > 0", key, v));
  return v;
}

// `shrinkage: 0.12`, or a test bar's lengths `shrinkage: {wet: 100, fired: 88}`.
void read_shrinkage(const yaml::Fields& f, const YAML::Node& n, VesselDesign& v) {
  if (n.IsMap()) {
    f.require_map(n, "shrinkage", key_group("vessel.shrinkage"));
    const YAML::Node wet = f.required(n, "wet", "shrinkage");
    const YAML::Node fired = f.required(n, "fired", "shrinkage");
    v.shrinkage_wet = f.number(wet, "shrinkage.wet");
    v.shrinkage_fired = f.number(fired, "shrinkage.fired");
    if (!(v.shrinkage_wet > 0.0))
      f.fail(wet, "shrinkage.wet",
             fmt::format("wet = {} must be > 0 (the bar's length before firing)", wet.Scalar()));
    if (!(v.shrinkage_fired > 0.0) || v.shrinkage_fired > v.shrinkage_wet) {
      f.fail(fired, "shrinkage.fired",
             fmt::format("fired = {} must be in (0, wet = {}]: the bar's length after firing", fired.Scalar(),
                         wet.Scalar()));
    }
    v.shrinkage = 1.0 - v.shrinkage_fired / v.shrinkage_wet;
    return;
  }
  v.shrinkage = f.number(n, "shrinkage");
  if (v.shrinkage < 0.0 || v.shrinkage >= 1.0) {
    f.fail(n, "shrinkage", fmt::format("shrinkage = {} must be in [0, 1) (0.12 for 12 %)", n.Scalar()));
  }
}

// `case: {wall, clearance, draft_deg}`: the casting cases' wall and pins'
// clearance, in model units (5 and 0.2 mm by default), and their draft (1 degree).
CaseOptions read_case(const yaml::Fields& f, const YAML::Node& n, const DesignCommon& common) {
  f.require_map(n, "case", key_group("vessel.case"));
  CaseOptions o;
  o.wall = f.number_or(n, "wall", "case.wall", o.wall / millimetres_per_unit(common.units));
  if (!(o.wall > 0.0)) f.fail(n["wall"], "case.wall", fmt::format("wall = {} must be > 0", o.wall));
  o.clearance =
      f.number_or(n, "clearance", "case.clearance", o.clearance / millimetres_per_unit(common.units));
  if (!(o.clearance >= 0.0) || !(o.clearance < o.wall / 4.0)) {
    f.fail(n["clearance"].IsDefined() ? n["clearance"] : n["wall"], "case.clearance",
           fmt::format(
               "clearance = {} {} must be at least 0 and below a quarter of case.wall ({} {}): a plate's "
               "pins are a quarter of the wall in radius, and their holes must keep wall all round",
               o.clearance, common.units, o.wall / 4.0, common.units));
  }
  o.draft_deg = f.number_or(n, "draft_deg", "case.draft_deg", o.draft_deg);
  if (!(o.draft_deg >= 0.0 && o.draft_deg <= 10.0)) {
    f.fail(n["draft_deg"], "case.draft_deg",
           fmt::format("draft_deg = {} must be an angle from 0 to 10 degrees (0: the part's free faces do "
                       "not lean)",
                       o.draft_deg));
  }
  return o;
}

// `print: {bed, max_overhang_deg, min_wall, strict, pin_diameter,
// pin_clearance}`: lengths in model units, the millimetre defaults converted.
PrintOptions read_print(const yaml::Fields& f, const YAML::Node& n, const DesignCommon& common) {
  f.require_map(n, "print", key_group("vessel.print"));
  PrintOptions o;
  o.units = common.units;
  o.min_wall = f.number_or(n, "min_wall", "print.min_wall", o.min_wall / millimetres_per_unit(common.units));
  if (!(o.min_wall > 0.0))
    f.fail(n["min_wall"], "print.min_wall", fmt::format("min_wall = {} must be > 0", o.min_wall));
  o.max_overhang_deg = f.number_or(n, "max_overhang_deg", "print.max_overhang_deg", o.max_overhang_deg);
  if (!(o.max_overhang_deg > 0.0 && o.max_overhang_deg < 90.0)) {
    f.fail(
        n["max_overhang_deg"], "print.max_overhang_deg",
        fmt::format("max_overhang_deg = {} must be in (0, 90): degrees from vertical", o.max_overhang_deg));
  }
  if (n["bed"].IsDefined()) {
    if (!n["bed"].IsSequence() || n["bed"].size() != 3)
      f.fail(n["bed"], "print.bed", "expected the printer's build volume [X, Y, Z]");
    o.bed = f.point3(n["bed"], "print.bed");
    if (!(o.bed->minCoeff() > 0.0)) {
      f.fail(n["bed"], "print.bed",
             fmt::format("bed = [{}, {}, {}]: the printer's X, Y and Z must each be > 0", o.bed->x(),
                         o.bed->y(), o.bed->z()));
    }
  }
  o.strict = f.boolean_or(n, "strict", "print.strict", false);
  const double mm = millimetres_per_unit(common.units);
  o.pin_diameter = f.number_or(n, "pin_diameter", "print.pin_diameter", o.pin_diameter / mm);
  if (!(o.pin_diameter > 0.0))
    f.fail(n["pin_diameter"], "print.pin_diameter",
           fmt::format("pin_diameter = {} must be > 0", o.pin_diameter));
  o.pin_clearance = f.number_or(n, "pin_clearance", "print.pin_clearance", o.pin_clearance / mm);
  if (!(o.pin_clearance >= 0.0)) {
    f.fail(n["pin_clearance"], "print.pin_clearance",
           fmt::format("pin_clearance = {} must be >= 0", o.pin_clearance));
  }
  return o;
}

}  // namespace

VesselDesign read_vessel(const yaml::Fields& f, const YAML::Node& root, const DesignCommon& common) {
  VesselDesign v;
  v.profile = read_curve(f, f.required(root, "profile", "profile"), "profile");
  const YAML::Node body = f.required(root, "body", "body");
  f.require_map(body, "body", key_group("vessel.body"));
  const std::string mode = f.choice(f.required(body, "mode", "body"), "body.mode", {"solid", "shell"});
  v.mode = mode == "shell" ? BodyMode::Shell : BodyMode::Solid;
  if (v.mode == BodyMode::Shell) {
    const YAML::Node wall = f.required(body, "wall", "body");
    v.wall = f.number(wall, "body.wall");
    if (v.wall <= 0.0) f.fail(wall, "body.wall", fmt::format("wall = {} must be > 0", v.wall));
    v.base = f.number_or(body, "base", "body.base", v.wall);
    if (v.base <= 0.0) f.fail(body["base"], "body.base", fmt::format("base = {} must be > 0", v.base));
    if (body["rim"].IsDefined()) {
      const std::string rim = f.choice(body["rim"], "body.rim", {"square", "level"});
      v.rim = rim == "level" ? RimCut::Level : RimCut::Square;
    }
  } else {
    // A mode a choice or an override gives may leave the shell's keys in
    // place for the shell it also makes: they are not used, and a note says so.
    const YAML::Node given = body["mode"];
    const bool varied = given.Tag() == yaml::kChosenTag || !f.source(given).override_text.empty();
    for (const char* key : {"wall", "base", "rim"}) {
      if (!body[key].IsDefined()) continue;
      if (!varied) f.fail(body[key], std::string("body.") + key, "a solid body has no wall, base or rim");
      f.note(fmt::format("body.{} is not used: the body is solid ({})", key, f.location(given)));
    }
  }
  v.max_triangles = f.budget_or(root, "max_triangles", v.max_triangles);
  if (root["shrinkage"].IsDefined()) read_shrinkage(f, root["shrinkage"], v);
  if (root["print"].IsDefined()) v.print = read_print(f, root["print"], common);
  v.casting_case.wall /= millimetres_per_unit(common.units);       // 5 mm
  v.casting_case.clearance /= millimetres_per_unit(common.units);  // 0.2 mm
  if (root["case"].IsDefined()) v.casting_case = read_case(f, root["case"], common);
  // `mould: false` (a switch, "=with_mould") is none; `mould: true` the mould of every default.
  const bool mould_off = root["mould"].IsDefined() && root["mould"].IsScalar() &&
                         f.boolean_or(root, "mould", "mould", true) == false;
  if (root["mould"].IsDefined() && !mould_off) {
    const YAML::Node m = root["mould"].IsScalar() ? YAML::Node(YAML::NodeType::Map) : root["mould"];
    v.mould = read_mould(f, m, common, v);
    v.plaster_ratio = positive_or(f, m, "plaster_ratio", v.plaster_ratio);
    v.plaster_density = positive_or(f, m, "plaster_density", v.plaster_density);
    v.slip_density = positive_or(f, m, "slip_density", v.slip_density);
  }
  return v;
}

}  // namespace fabmesh
