#include "pipeline/batch/batch_row.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "geometry/core/errors.h"
#include "pipeline/batch/csv_cell.h"
#include "pipeline/report.h"

namespace fabmesh {
namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kFixedColumns[] = {
    "index",      "name",       "design",        "status",     "exit_code",  "message",
    "key",        "kind",       "units",         "vertices",   "triangles",  "volume",
    "area",       "valid",      "bbox_min_x",    "bbox_min_y", "bbox_min_z", "bbox_max_x",
    "bbox_max_y", "bbox_max_z", "max_deviation", "tolerance",  "files"};

std::string number(double x) { return fmt::format("{}", x); }

// A parameter's column: its path, or parameter:PATH when a fixed column has that name.
std::string parameter_column(const std::string& path) {
  const bool taken = std::any_of(std::begin(kFixedColumns), std::end(kFixedColumns),
                                 [&](const char* c) { return path == c; });
  return taken ? "parameter:" + path : path;
}

double timing(const StageTimings& timings, const std::string& stage) {
  for (const auto& [name, ms] : timings) {
    if (name == stage) return ms;
  }
  return 0.0;
}

// A whole number of type T, as row_json writes one. nlohmann's get<T> casts
// any number, and a number beyond T's range (1e300 as an int) is undefined
// behaviour: a damaged row must be bad input instead.
template <class T>
T whole_number(const nlohmann::ordered_json& v, const char* key) {
  static_assert(std::is_integral_v<T> && !std::is_same_v<T, bool>);
  using Limits = std::numeric_limits<T>;
  const auto max = static_cast<std::uint64_t>(Limits::max());
  bool fits = false;
  if (v.is_number_unsigned()) {
    fits = v.get<std::uint64_t>() <= max;
  } else if (v.is_number_integer()) {
    const auto x = v.get<std::int64_t>();
    fits = x >= 0 ? static_cast<std::uint64_t>(x) <= max
                  : Limits::is_signed && x >= static_cast<std::int64_t>(Limits::min());
  }
  if (!fits) {
    throw InputError(fmt::format("summary row: field '{}' is {}, not a whole number in [{}, {}]", key,
                                 v.dump(), Limits::min(), Limits::max()));
  }
  return v.get<T>();
}

// A box corner as row_json writes it: [x, y, z].
Vec3 point(const nlohmann::ordered_json& xyz) {
  const auto p = xyz.get<std::array<double, 3>>();
  return {p[0], p[1], p[2]};
}

template <class T>
T field(const nlohmann::ordered_json& j, const char* key) {
  if (!j.contains(key)) throw InputError(fmt::format("summary row: missing field '{}'", key));
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    return whole_number<T>(j.at(key), key);
  } else {
    return j.at(key).get<T>();
  }
}

}  // namespace

bool is_final(VariantStatus status) {
  return status == VariantStatus::Ok || status == VariantStatus::Invalid || status == VariantStatus::BadInput;
}

VariantStatus parse_variant_status(const std::string& text) {
  for (const VariantStatus s : {VariantStatus::Ok, VariantStatus::Invalid, VariantStatus::BadInput,
                                VariantStatus::Error, VariantStatus::Missing, VariantStatus::Environment}) {
    if (text == to_string(s)) return s;
  }
  throw InputError(fmt::format("summary row: unknown status '{}'", text));
}

void record_result(BatchRow& row, const Result& result) {
  row.mesh = mesh_facts(result);
  row.build = result.facts;
  row.skipped = result.skipped;
  for (const SkippedOutput& s : result.skipped)
    row.message += fmt::format("{}skipped {}: {}", row.message.empty() ? "" : "; ", s.format, s.reason);
}

Json row_json(const BatchRow& r) {
  Json j;
  j["index"] = r.index;
  j["name"] = r.name;
  j["design"] = r.design;
  j["overrides"] = Json::object();
  for (const auto& [path, value] : r.overrides) j["overrides"][path] = value;
  j["key"] = r.key;
  j["status"] = to_string(r.status);
  j["exit_code"] = r.status == VariantStatus::Missing ? Json(nullptr) : Json(r.exit_code);
  j["message"] = r.message;
  if (r.mesh) {
    const MeshFacts& m = *r.mesh;
    j["kind"] = m.kind;
    j["units"] = m.units;
    j["vertices"] = m.vertices;
    j["triangles"] = m.triangles;
    j["volume"] = m.volume;
    j["area"] = m.area;
    j["valid"] = m.valid;
    j["bounding_box"] = bounding_box_json(m);
    j["max_deviation"] = m.max_deviation;
    j["tolerance"] = m.tolerance;
  }
  if (!r.build.empty()) j["build"] = facts_json(r.build);
  j["files"] = Json::array();
  for (const RowFile& f : r.files) {
    j["files"].push_back({{"path", f.path},
                          {"format", f.format},
                          {"units", f.units},
                          {"bytes", f.bytes},
                          {"sha256", f.sha256}});
  }
  j["skipped_outputs"] = Json::array();
  for (const SkippedOutput& s : r.skipped)
    j["skipped_outputs"].push_back({{"format", s.format}, {"reason", s.reason}});
  j["timings_ms"] = Json::object();
  for (const auto& [stage, ms] : r.timings_ms) j["timings_ms"][stage] = ms;
  return j;
}

ItemFacts row_facts(const BatchRow& r) {
  ItemFacts item;
  item.name = r.name;
  item.status = r.status;
  item.message = r.status == VariantStatus::Missing ? "not run yet" : r.message;
  item.mesh = r.mesh;
  if (r.status == VariantStatus::Ok && r.mesh) {
    // Written: the verdict every report gives the same files (a written open surface is for viewing).
    set_written_verdict(item, *r.mesh);
    if (!r.message.empty()) {  // the warnings of skipped outputs say more than "valid"
      item.message = item.status == ItemStatus::Ok ? r.message : item.message + "; " + r.message;
    }
  } else if (item.message.empty() && r.status == VariantStatus::Ok) {
    item.message = kValidForFabrication;
  }
  for (const RowFile& f : r.files) item.files.push_back(f.path);
  item.timings_ms = r.timings_ms;
  return item;
}

BatchRow row_from_json(const nlohmann::ordered_json& j) {
  try {
    BatchRow r;
    r.index = field<std::size_t>(j, "index");
    r.name = field<std::string>(j, "name");
    r.design = field<std::string>(j, "design");
    for (const auto& [path, value] : j.at("overrides").items())
      r.overrides.emplace_back(path, value.get<std::string>());
    r.key = field<std::string>(j, "key");
    r.status = parse_variant_status(field<std::string>(j, "status"));
    r.exit_code = j.at("exit_code").is_null() ? 0 : field<int>(j, "exit_code");
    r.message = field<std::string>(j, "message");
    if (j.contains("kind")) {
      MeshFacts m;
      m.kind = field<std::string>(j, "kind");
      m.measured = m.kind != "curve";  // a curve design writes a drawing, no mesh
      m.units = field<std::string>(j, "units");
      m.vertices = field<std::size_t>(j, "vertices");
      m.triangles = field<std::size_t>(j, "triangles");
      m.volume = field<double>(j, "volume");
      m.area = field<double>(j, "area");
      m.valid = field<bool>(j, "valid");
      m.bbox_min = point(j.at("bounding_box").at("min"));
      m.bbox_max = point(j.at("bounding_box").at("max"));
      m.max_deviation = field<double>(j, "max_deviation");
      m.tolerance = field<double>(j, "tolerance");
      r.mesh = m;
    }
    if (j.contains("build")) r.build = facts_from_json(j.at("build"));
    for (const auto& f : j.at("files")) {
      r.files.push_back({field<std::string>(f, "path"), field<std::string>(f, "format"),
                         field<std::string>(f, "units"), field<std::uint64_t>(f, "bytes"),
                         field<std::string>(f, "sha256")});
    }
    for (const auto& s : j.at("skipped_outputs"))
      r.skipped.push_back({field<std::string>(s, "format"), field<std::string>(s, "reason")});
    for (const auto& [stage, ms] : j.at("timings_ms").items())
      r.timings_ms.emplace_back(stage, ms.get<double>());
    return r;
  } catch (const nlohmann::ordered_json::exception& e) {
    throw InputError(fmt::format("summary row: {}", e.what()));
  }
}

std::string csv_header(const std::vector<std::string>& parameters) {
  std::string line;
  for (const char* c : {"index", "name", "design"}) line += std::string(line.empty() ? "" : ",") + c;
  for (const std::string& p : parameters) line += "," + csv_cell(parameter_column(p));
  for (std::size_t i = 3; i < std::size(kFixedColumns); ++i) line += std::string(",") + kFixedColumns[i];
  return line + ",resolve_ms,job_ms,record_ms\n";
}

std::string csv_line(const BatchRow& r, const std::vector<std::string>& parameters) {
  std::string line = fmt::format("{},{},{}", r.index, csv_cell(r.name), csv_cell(r.design));
  for (const std::string& p : parameters) {
    std::string value;
    for (const auto& [path, v] : r.overrides) {
      if (path == p) value = v;
    }
    line += "," + csv_cell(value);
  }
  line += fmt::format(",{},{},{},{}", to_string(r.status),
                      r.status == VariantStatus::Missing ? "" : std::to_string(r.exit_code),
                      csv_cell(r.message), r.key);
  if (r.mesh) {
    const MeshFacts& m = *r.mesh;
    line += fmt::format(",{},{},{},{},{},{},{}", m.kind, m.units, m.vertices, m.triangles, number(m.volume),
                        number(m.area), m.valid ? "true" : "false");
    for (const Vec3& corner : {m.bbox_min, m.bbox_max}) {
      for (int axis = 0; axis < 3; ++axis) line += "," + number(corner[axis]);
    }
    line += fmt::format(",{},{}", number(m.max_deviation), number(m.tolerance));
  } else {
    line += std::string(15, ',');
  }
  std::string files;
  for (const RowFile& f : r.files) files += (files.empty() ? "" : ";") + f.path;
  line += "," + csv_cell(files);
  line += fmt::format(",{:.3f},{:.3f},{:.3f}\n", timing(r.timings_ms, "resolve"), timing(r.timings_ms, "job"),
                      timing(r.timings_ms, "record"));
  return line;
}

}  // namespace fabmesh
