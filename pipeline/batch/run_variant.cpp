#include "pipeline/batch/run_variant.h"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "geometry/core/errors.h"
#include "pipeline/batch/sha256.h"
#include "pipeline/failure.h"
#include "pipeline/job.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Removes the regular files of `folder` not in `keep` (file names); the folder
// too when nothing is left. Hidden files (temporaries of writers) are left alone.
void tidy_folder(const fs::path& folder, const std::set<std::string>& keep) {
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::error_code type_ec;
    if (keep.count(name) || name.front() == '.' || !it->is_regular_file(type_ec)) continue;
    fs::remove(it->path(), type_ec);
  }
  if (keep.empty()) fs::remove(folder, ec);  // only when empty
}

RowMesh mesh_of(const JobReport& r) {
  RowMesh m;
  m.kind = r.kind;
  m.units = r.units;
  m.vertices = r.validation.vertices;
  m.triangles = r.validation.triangles;
  m.volume = r.validation.volume;
  m.area = r.validation.area;
  m.valid = r.validation.valid();
  m.bbox_min = {r.bbox_min.x(), r.bbox_min.y(), r.bbox_min.z()};
  m.bbox_max = {r.bbox_max.x(), r.bbox_max.y(), r.bbox_max.z()};
  m.max_deviation = r.max_deviation;
  m.tolerance = r.tolerance;
  return m;
}

}  // namespace

std::string variant_folder(const std::string& out_dir, const std::string& name) {
  return (fs::path(out_dir) / name).string();
}

BatchRow run_variant(const BatchManifest& manifest, std::size_t index, const PlannedVariant& planned,
                     const std::string& out_dir) {
  const Variant v = manifest.variant(index);
  BatchRow row;
  row.index = index;
  row.name = planned.name;
  row.design = planned.design;
  row.overrides = planned.overrides;
  row.key = planned.key;
  const fs::path folder = variant_folder(out_dir, v.name);
  std::error_code ec;
  const bool existed = fs::exists(folder, ec);
  std::set<std::string> written;
  Clock::time_point start = Clock::now();
  double job_ms = 0.0, record_ms = 0.0;
  StageTimings stages;
  try {
    std::string canonical;
    const Design design = manifest.bases[v.base].resolve(variant_overrides(manifest, v), &canonical);
    if (variant_key(canonical) != planned.key) {
      throw std::runtime_error(
          "its design or a file it reads changed while the batch ran (its key differs from the plan's): run "
          "the "
          "batch again");
    }
    row.timings_ms.emplace_back("resolve", ms_since(start));
    JobOptions options;
    options.out_dir = folder.string();
    PreparedJob job = prepare_job(design, options);
    const Clock::time_point digest_start = Clock::now();
    for (std::size_t k = 0; k < job.files.size(); ++k) {
      const OutputFile& f = job.report.files[k];
      const std::string file_name = fs::path(f.path).filename().string();
      row.files.push_back({v.name + "/" + file_name, f.format, f.units, job.files[k].bytes.size(),
                           sha256_hex(job.files[k].bytes)});
      written.insert(file_name);
    }
    record_ms += ms_since(digest_start);
    const JobReport report = write_job(std::move(job));
    for (const auto& stage : report.timings_ms) job_ms += stage.second;
    stages = report.timings_ms;
    row.mesh = mesh_of(report);
    row.skipped = report.skipped;
    for (const SkippedOutput& s : report.skipped)
      row.message += fmt::format("{}skipped {}: {}", row.message.empty() ? "" : "; ", s.format, s.reason);
    row.status = VariantStatus::Ok;
    row.exit_code = 0;
  } catch (...) {
    const Failure failure = describe_failure(std::current_exception(), planned.design);
    row.status = status_of<VariantStatus>(failure.exit_code);
    row.exit_code = failure.exit_code;
    row.message = failure.message;
    row.files.clear();
    row.mesh.reset();
    written.clear();
    if (row.timings_ms.empty()) row.timings_ms.emplace_back("resolve", ms_since(start));
  }
  const Clock::time_point tidy_start = Clock::now();
  if (existed || row.status != VariantStatus::Ok) tidy_folder(folder, written);
  record_ms += ms_since(tidy_start);
  row.timings_ms.emplace_back("job", job_ms);
  row.timings_ms.emplace_back("record", record_ms);
  for (const auto& stage : stages) row.timings_ms.push_back(stage);
  return row;
}

bool row_stands(std::string_view row_json, const std::string& out_dir) {
  const nlohmann::json j = nlohmann::json::parse(row_json, nullptr, false);
  if (j.is_discarded()) return false;
  const std::string status = j.value("status", "");
  if (status == "invalid" || status == "bad input") return true;
  if (status != "ok" || !j.contains("files")) return false;
  for (const auto& f : j.at("files")) {
    std::error_code ec;
    const fs::path path = fs::path(out_dir) / f.value("path", "");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec || size != f.value("bytes", std::uint64_t{0})) return false;
  }
  return true;
}

}  // namespace fabmesh
