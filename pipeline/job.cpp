#include "pipeline/job.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <optional>

#include "geometry/core/errors.h"
#include "geometry/mesh/bounding_box.h"
#include "pipeline/build_design.h"
#include "pipeline/outputs.h"
#include "pipeline/planned_outputs.h"
#include "pipeline/validate_built.h"

namespace fabmesh {
namespace {

// Share of the tolerance kept for output quantization (Draco, float32 files),
// unless the outputs' number formats need more (build_within_budget).
constexpr double kOutputShare = 0.1;

TriangleSoup scaled(const TriangleSoup& soup, double factor) {
  if (factor == 1.0) return soup;
  TriangleSoup out = soup;
  for (Vec3& p : out.vertices) p *= factor;
  return out;
}

std::vector<const OutputFormat*> formats_of(const Design& design, const JobOptions& options) {
  std::vector<const OutputFormat*> formats;
  if (!options.export_format) {
    formats = resolve_outputs(design);
  } else {
    Design one = design;
    one.common.outputs = {{*options.export_format, "--export-format " + *options.export_format, 0, 0}};
    formats = resolve_outputs(one);
  }
  // Pictures asked for by the command (a report's): those the design has content for, once.
  for (const std::string& name : options.also_formats) {
    const OutputFormat* f = find_output_format(name);
    if (f == nullptr || !has_content(design, f->content) || !f->kinds.test(design.body.index())) continue;
    if (std::find(formats.begin(), formats.end(), f) == formats.end()) formats.push_back(f);
  }
  return formats;
}

double largest_coordinate(const BuiltMesh& built) {
  double largest = 0.0;
  for (const Vec3& p : built.soup.vertices) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  for (const NamedSoup& part : built.mould_parts) {
    for (const Vec3& p : part.soup.vertices) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  }
  return largest;
}

// Builds `design` within its tolerance less what writing needs. The build
// first gets all but a tenth; when the outputs' number formats (float32,
// 3MF's decimals) move vertices of a mesh this large by more than the build
// left, it builds again keeping exactly what they need: a mesh built within a
// smaller tolerance lies within twice the tolerance of the first one's
// coordinates, so that need, taken at coordinates 2 x tolerance larger, holds.
BuiltMesh build_within_budget(const Design& design, BuildContext& context,
                              const std::vector<const OutputFormat*>& formats, double export_scale) {
  BuiltMesh built = build_design(design, context);
  const double tolerance = context.common.tolerance;
  const double largest = largest_coordinate(built) + 2.0 * tolerance;
  double need = 0.0;
  for (const OutputFormat* f : formats)
    need = std::max(need, writing_error_bound(f->name, largest, export_scale));
  if (need <= tolerance - built.max_deviation || need >= tolerance) return built;
  context.tolerance = tolerance - need;
  return build_design(design, context);
}

std::string path_with_suffix(const Design& design, const std::string& suffix, const JobOptions& options) {
  return (std::filesystem::path(options.out_dir) / (design.common.name + suffix)).string();
}

std::string path_of(const Design& design, const OutputFormat& format, const JobOptions& options) {
  if (options.output_file) return *options.output_file;
  return path_with_suffix(design, std::string(format.file_suffix), options);
}

// A job's outputs as they are encoded: the file each goes to and its encoding.
using TakeOutput = std::function<void(const std::string& file, Encoded& encoded)>;

// Builds and validates `design`, then encodes its outputs one by one, each
// handed to `take` while the mesh it may refer to (Encoded::stream) lives.
JobReport build_and_encode(const Design& design, const JobOptions& options, const TakeOutput& take) {
  JobReport report;
  DesignCommon common = design.common;
  if (options.export_units) common.export_units = *options.export_units;
  report.name = common.name;
  report.kind = kind_name(design);
  report.units = common.units;
  report.export_units = common.export_units;
  report.tolerance = common.tolerance;
  report.notes = common.notes;
  report.parameters = common.parameters;
  StageTimer watch(report.timings_ms, options.on_stage);
  const std::vector<const OutputFormat*> formats = formats_of(design, options);
  report.warnings = unused_block_warnings(design, options, formats);
  if (options.output_file && formats.size() != 1) {
    std::string names;
    for (const OutputFormat* f : formats) names += (names.empty() ? "" : ", ") + std::string(f->name);
    throw InputError(
        fmt::format("the design asks for {} outputs ({}); -o {} takes one: choose it with "
                    "--export-format",
                    formats.size(), names, *options.output_file));
  }
  const bool wants_cutting = std::any_of(formats.begin(), formats.end(), [](const OutputFormat* f) {
    return f->content == OutputContent::Drawing || f->content == OutputContent::Toolpath;
  });
  const double export_scale = metres_per_unit(common.units) / metres_per_unit(common.export_units);
  BuildContext context{common, (1.0 - kOutputShare) * common.tolerance, wants_cutting, watch,
                       process_memory_limit()};
  context.wants_exact = std::any_of(formats.begin(), formats.end(),
                                    [](const OutputFormat* f) { return f->content == OutputContent::Exact; });
  const BuiltMesh built = build_within_budget(design, context, formats, export_scale);
  if (options.on_built) options.on_built(built);
  report.build_tolerance = context.tolerance;
  report.max_deviation = built.max_deviation;
  report.tolerance_shares = built.tolerance_shares;
  report.build = built.facts;
  report.warnings.insert(report.warnings.end(), built.warnings.begin(), built.warnings.end());
  report.validation = built.validation;
  report.purpose = built.purpose;
  const std::string what = fmt::format("{} '{}'", report.kind, report.name);
  require_fit(report.validation, built.purpose, what);  // the builder validated it (validate_built)
  if (built.purpose == MeshPurpose::Viewing && common.purpose != Purpose::View) {
    throw ValidationFailed(fmt::format(
        "{}: the mesh is open ({} boundary edges): not fit for fabrication, so nothing is written; give the "
        "surface a `thickness` for a solid shell, or set `purpose: view` to write it for viewing",
        what, report.validation.boundary_edges));
  }
  if (!built.soup.vertices.empty()) {
    // The mesh's box, in model units (the report's bounding_box).
    const BoundingBox box = bounding_box(built.soup.vertices);
    report.bbox_min = box.lo;
    report.bbox_max = box.hi;
  } else if (!built.cutting.empty()) {
    const auto [lo, hi] = cut_bounds(built.cutting);
    report.bbox_min = Vec3(lo.x(), lo.y(), 0.0);
    report.bbox_max = Vec3(hi.x(), hi.y(), 0.0);
  }
  if (!options.encode) return report;
  // The encoders get the tolerance the build left unused, and the mesh in the
  // export unit (the built mesh itself when the units agree: no copy).
  const std::optional<TriangleSoup> rescaled =
      export_scale == 1.0 ? std::nullopt : std::optional<TriangleSoup>(scaled(built.soup, export_scale));
  const TriangleSoup& exported = rescaled ? *rescaled : built.soup;
  const double output_tolerance = common.tolerance - built.max_deviation;
  for (const OutputFormat* format : formats) {
    const std::string path = path_of(design, *format, options);
    try {
      for (Encoded& e : format->encode({common, built, exported, export_scale, output_tolerance, path})) {
        const std::string file = e.suffix.empty() ? path : path_with_suffix(design, e.suffix, options);
        report.files.push_back({file, std::string(format->name), e.units, e.added_error, e.valid_as_written});
        report.outputs.push_back(file);
        take(file, e);
      }
    } catch (const OutputError& e) {
      if (common.on_output_error == OutputErrorPolicy::Fail) {
        // At the `outputs:` entry that asked for it (or the list, for a kind's default outputs).
        const auto asked = std::find_if(common.outputs.begin(), common.outputs.end(),
                                        [&](const OutputRequest& r) { return r.format == format->name; });
        const std::string key =
            asked != common.outputs.end()
                ? fmt::format("outputs[{}]", static_cast<std::size_t>(asked - common.outputs.begin()))
                : "outputs";
        throw OutputError(e.format(), e.what(), placed(common, ErrorLocation{key}));
      }
      report.skipped.push_back({std::string(format->name), e.what()});
    }
    watch.lap("encode_" + std::string(format->name));
  }
  if (report.files.empty() && !report.skipped.empty()) {
    // `skip` writes the others; with none left, the job would make nothing it was asked for.
    std::string reasons;
    for (const SkippedOutput& s : report.skipped) reasons += (reasons.empty() ? "" : "; ") + s.reason;
    throw OutputError(report.skipped.front().format,
                      fmt::format("every output was skipped, so nothing is written: {}", reasons),
                      placed(common, ErrorLocation{"outputs"}));
  }
  return report;
}

void create_folders(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    if (folder.empty()) continue;
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) throw_write_failure(folder.string(), "cannot create the output folder", ec.value());
  }
}

}  // namespace

std::vector<const OutputFormat*> job_formats(const Design& design, const JobOptions& options) {
  return formats_of(design, options);
}

PreparedJob prepare_job(const Design& design, const JobOptions& options) {
  PreparedJob job;
  job.on_stage = options.on_stage;
  job.report = build_and_encode(design, options, [&](const std::string& file, Encoded& e) {
    if (e.stream) e.stream([&](std::string_view piece) { e.bytes.append(piece); });
    job.files.push_back({file, std::move(e.bytes)});
  });
  return job;
}

JobReport write_job(PreparedJob job) {
  StageTimer watch(job.report.timings_ms, job.on_stage);
  std::vector<std::string> paths;
  for (const FileWrite& f : job.files) paths.push_back(f.path);
  create_folders(paths);
  write_files_atomically(job.files);
  watch.lap("write");
  return std::move(job.report);
}

JobReport run_job(const Design& design, const JobOptions& options) {
  // Each output goes to its temporary file as soon as it is encoded (a
  // streamed one piece by piece, never whole in memory); the temporaries are
  // renamed into place together once every output is made, and removed when
  // anything fails: all or nothing, as write_job.
  std::vector<PendingFile> pending;
  JobReport report = build_and_encode(design, options, [&](const std::string& file, Encoded& e) {
    create_folders({file});
    pending.emplace_back(file);
    PendingFile& out = pending.back();
    if (e.stream) {
      e.stream([&](std::string_view piece) { out.write(piece); });
    } else {
      out.write(e.bytes);
      e.bytes = std::string();  // written: its memory is free for the next output
    }
  });
  StageTimer watch(report.timings_ms, options.on_stage);
  for (PendingFile& f : pending) f.finish();
  commit_files(pending);
  watch.lap("write");
  return report;
}

}  // namespace fabmesh
