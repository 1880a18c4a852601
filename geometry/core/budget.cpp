#include "geometry/core/budget.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {

void throw_over_budget(double requested, std::size_t budget, const std::string& need,
                       std::string_view advice) {
  throw BudgetError(requested, static_cast<double>(budget),
                    advice.empty() ? fmt::format("{}, over the budget of {}", need, budget)
                                   : fmt::format("{}, over the budget of {} ({})", need, budget, advice));
}

}  // namespace fabmesh
