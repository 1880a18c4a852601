#pragma once
// validate with ValidationOptions::moved_from, as the Draco and float32
// checks call it: the report of `moved`, a copy of `original` (validated as
// `report`) whose vertices moved.

#include "geometry/validation/validate.h"

namespace fabmesh::test {

inline ValidationReport validate_moved(const TriangleSoup& original, const ValidationReport& report,
                                       const TriangleSoup& moved) {
  ValidationOptions options;
  options.moved_from = MovedFrom{&original, &report};
  return validate(moved, options);
}

}  // namespace fabmesh::test
