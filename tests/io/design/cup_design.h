#pragma once
// A small design text the design-reading tests share: the golden shell cup
// (5 control points, a 0.3 cm wall), named `cup`.

#include <string>

namespace fabmesh::test {

inline const std::string kCup = R"(name: cup
kind: vessel
units: cm
tolerance: 0.005
profile:
  family: quasi_bspline
  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]
  lambdas: [0, 0, 0]
body: {mode: shell, wall: 0.3, base: 0.4}
)";

}  // namespace fabmesh::test
