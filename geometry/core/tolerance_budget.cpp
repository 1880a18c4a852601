#include "geometry/core/tolerance_budget.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace fabmesh {
namespace {

// A rest computed as total - committed, added back, may exceed the total by
// the rounding of that subtraction and of the sum: a few units in the last place.
constexpr double kRounding = 8.0 * std::numeric_limits<double>::epsilon();

}  // namespace

ToleranceBudget::ToleranceBudget(double total) : total_(total) {
  if (!(total > 0.0) || !std::isfinite(total))
    throw std::logic_error(fmt::format("a tolerance budget of {} (must be > 0)", total));
}

double ToleranceBudget::committed() const {
  double sum = 0.0;
  for (const ToleranceShare& s : shares_) sum += s.done ? s.used : s.given;
  return sum;
}

double ToleranceBudget::take(std::string_view stage, double fraction) {
  if (!(fraction > 0.0 && fraction <= 1.0))
    throw std::logic_error(
        fmt::format("tolerance share of {}: fraction {} is outside (0, 1]", stage, fraction));
  const double given = fraction * total_;
  if (committed() + given > total_ * (1.0 + kRounding)) {
    throw std::logic_error(fmt::format("tolerance budget: {} takes {} but only {} of {} is left", stage,
                                       given, total_ - committed(), total_));
  }
  shares_.push_back({std::string(stage), given, 0.0, false});
  return given;
}

double ToleranceBudget::take_rest(std::string_view stage) {
  const double given = std::max(0.0, total_ - committed());
  shares_.push_back({std::string(stage), given, 0.0, false});
  return given;
}

ToleranceShare& ToleranceBudget::share(std::string_view stage) {
  for (ToleranceShare& s : shares_) {
    if (s.stage == stage && !s.done) return s;
  }
  throw std::logic_error(fmt::format("tolerance budget: {} reports use without having taken a share", stage));
}

void ToleranceBudget::use(std::string_view stage, double proven) {
  ToleranceShare& s = share(stage);
  if (!(proven >= 0.0) || proven > s.given * (1.0 + kRounding)) {
    throw std::logic_error(
        fmt::format("tolerance budget: {} used {} of the {} it was given", stage, proven, s.given));
  }
  s.used = proven;
  s.done = true;
}

}  // namespace fabmesh
