#include "io/design/yaml/read_surface.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fabmesh {
namespace {

HBezierParams read_params(const yaml::Fields& f, const YAML::Node& patch, const char* key,
                          const std::string& field, const HBezierParams& fallback) {
  const YAML::Node n = patch[key];
  if (!n.IsDefined()) return fallback;
  const std::string pf = field + "." + key;
  f.require_map(n, pf, key_group("surface.patches[].u"));
  HBezierParams p;
  p.alpha = f.number_or(n, "alpha", pf + ".alpha", 1.0);
  p.lambda = f.number_or(n, "lambda", pf + ".lambda", 0.0);
  p.mu = f.number_or(n, "mu", pf + ".mu", 0.0);
  f.checked(n, pf, [&] { require_valid_params(p, pf); });
  return p;
}

std::array<Vec3, 4> read_line(const yaml::Fields& f, const YAML::Node& n, const std::string& field) {
  f.require_list(n, field);
  if (n.size() != 4) f.fail(n, field, fmt::format("expected 4 points [x, y, z], got {}", n.size()));
  std::array<Vec3, 4> line;
  for (std::size_t j = 0; j < 4; ++j) line[j] = f.point3(n[j], fmt::format("{}[{}]", field, j));
  return line;
}

PatchJoin read_join(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                    const std::vector<std::string>& names) {
  f.require_map(n, field, key_group("surface.patches[].join"));
  PatchJoin j;
  const YAML::Node to = f.required(n, "to", field);
  const std::string target = f.text(to, field + ".to");
  const auto it = std::find(names.begin(), names.end(), target);
  if (it == names.end()) {
    f.fail(to, field + ".to",
           fmt::format("no earlier patch is named '{}' (a join refers to a patch above it)", target));
  }
  j.to = static_cast<std::size_t>(it - names.begin());
  const std::string side =
      f.choice(f.required(n, "side", field), field + ".side", {"u_min", "u_max", "v_min", "v_max"});
  j.side = side == "u_min"   ? PatchSide::UMin
           : side == "u_max" ? PatchSide::UMax
           : side == "v_min" ? PatchSide::VMin
                             : PatchSide::VMax;
  const std::string c =
      f.choice(f.required(n, "continuity", field), field + ".continuity", {"G0", "G1", "G2"});
  j.continuity = c == "G0" ? Continuity::G0 : c == "G1" ? Continuity::G1 : Continuity::G2;
  if (j.continuity != Continuity::G1 && n["gamma"].IsDefined()) {
    f.fail(n["gamma"], field + ".gamma", fmt::format("gamma belongs to G1 joins (a {} join uses k, m)", c));
  }
  for (const char* key : {"k", "m"}) {
    if (j.continuity != Continuity::G2 && n[key].IsDefined()) {
      f.fail(n[key], field + "." + key, fmt::format("{} belongs to G2 joins (a G1 join uses gamma)", key));
    }
  }
  j.gamma = f.number_or(n, "gamma", field + ".gamma", 1.0);
  if (!(j.gamma > 0.0) || !std::isfinite(j.gamma)) {
    f.fail(n["gamma"], field + ".gamma", fmt::format("gamma = {} must be > 0", j.gamma));
  }
  j.k = f.number_or(n, "k", field + ".k", 1.0);
  if (!(j.k > 0.0) || !std::isfinite(j.k))
    f.fail(n["k"], field + ".k", fmt::format("k = {} must be > 0", j.k));
  j.m = f.number_or(n, "m", field + ".m", 0.0);
  if (!std::isfinite(j.m)) f.fail(n["m"], field + ".m", fmt::format("m = {} is not a finite number", j.m));
  return j;
}

PatchSpec read_patch(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                     const std::vector<PatchSpec>& earlier, const std::vector<std::string>& names) {
  f.require_map(n, field, key_group("surface.patches[]"));
  PatchSpec s;
  s.name = f.text(f.required(n, "name", field), field + ".name");
  if (std::find(names.begin(), names.end(), s.name) != names.end()) {
    f.fail(n["name"], field + ".name", fmt::format("patch name '{}' is used twice", s.name));
  }
  s.key = field;
  std::size_t rows = 4;
  if (n["join"].IsDefined()) {
    s.join = read_join(f, n["join"], field + ".join", names);
    rows = 3 - static_cast<std::size_t>(static_cast<int>(s.join->continuity));
  }
  // A joined patch shares the border's parameterisation: inherit it, or check it.
  HBezierParams border_u, border_v;
  const PatchSpec* target = s.join ? &earlier[s.join->to] : nullptr;
  const bool along_u = s.join && (s.join->side == PatchSide::UMin || s.join->side == PatchSide::UMax);
  if (target) (along_u ? border_v : border_u) = along_u ? target->v : target->u;
  s.u = read_params(f, n, "u", field, border_u);
  s.v = read_params(f, n, "v", field, border_v);
  if (target) {
    const char* key = along_u ? "v" : "u";
    const HBezierParams& own = along_u ? s.v : s.u;
    const HBezierParams& theirs = along_u ? target->v : target->u;
    if (own != theirs) {
      f.fail(n[key], field + "." + key,
             fmt::format("the patch joins '{}' along {}, so its {} parameters must be the border's (alpha "
                         "{}, lambda {}, mu {}); "
                         "got (alpha {}, lambda {}, mu {}) (omit '{}' to inherit them)",
                         target->name, to_string(s.join->side), key, theirs.alpha, theirs.lambda, theirs.mu,
                         own.alpha, own.lambda, own.mu, key));
    }
  }
  const YAML::Node pts = f.required(n, "points", field);
  f.require_list(pts, field + ".points");
  if (pts.size() != rows) {
    f.fail(pts, field + ".points",
           s.join ? fmt::format("a {} join leaves {} free {} of 4 points; got {}",
                                to_string(s.join->continuity), rows, along_u ? "rows" : "columns", pts.size())
                  : fmt::format("an explicit patch needs 4 rows of 4 points [x, y, z]; got {} rows",
                                pts.size()));
  }
  for (std::size_t i = 0; i < rows; ++i)
    s.points.push_back(read_line(f, pts[i], fmt::format("{}.points[{}]", field, i)));
  return s;
}

}  // namespace

SurfaceDesign read_surface(const yaml::Fields& f, const YAML::Node& root) {
  SurfaceDesign d;
  const YAML::Node patches = f.required(root, "patches", "patches");
  f.require_list(patches, "patches", 1);
  std::vector<std::string> names;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    d.patches.push_back(read_patch(f, patches[i], fmt::format("patches[{}]", i), d.patches, names));
    names.push_back(d.patches.back().name);
  }
  if (root["thickness"].IsDefined()) {
    d.thickness = f.number(root["thickness"], "thickness");
    if (!(d.thickness > 0.0))
      f.fail(root["thickness"], "thickness", fmt::format("thickness = {} must be > 0", d.thickness));
  }
  if (root["thicken"].IsDefined()) {
    const std::string side =
        f.choice(root["thicken"], "thicken", {"normal", "outward", "inward", "centered"});
    if (d.thickness == 0.0) {
      f.fail(root["thicken"], "thicken", "thicken says which side a shell goes to; give a thickness too");
    }
    d.thicken = side == "outward"    ? ThickenSide::Outward
                : side == "inward"   ? ThickenSide::Inward
                : side == "centered" ? ThickenSide::Centered
                                     : ThickenSide::Normal;
  }
  d.max_triangles = f.budget_or(root, "max_triangles", d.max_triangles);
  // Joins that cannot be made (continuity contradicted, borders that do not meet) at their patch.
  try {
    build_patch_network(d.patches);
  } catch (const GeometryError& e) {
    for (std::size_t i = 0; i < d.patches.size(); ++i) {
      if (e.where().empty() || d.patches[i].key != e.where()) continue;
      const YAML::Mark m = patches[i].Mark();
      throw FileError(f.path(), m.line + 1, m.column + 1,
                      fmt::format("{}: {}", f.label(patches[i], e.location().name), e.what()));
    }
    throw FileError(f.path(), 0, 0, fmt::format("{}: {}", f.path(), e.what()));
  } catch (const RangeError& e) {
    f.fail(patches, "patches", e.what());
  }
  return d;
}

}  // namespace fabmesh
