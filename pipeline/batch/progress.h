#pragma once
// Progress lines of a running batch, on the error stream: a live line on a
// terminal, a plain line every few seconds otherwise.

#include <ostream>
#include <string>

#include "pipeline/batch/run_batch.h"

namespace fabmesh {

struct ProgressOptions {
  /// A terminal: the line is redrawn in place ("\r", erase to end of line).
  bool terminal = false;
  /// Least seconds between two lines (the last line is always printed);
  /// negative: 0.2 s on a terminal, 5 s otherwise.
  double interval_s = -1.0;
};

/// "batch: 120/1000 done (12%), 3 failed, 40 reused, 45.2/s, ETA 0:19"; the
/// last: "batch: 1000/1000 done, 3 failed, 40 reused, 44.1/s, 22.7 s". The
/// rate counts the variants run (not the reused ones) per second of the run.
std::string progress_line(const BatchProgress& progress);

/// Prints progress lines to `out`, at most one per interval (BatchOptions::progress).
class ProgressPrinter {
 public:
  ProgressPrinter(std::ostream& out, ProgressOptions options);
  void operator()(const BatchProgress& progress);

 private:
  std::ostream& out_;
  ProgressOptions options_;
  double last_s_ = -1e300;
};

}  // namespace fabmesh
