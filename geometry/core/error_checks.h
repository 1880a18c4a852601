#pragma once
// Checks that throw the errors of geometry/core/errors.h, and how messages
// name an error's location.

#include <string>

#include "geometry/core/errors.h"

namespace fabmesh {

/// How messages name `location`: "place: name", "path: key (default)" for a
/// key the design does not write, or just the name before io placed it.
std::string location_text(const ErrorLocation& location);

/// Throws RangeError unless `value` is finite and within [lo, hi].
void require_in_range(const std::string& field, double value, double lo, double hi);

/// Throws RangeError unless `value` is finite and > 0.
void require_positive(const std::string& field, double value);

}  // namespace fabmesh
