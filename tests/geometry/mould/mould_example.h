#pragma once
// Reads the configs/examples/mould_*.yaml designs with the design reader
// (`shrinkage:` and `mould:` included) for the mould tests.

#include <string>

#include "geometry/fairing/build_curve.h"
#include "geometry/mould/mould_options.h"
#include "io/design/read_design.h"

namespace fabmesh::test {

struct MouldExample {
  std::string name;
  std::string units;
  CompositeCurve profile;  ///< as designed (fired)
  MouldOptions options;    ///< with the design's tolerance and shrinkage
};

inline MouldExample read_mould_example(const std::string& path) {
  const Design d = read_design(path);
  const auto& v = std::get<VesselDesign>(d.body);
  MouldExample e;
  e.name = d.common.name;
  e.units = d.common.units;
  e.profile = build_curve(v.profile).curve;
  e.options = v.mould.value();
  return e;
}

}  // namespace fabmesh::test
