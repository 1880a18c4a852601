#pragma once
// A builder's tolerance, divided among the stages that spend it: who was
// given what, who proved they used what, and one check that the parts fit.

#include <string>
#include <string_view>
#include <vector>

namespace fabmesh {

/// One stage's part of a tolerance.
struct ToleranceShare {
  std::string stage;   ///< e.g. "section", "revolution", "tool path chords"
  double given = 0.0;  ///< the most the stage may move the shape by
  double used = 0.0;   ///< proven: what it moved the shape by at most (<= given)
  bool done = false;   ///< whether `used` has been reported
};

/// A tolerance divided among stages, in order. A stage takes a fixed part of
/// the total (`take`) or what the stages before it left (`take_rest`: the
/// total less what the done ones used and the open ones were given), runs,
/// and reports what it proved it used (`use`). Every take checks that the
/// parts still fit in the total, so a builder that hands out more than its
/// tolerance fails here (std::logic_error: a bug), not in a report.
class ToleranceBudget {
 public:
  /// \throw std::logic_error unless `total` > 0 and finite
  explicit ToleranceBudget(double total);

  double total() const { return total_; }
  /// `fraction` (in (0, 1]) of the total, for `stage`.
  double take(std::string_view stage, double fraction);
  /// What the stages before left, for `stage` (0 when nothing is left).
  double take_rest(std::string_view stage);
  /// `stage` proved it used `proven` (>= 0, at most what it was given).
  void use(std::string_view stage, double proven);
  /// The parts, in the order taken.
  const std::vector<ToleranceShare>& shares() const { return shares_; }

 private:
  double committed() const;  ///< what the done stages used and the open ones were given
  ToleranceShare& share(std::string_view stage);
  double total_;
  std::vector<ToleranceShare> shares_;
};

}  // namespace fabmesh
