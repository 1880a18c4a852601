#include "geometry/core/errors.h"

#include <fmt/format.h>

#include <cmath>

namespace fabmesh {

void require_in_range(const std::string& field, double value, double lo, double hi) {
  if (!std::isfinite(value)) {
    throw RangeError(field, value, fmt::format("{} = {} is not a finite number", field, value));
  }
  if (value < lo || value > hi) {
    throw RangeError(field, value, fmt::format("{} = {} is outside [{}, {}]", field, value, lo, hi));
  }
}

void require_positive(const std::string& field, double value) {
  if (!std::isfinite(value)) {
    throw RangeError(field, value, fmt::format("{} = {} is not a finite number", field, value));
  }
  if (value <= 0.0) {
    throw RangeError(field, value, fmt::format("{} = {} must be > 0", field, value));
  }
}

}  // namespace fabmesh
