#pragma once
// interpret_gcode for test cases: the interpreter must be installed (REQUIRE, with what is missing).

#include <catch2/catch.hpp>
#include <string>

#include "tests/io/cutting/gcode_checks.h"

namespace fabmesh::test {

inline Trace interpret(const std::string& gcode, const std::string& name) {
  const std::string problem = gcode_interpreter_problem();
  INFO(problem);
  REQUIRE(problem.empty());
  return interpret_gcode(gcode, name);
}

}  // namespace fabmesh::test
