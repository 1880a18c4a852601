#pragma once
// The digitised worktop the router tests share: a 2400 x 650 outline whose
// front edge is a concave arc of radius 19 m given as 301 points (rising 38 mm
// into the part at the middle), and whose back corners are rounded convexly
// (radius 100) by 41 points each, as a digital template gives it.

#include <cmath>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh::test {

inline std::vector<Vec2> digitised_worktop_points() {
  std::vector<Vec2> p;
  const double R = 19000;
  for (int i = 0; i <= 300; ++i) {
    const double x = 2400.0 * i / 300;
    p.emplace_back(x, std::sqrt(R * R - (x - 1200) * (x - 1200)) - std::sqrt(R * R - 1200.0 * 1200.0));
  }
  for (int i = 0; i <= 40; ++i) {
    const double a = M_PI / 2 * i / 40;
    p.emplace_back(2300 + 100 * std::cos(a), 550 + 100 * std::sin(a));
  }
  for (int i = 0; i <= 40; ++i) {
    const double a = M_PI / 2 + M_PI / 2 * i / 40;
    p.emplace_back(100 + 100 * std::cos(a), 550 + 100 * std::sin(a));
  }
  return p;
}

}  // namespace fabmesh::test
