#pragma once
// Reads the configs/examples/mould_*.yaml designs for the tests until the
// design reader knows the `shrinkage:` and `mould:` keys: those two keys are
// read here (strictly: an unknown key fails the test) and the rest of the
// file goes through parse_design.

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "geometry/curves/build_curve.h"
#include "geometry/mould/mould_options.h"
#include "io/design/read_design.h"

namespace fabmesh::test {

struct MouldExample {
  std::string name;
  std::string units;
  CompositeCurve profile;
  MouldOptions options;
};

inline MouldOptions parse_mould_options(const YAML::Node& m, double shrinkage, double tolerance) {
  MouldOptions o;
  o.shrinkage = shrinkage;
  o.tolerance = tolerance;
  for (const auto& kv : m) {
    const std::string key = kv.first.as<std::string>();
    const YAML::Node& v = kv.second;
    if (key == "parts")
      o.parts = v.as<int>();
    else if (key == "wall")
      o.wall = v.as<double>();
    else if (key == "spare")
      o.spare = v.as<double>();
    else if (key == "spare_shape")
      o.spare_shape = v.as<std::string>() == "cone" ? SpareShape::Cone : SpareShape::Cylinder;
    else if (key == "spare_taper_deg")
      o.spare_taper_deg = v.as<double>();
    else if (key == "block")
      o.block = v.as<std::string>() == "box" ? BlockShape::Box : BlockShape::Cylinder;
    else if (key == "block_radius")
      o.block_radius = v.as<double>();
    else if (key == "base_part")
      o.base_part = v.as<bool>();
    else if (key == "base_height")
      o.base_height = v.as<double>();
    else if (key == "keys")
      o.keys = v.as<int>();
    else if (key == "key_radius")
      o.key_radius = v.as<double>();
    else if (key == "key_clearance")
      o.key_clearance = v.as<double>();
    else if (key == "key_margin")
      o.key_margin = v.as<double>();
    else if (key == "allow_undercuts")
      o.allow_undercuts = v.as<bool>();
    else if (key == "key_positions") {
      for (const auto& p : v) o.key_positions.emplace_back(p[0].as<double>(), p[1].as<double>());
    } else {
      throw std::runtime_error("mould example: unknown key mould." + key);
    }
  }
  return o;
}

inline MouldExample read_mould_example(const std::string& path) {
  YAML::Node root = YAML::LoadFile(path);
  const YAML::Node mould = YAML::Clone(root["mould"]);
  const double shrinkage = root["shrinkage"] ? root["shrinkage"].as<double>() : 0.0;
  if (!mould) throw std::runtime_error(path + ": no mould section");
  root.remove("mould");
  root.remove("shrinkage");
  YAML::Emitter out;
  out << root;
  const Design d = parse_design(out.c_str(), path);
  MouldExample e;
  e.name = d.common.name;
  e.units = d.common.units;
  e.profile = build_curve(std::get<VesselDesign>(d.body).profile).curve;
  e.options = parse_mould_options(mould, shrinkage, d.common.tolerance);
  return e;
}

}  // namespace fabmesh::test
