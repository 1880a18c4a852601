#pragma once
// Wall-clock timings of the stages of a job, in the order they ran.

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace fabmesh {

/// Stage name -> wall milliseconds, in order.
using StageTimings = std::vector<std::pair<std::string, double>>;

/// Appends to `log` the time since the previous lap (or since construction).
class StageTimer {
 public:
  explicit StageTimer(StageTimings& log) : log_(log) {}
  /// Records the time since the previous lap under `stage`; returns it (ms).
  double lap(const std::string& stage) {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    log_.emplace_back(stage, ms);
    start_ = now;
    return ms;
  }

 private:
  StageTimings& log_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace fabmesh
