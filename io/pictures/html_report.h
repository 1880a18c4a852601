#pragma once
// One self-contained HTML page summarising a run or a batch: a sortable
// table of every design/variant with its verdict, measures, files and
// thumbnails of its preview and plot.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

enum class ReportStatus { Ok, Invalid, BadInput, Error };

/// "ok", "invalid", "bad input", "error".
const char* to_string(ReportStatus status);

struct StageTiming {
  std::string stage;     ///< "build", "validate", "write", ...
  double seconds = 0.0;  ///< wall time, >= 0
};

/// One design or variant. Optional measures are shown as "-" and sort last.
struct ReportRow {
  std::string name;
  std::string kind;  ///< vessel | countertop | surface | curve
  ReportStatus status = ReportStatus::Ok;
  std::string message;                      ///< the verdict in words
  std::vector<std::string> remarks;         ///< lines under the verdict (class "remarks")
  std::string units;                        ///< model units of the measures ("mm", "cm", ...)
  std::optional<double> max_deviation;      ///< proven bound, model units
  std::optional<double> volume;             ///< model units cubed
  std::optional<double> area;               ///< model units squared
  std::optional<std::array<Vec3, 2>> bbox;  ///< {min, max}, model units
  std::optional<std::size_t> triangles;
  std::vector<StageTiming> timings;
  /// Output files, paths relative to the page (e.g. "out/cup.stl").
  std::vector<std::string> files;
  std::string preview_png;  ///< relative path of the preview image; empty: none
  std::string plot_svg;     ///< relative path of the curve plot; empty: none
};

struct HtmlReport {
  std::string title = "fabmesh report";
  std::string generated_by;  ///< e.g. "fabmesh 0.1.0 run --report"
  std::vector<ReportRow> rows;
};

struct HtmlReportOptions {
  int thumbnail_width = 120;  ///< pixels, [16, 1024]; images keep their aspect inside the box
  int thumbnail_height = 90;  ///< pixels, [16, 1024]
};

/// The report as one HTML5 page with no network access: inline style and
/// script, no external fonts or scripts; images and files referenced by
/// their relative paths (percent-encoded, so a ':' cannot start a URL
/// scheme), thumbnails lazy-loaded with
/// width/height set and linking to the full image. Clicking a column header
/// sorts the table (again: reversed); a filter box hides rows not containing
/// its text. Once the images have loaded, <body> carries
/// data-images-loaded/-failed and the footer says how many failed. All text
/// is escaped. Deterministic.
/// \throw RangeError for bad thumbnail sizes or a negative/non-finite timing,
/// InputError for an absolute path (leading '/' or '\\').
std::string render_report_html(const HtmlReport& report, const HtmlReportOptions& options = {});

}  // namespace fabmesh
