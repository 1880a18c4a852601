#include "geometry/core/error_checks.h"

#include <fmt/format.h>

#include <cmath>

namespace fabmesh {

std::string location_text(const ErrorLocation& location) {
  const std::string& name = location.name.empty() ? location.key : location.name;
  if (location.place.empty()) return name;
  if (location.is_default) return fmt::format("{}: {} (default)", location.place, location.key);
  return fmt::format("{}: {}", location.place, name);
}

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
