#pragma once
// Wall-clock timings of the stages of a job, in the order they ran.

#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace fabmesh {

/// Stage name -> wall milliseconds, in order.
using StageTimings = std::vector<std::pair<std::string, double>>;

/// Called after each lap with the stage's name and milliseconds (progress).
using StageObserver = std::function<void(const std::string& stage, double ms)>;

/// Appends to `log` the time since the previous lap (or since construction),
/// and tells `observer`, when given.
class StageTimer {
 public:
  explicit StageTimer(StageTimings& log, StageObserver observer = {})
      : log_(log), observer_(std::move(observer)) {}
  /// Records the time since the previous lap under `stage`; returns it (ms).
  double lap(const std::string& stage) {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    log_.emplace_back(stage, ms);
    start_ = now;
    if (observer_) observer_(stage, ms);
    return ms;
  }

 private:
  StageTimings& log_;
  StageObserver observer_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace fabmesh
