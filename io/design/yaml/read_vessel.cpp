#include "io/design/yaml/read_vessel.h"

#include <fmt/format.h>

#include "io/design/yaml/read_curve.h"

namespace fabmesh {

VesselDesign read_vessel(const yaml::Fields& f, const YAML::Node& root) {
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
  } else {
    for (const char* key : {"wall", "base"}) {
      if (body[key].IsDefined())
        f.fail(body[key], std::string("body.") + key, "a solid body has no wall or base");
    }
  }
  v.max_triangles = f.budget_or(root, "max_triangles", v.max_triangles);
  return v;
}

}  // namespace fabmesh
