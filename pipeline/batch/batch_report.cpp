#include "pipeline/batch/batch_report.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "io/mesh/read_mesh.h"
#include "pipeline/batch/batch_row.h"
#include "pipeline/pictures.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

std::vector<BatchRow> read_rows(const fs::path& summary) {
  const std::string text = read_file(summary.string());
  std::vector<BatchRow> rows;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    rows.push_back(row_from_json(nlohmann::ordered_json::parse(line)));
  }
  return rows;
}

// The row's STL (relative to the batch folder), if it wrote one.
const RowFile* stl_of(const BatchRow& row) {
  for (const RowFile& f : row.files) {
    if (f.format == "stl") return &f;
  }
  return nullptr;
}

// The row's page row; its files (relative to the batch folder `dir`) linked
// relative to the page's folder `base`.
ReportRow page_row(const BatchRow& row, const fs::path& dir, const fs::path& base) {
  ItemFacts item = row_facts(row);
  for (std::string& file : item.files) file = (dir / file).string();
  ReportRow r = report_row(item, base.string());
  if (stl_of(row) != nullptr)
    r.preview_png = page_link((dir / row.name / (row.name + ".thumb.png")).string(), base.string());
  return r;
}

}  // namespace

void write_batch_report(const std::string& batch_dir, const std::string& report_path) {
  const fs::path dir(batch_dir);
  const fs::path summary = dir / "summary.jsonl";
  if (!fs::is_regular_file(summary)) {
    throw FileError(
        summary.string(), 0, 0,
        fmt::format("{}: no summary yet: the report is made from a whole batch's summary", summary.string()));
  }
  const std::vector<BatchRow> rows = read_rows(summary);
  // Thumbnails, once per variant, in parallel (each reads its own STL).
  PreviewOptions thumb;
  thumb.width = 240;
  thumb.height = 180;
  tbb::parallel_for(std::size_t{0}, rows.size(), [&](std::size_t i) {
    const RowFile* stl = stl_of(rows[i]);
    if (stl == nullptr) return;
    const fs::path target = dir / rows[i].name / (rows[i].name + ".thumb.png");
    std::error_code ec;
    if (fs::is_regular_file(target, ec)) return;
    write_file_atomically(target.string(), preview_png(read_mesh((dir / stl->path).string()), thumb));
  });
  const fs::path base = fs::absolute(report_path).parent_path();
  HtmlReport page;
  page.title = fmt::format("fabmesh batch {}", dir.filename().string());
  page.generated_by = std::string("fabmesh ") + FABMESH_VERSION + " batch --report";
  page.rows.reserve(rows.size());
  for (const BatchRow& row : rows) page.rows.push_back(page_row(row, fs::absolute(dir), base));
  fs::create_directories(base);
  write_file_atomically(report_path, render_report_html(page));
}

}  // namespace fabmesh
