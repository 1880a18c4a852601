#pragma once
// Progress of `fabmesh run` on the error stream: which stage each design has
// finished, so a long run is not silent. A live line on a terminal; otherwise
// a plain line at most every few seconds (a run shorter than that prints none).

#include <chrono>
#include <cstddef>
#include <mutex>
#include <ostream>
#include <string>

namespace fabmesh::cli {

class RunProgress {
 public:
  /// `terminal`: redraw one line in place. `interval_s`: least seconds between
  /// two lines, counted from the start too; negative: 0.2 s on a terminal, 5 s otherwise.
  RunProgress(std::ostream& out, std::size_t designs, bool terminal, double interval_s = -1.0);

  /// Design `name` finished `stage` in `ms`. Thread-safe (jobs run in parallel).
  void stage(const std::string& name, const std::string& stage, double ms);
  /// A design finished (ok or not).
  void design_done();
  /// Clears the live line before the results are printed.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;

  std::ostream& out_;
  std::size_t designs_;
  std::size_t done_ = 0;
  bool terminal_;
  double interval_s_;
  bool drawn_ = false;
  Clock::time_point start_ = Clock::now();
  double last_s_ = 0.0;
  std::mutex mutex_;
};

}  // namespace fabmesh::cli
