#include "io/design/read_design.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/design/read_countertop.h"
#include "io/design/read_curve.h"
#include "io/design/read_surface.h"
#include "io/design/yaml_fields.h"

namespace fabmesh {
namespace {

constexpr std::size_t kMaxDesignBytes = 64u << 20;

DesignCommon read_common(const yaml::Fields& f, const YAML::Node& root) {
  DesignCommon c;
  c.path = f.path();
  c.name = f.text_or(root, "name", "name", std::filesystem::path(f.path()).stem().string());
  c.kind = f.choice(f.required(root, "kind", "kind"), "kind", {"curve", "vessel", "countertop", "surface"});
  c.units = f.choice(root["units"].IsDefined() ? root["units"] : YAML::Node("mm"), "units",
                     {"mm", "cm", "m", "in"});
  c.tolerance = f.number_or(root, "tolerance", "tolerance", 0.01);
  if (c.tolerance <= 0.0)
    f.fail(root["tolerance"], "tolerance", fmt::format("tolerance = {} must be > 0", c.tolerance));
  if (root["outputs"].IsDefined()) {
    const YAML::Node outs = root["outputs"];
    f.require_list(outs, "outputs", 1);
    for (std::size_t i = 0; i < outs.size(); ++i) {
      const std::string field = fmt::format("outputs[{}]", i);
      c.outputs.push_back(f.choice(outs[i], field, {"stl", "drc", "obj", "ply", "off", "dxf", "svg"}));
      if ((c.outputs.back() == "dxf" || c.outputs.back() == "svg") && c.kind != "countertop") {
        f.fail(outs[i], field,
               fmt::format("{} is a cutting outline; only countertop designs have one", c.outputs.back()));
      }
    }
  } else if (c.kind == "countertop") {
    c.outputs = {"stl", "drc", "dxf", "svg"};  // the slab, and its cutting outline for the CNC router
  } else {
    c.outputs = {"stl", "drc"};
  }
  return c;
}

VesselDesign read_vessel(const yaml::Fields& f, const YAML::Node& root) {
  f.require_map(root, "",
                {"name", "kind", "units", "tolerance", "outputs", "profile", "body", "max_triangles"});
  VesselDesign v;
  v.profile = read_curve(f, f.required(root, "profile", "profile"), "profile");
  const YAML::Node body = f.required(root, "body", "body");
  f.require_map(body, "body", {"mode", "wall", "base"});
  const std::string mode = f.choice(f.required(body, "mode", "body"), "body.mode", {"solid", "shell"});
  v.mode = mode == "shell" ? BodyMode::Shell : BodyMode::Solid;
  if (v.mode == BodyMode::Shell) {
    const YAML::Node wall = f.required(body, "wall", "body");
    v.wall = f.number(wall, "body.wall");
    if (v.wall <= 0.0) f.fail(wall, "body.wall", fmt::format("wall = {} must be > 0", v.wall));
    v.base = f.number_or(body, "base", "body.base", v.wall);
    if (v.base <= 0.0) f.fail(body["base"], "body.base", fmt::format("base = {} must be > 0", v.base));
  } else {
    for (const char* key : {"wall", "base"}) {
      if (body[key].IsDefined())
        f.fail(body[key], std::string("body.") + key, "a solid body has no wall or base");
    }
  }
  if (root["max_triangles"].IsDefined()) {
    const double budget = f.number(root["max_triangles"], "max_triangles");
    if (budget < 1.0 || budget > 2e9 || budget != std::floor(budget)) {
      f.fail(root["max_triangles"], "max_triangles",
             fmt::format("max_triangles = {} must be a whole number in "
                         "[1, 2e9]",
                         budget));
    }
    v.max_triangles = static_cast<std::size_t>(budget);
  }
  return v;
}

}  // namespace

Design parse_design(const std::string& text, const std::string& path) {
  const yaml::Fields f(path);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw FileError(
        path, e.mark.line + 1, e.mark.column + 1,
        fmt::format("{}:{}:{}: invalid YAML: {}", path, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  if (!root.IsMap()) throw FileError(path, 0, 0, fmt::format("{}: a design file must be a YAML map", path));
  Design d;
  d.common = read_common(f, root);
  if (d.common.kind == "curve") {
    f.require_map(root, "", {"name", "kind", "units", "tolerance", "outputs", "curve"});
    d.body = CurveDesign{read_curve(f, f.required(root, "curve", "curve"), "curve")};
    return d;
  }
  if (d.common.kind == "vessel") {
    d.body = read_vessel(f, root);
    return d;
  }
  if (d.common.kind == "countertop") {
    d.body = read_countertop(f, root);
    return d;
  }
  if (d.common.kind == "surface") {
    d.body = read_surface(f, root);
    return d;
  }
  f.fail(root["kind"], "kind",
         fmt::format("kind '{}' is not available in this version of fabmesh", d.common.kind));
}

Design read_design(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, 0, 0, fmt::format("{}: cannot open design file", path));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  if (text.size() > kMaxDesignBytes) {
    throw FileError(path, 0, 0,
                    fmt::format("{}: design file is larger than {} bytes", path, kMaxDesignBytes));
  }
  return parse_design(text, path);
}

}  // namespace fabmesh
