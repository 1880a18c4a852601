#include "pipeline/batch/progress.h"

#include <fmt/format.h>

#include <cmath>

namespace fabmesh {
namespace {

std::string duration(double seconds) {
  const long s = std::lround(seconds);
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

}  // namespace

std::string progress_line(const BatchProgress& p) {
  const std::size_t ran = p.done - p.reused;
  const double rate = p.elapsed_s > 0.0 ? static_cast<double>(ran) / p.elapsed_s : 0.0;
  std::string line = fmt::format("batch: {}/{} done", p.done, p.total);
  if (!p.finished && p.total > 0) line += fmt::format(" ({}%)", 100 * p.done / p.total);
  line += fmt::format(", {} failed, {} reused, {:.1f}/s", p.failed, p.reused, rate);
  if (p.finished) return line + fmt::format(", {:.1f} s", p.elapsed_s);
  if (rate <= 0.0) return line + ", ETA -";
  return line + ", ETA " + duration(static_cast<double>(p.total - p.done) / rate);
}

ProgressPrinter::ProgressPrinter(std::ostream& out, ProgressOptions options) : out_(out), options_(options) {
  if (options_.interval_s < 0.0) options_.interval_s = options_.terminal ? 0.2 : 5.0;
}

void ProgressPrinter::operator()(const BatchProgress& p) {
  if (!p.finished && p.elapsed_s - last_s_ < options_.interval_s) return;
  last_s_ = p.elapsed_s;
  if (options_.terminal) {
    out_ << '\r' << progress_line(p) << "\x1b[K" << (p.finished ? "\n" : "") << std::flush;
  } else {
    out_ << progress_line(p) << '\n' << std::flush;
  }
}

}  // namespace fabmesh
