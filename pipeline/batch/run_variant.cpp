#include "pipeline/batch/run_variant.h"

#include <dirent.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "geometry/core/errors.h"
#include "pipeline/batch/output_links.h"
#include "pipeline/batch/sha256.h"
#include "pipeline/failure.h"
#include "pipeline/job.h"
#include "pipeline/report.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Removes the regular files of `folder` not in `keep` (file names); the folder
// too when nothing is left. Hidden files (temporaries of writers) are left
// alone, and so are links: a folder that is a link is not tidied at all, and
// a link in it is not followed (opened with O_NOFOLLOW, entries judged by
// lstat and removed relative to the folder's descriptor).
void tidy_folder(const fs::path& folder, const std::set<std::string>& keep) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;  // missing, not a folder, or a link
  DIR* dir = ::fdopendir(fd);
  if (dir == nullptr) {
    ::close(fd);
    return;
  }
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (name.empty() || keep.count(name) || name.front() == '.') continue;
    struct stat st {};
    if (::fstatat(fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode)) continue;
    ::unlinkat(fd, name.c_str(), 0);
  }
  ::closedir(dir);
  if (keep.empty()) ::rmdir(folder.c_str());  // only when empty; never a link
}

// How the file at `path` differs from a ledger's record of it (`bytes`,
// `sha256`): "is missing", "is not a regular file", "has N bytes, not M",
// "no longer matches its digest"; nothing when it is the same. Read a block
// at a time, never through a link.
std::optional<std::string> file_differs(const std::string& path, std::uint64_t bytes,
                                        const std::string& sha256) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return std::string(errno == ENOENT ? "is missing" : "cannot be read");
  struct stat st {};
  std::optional<std::string> differs;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    differs = "is not a regular file";
  } else if (static_cast<std::uint64_t>(st.st_size) != bytes) {
    differs = fmt::format("has {} bytes, not the {} recorded", st.st_size, bytes);
  } else {
    Sha256 digest;
    std::string block(std::size_t{1} << 16, '\0');
    for (;;) {
      const ssize_t n = ::read(fd, block.data(), block.size());
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        differs = "cannot be read";
        break;
      }
      if (n == 0) break;
      digest.update(std::string_view(block.data(), static_cast<std::size_t>(n)));
    }
    if (!differs && digest.hex_digest() != sha256) differs = "no longer matches the digest recorded";
  }
  ::close(fd);
  return differs;
}

// True when `j` has no `key`, or one that `is` (a type test) holds for:
// json::value(key, default) throws for a key of another type.
bool has_type(const nlohmann::json& j, const char* key, bool (nlohmann::json::*is)() const noexcept) {
  const auto it = j.find(key);
  return it == j.end() || ((*it).*is)();
}

// A file of a row as row_json writes it: an object whose path and digest are
// text and whose size is a whole number. A row that passed the ledger's check
// can still hold anything else (edited by hand, or by another program).
bool is_file_entry(const nlohmann::json& f) {
  return f.is_object() && has_type(f, "path", &nlohmann::json::is_string) &&
         has_type(f, "sha256", &nlohmann::json::is_string) &&
         has_type(f, "bytes", &nlohmann::json::is_number_unsigned);
}

}  // namespace

std::string variant_folder(const std::string& out_dir, const std::string& name) {
  return (fs::path(out_dir) / name).string();
}

BatchRow run_variant(const BatchManifest& manifest, std::size_t index, const PlannedVariant& planned,
                     const std::string& out_dir, PlaneMemo* planes) {
  const Variant v = manifest.variant(index);
  BatchRow row;
  row.index = index;
  row.name = planned.name;
  row.design = planned.design;
  row.overrides = planned.overrides;
  row.key = planned.key;
  const fs::path folder = variant_folder(out_dir, v.name);
  std::error_code ec;
  const bool linked = is_link(folder.string());  // refused below: never written or tidied through
  const bool existed = fs::exists(folder, ec);
  std::set<std::string> written;
  Clock::time_point start = Clock::now();
  double job_ms = 0.0, record_ms = 0.0;
  StageTimings stages;
  try {
    refuse_link(folder.string(), "variant folder");
    std::string canonical;
    BlankedText plane_text{plane_free_keys(), {}};
    const Design design = manifest.bases[v.base].resolve(variant_overrides(manifest, v), &canonical,
                                                         planes != nullptr ? &plane_text : nullptr);
    if (variant_key(canonical) != planned.key) {
      throw std::runtime_error(
          "its design or a file it reads changed while the batch ran (its key differs from the plan's): run "
          "the "
          "batch again");
    }
    row.timings_ms.emplace_back("resolve", ms_since(start));
    JobOptions options;
    options.out_dir = folder.string();
    if (planes != nullptr) options.reuse = {planes, std::move(plane_text.text)};  // read by countertops
    auto [report, job] = prepare_job(design, options);
    const Clock::time_point digest_start = Clock::now();
    for (const EncodedFile& e : job.files) {
      const OutputFile& f = e.file;
      const std::string file_name = fs::path(f.path).filename().string();
      row.files.push_back(
          {v.name + "/" + file_name, f.format, f.units, e.encoded.bytes.size(), sha256_hex(e.encoded.bytes)});
      written.insert(file_name);
    }
    record_ms += ms_since(digest_start);
    {
      StageTimer watch(report.timings_ms);
      write_job(job);
      watch.lap("write");
    }
    for (const auto& stage : report.timings_ms) job_ms += stage.second;
    stages = report.timings_ms;
    record_result(row, report);
    row.status = VariantStatus::Ok;
  } catch (...) {
    const Failure failure = describe_failure(std::current_exception(), planned.design);
    row.status = status_of(failure.exit_code);
    row.message = failure.message;
    row.files.clear();
    row.mesh.reset();
    written.clear();
    if (row.timings_ms.empty()) row.timings_ms.emplace_back("resolve", ms_since(start));
  }
  row.exit_code = exit_code_of(row.status);
  const Clock::time_point tidy_start = Clock::now();
  if (!linked && (existed || row.status != VariantStatus::Ok)) tidy_folder(folder, written);
  record_ms += ms_since(tidy_start);
  row.timings_ms.emplace_back("job", job_ms);
  row.timings_ms.emplace_back("record", record_ms);
  for (const auto& stage : stages) row.timings_ms.push_back(stage);
  return row;
}

namespace {

// Whether `relative` names a file inside the batch folder as fabmesh writes
// them: a relative path of plain names (no "..", ".", or empty ones).
bool inside_batch_folder(const std::string& relative) {
  const fs::path path(relative);
  if (relative.empty() || path.is_absolute() || relative.find('\0') != std::string::npos) return false;
  return std::none_of(path.begin(), path.end(),
                      [](const fs::path& part) { return part.empty() || part == ".." || part == "."; });
}

// The status a row's text names, in the ledger's words; nothing for other text.
std::optional<VariantStatus> known_status(const std::string& text) {
  try {
    return parse_variant_status(text);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

}  // namespace

bool row_stands(std::string_view row_json, const std::string& out_dir, std::string* why) {
  const nlohmann::json j = nlohmann::json::parse(row_json, nullptr, false);
  if (!j.is_object() || !has_type(j, "status", &nlohmann::json::is_string)) return false;
  const std::optional<VariantStatus> status = known_status(j.value("status", ""));
  if (!status) return false;
  if (*status != VariantStatus::Ok) return is_final(*status);  // invalid and bad input stand as they are
  if (!j.contains("files")) return false;
  if (!j.at("files").is_array() || !std::all_of(j.at("files").begin(), j.at("files").end(), is_file_entry)) {
    if (why != nullptr) *why = "its row lists its files in a form fabmesh does not write: built again";
    return false;
  }
  for (const auto& f : j.at("files")) {
    const std::string relative = f.value("path", "");
    if (!inside_batch_folder(relative)) {
      // A planted or damaged ledger must not make a rerun read outside DIR.
      if (why != nullptr)
        *why = fmt::format("its row names a file outside the batch folder ({}): built again", relative);
      return false;
    }
    const std::string path = (fs::path(out_dir) / relative).string();
    const std::optional<std::string> changed =
        file_differs(path, f.value("bytes", std::uint64_t{0}), f.value("sha256", ""));
    if (changed) {
      if (why != nullptr) *why = fmt::format("its file {} {}: built again", relative, *changed);
      return false;
    }
  }
  return true;
}

}  // namespace fabmesh
