#include "pipeline/cli/run_progress.h"

#include <fmt/format.h>

namespace fabmesh::cli {

RunProgress::RunProgress(std::ostream& out, std::size_t designs, bool terminal, double interval_s)
    : out_(out), designs_(designs), terminal_(terminal), interval_s_(interval_s) {
  if (interval_s_ < 0.0) interval_s_ = terminal ? 0.2 : 5.0;
}

void RunProgress::stage(const std::string& name, const std::string& stage, double ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  const double now = std::chrono::duration<double>(Clock::now() - start_).count();
  if (now - last_s_ < interval_s_) return;
  last_s_ = now;
  const std::string line = fmt::format("run: {}/{} designs done, {}: {} done in {:.1f} s ({:.1f} s so far)",
                                       done_, designs_, name, stage, ms / 1000.0, now);
  if (terminal_) {
    out_ << '\r' << line << "\x1b[K" << std::flush;
    drawn_ = true;
  } else {
    out_ << line << '\n' << std::flush;
  }
}

void RunProgress::design_done() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
}

void RunProgress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_) out_ << "\r\x1b[K" << std::flush;
  drawn_ = false;
}

}  // namespace fabmesh::cli
