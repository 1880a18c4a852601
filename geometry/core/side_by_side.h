#pragma once
// Two independent pieces of work run at once, failing as they would in turn.

#include <functional>

namespace fabmesh {

/// Runs `first` and `second` side by side (on two cores when there are two
/// free) and returns when both have finished. An exception from either is
/// rethrown, the first's when both throw: what fails is what would have
/// failed had they run one after the other, whatever the timing.
void side_by_side(const std::function<void()>& first, const std::function<void()>& second);

}  // namespace fabmesh
