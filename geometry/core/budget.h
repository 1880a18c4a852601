#pragma once
// Work budgets (max_triangles, max_points): how a builder refuses a job
// that needs more than its budget, in the one wording users see.

#include <cstddef>
#include <string>
#include <string_view>

namespace fabmesh {

/// Throws BudgetError(requested, budget, "NEED, over the budget of BUDGET"),
/// followed by " (ADVICE)" when `advice` is not empty. `need` says what the
/// job needs: "the slab needs 1200 triangles".
[[noreturn]] void throw_over_budget(double requested, std::size_t budget, const std::string& need,
                                    std::string_view advice = {});

/// throw_over_budget when `requested` > `budget` (compared as Count); the
/// callable `need` makes the need's text, only then.
template <class Count, class Need>
void require_within_budget(Count requested, std::size_t budget, Need&& need, std::string_view advice = {}) {
  if (requested > static_cast<Count>(budget)) {
    throw_over_budget(static_cast<double>(requested), budget, need(), advice);
  }
}

}  // namespace fabmesh
