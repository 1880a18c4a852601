#include "pipeline/job.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <utility>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "geometry/mesh/bounding_box.h"
#include "pipeline/build_design.h"
#include "pipeline/validate_parts.h"

namespace fabmesh {
namespace {

// Share of the tolerance kept for output quantization (Draco, float32 files),
// unless the outputs' number formats need more (build_within_budget).
constexpr double kOutputShare = 0.1;

// A draft's tolerance, in the design's: coarse enough to build and draw at
// once, fine enough to show the shape. A builder that refuses its coarse
// mesh (a vessel shell whose walls meet at that tolerance) is asked again at
// half the tolerance, down to kLeastDraftTolerance.
constexpr double kDraftTolerance = 32.0;
constexpr double kLeastDraftTolerance = 4.0;

// A surface's draft: its sheet refined for the surface alone at this many
// times the design's tolerance, then thickened (surface_draft): the wash
// basin's shell in 7 700 triangles and about 10 ms, where its builder's
// coarsest proven mesh took 10 000 and 25 ms, most of them the offset
// sheets' grid crowding toward the rim's singular corners.
constexpr double kSurfaceDraftTolerance = 2.0;

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
    if (f == nullptr || !applies_to(*f, design)) continue;
    if (std::find(formats.begin(), formats.end(), f) == formats.end()) formats.push_back(f);
  }
  return formats;
}

// "a or b", "a, b or c".
std::string either(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += names[i];
  }
  return text;
}

// Whether `format` writes a vessel's casting master (master_stl, master_3mf, master_step).
bool writes_master(const OutputFormat& format) { return format.name.substr(0, 7) == "master_"; }

// Whether `format` is made from the design's `block`: the mould's formats
// (its casting cases too), and the casting master's (its spare is the
// mould's); the router's.
bool made_from(const OutputFormat& format, DesignBlock block) {
  return format.block == block || (block == DesignBlock::Mould && writes_master(format));
}

// Warnings about the design's own `outputs` list: a `mould:` or `cnc:` block
// for which it asks for no output, so nothing made from it is written
// ("cup.yaml:12:1: mould: ... add mould_stl, mould_3mf, mould_step, ... to
// `outputs`"). None when the formats come from the command line or are the
// kind's defaults.
std::vector<std::string> unused_block_warnings(const Design& design, const JobOptions& options,
                                               const std::vector<const OutputFormat*>& formats) {
  std::vector<std::string> warnings;
  if (options.export_format || design.common.outputs.empty()) return warnings;
  struct Block {
    DesignBlock block;
    const char* key;
    const char* what;
  };
  for (const Block& block : {Block{DesignBlock::Mould, "mould", "no part of the mould is written"},
                             Block{DesignBlock::Cnc, "cnc", "the router path is not planned"}}) {
    if (!has_block(design, block.block)) continue;
    const bool used = std::any_of(formats.begin(), formats.end(),
                                  [&](const OutputFormat* f) { return made_from(*f, block.block); });
    if (used) continue;
    std::vector<std::string> users;
    for (const OutputFormat& f : output_formats()) {
      if (made_from(f, block.block) && applies_to(f, design)) users.emplace_back(f.name);
    }
    warnings.push_back(
        fmt::format("{}: `outputs` asks for no output made from it, so {}: add {} to `outputs` "
                    "(or remove `{}`)",
                    key_label(design.common, block.key), block.what, either(users), block.key));
  }
  return warnings;
}

std::string path_in(const std::string& out_dir, const DesignCommon& common, const std::string& suffix) {
  return (std::filesystem::path(out_dir) / (common.name + suffix)).string();
}

// The files of mould_stl: one per part, named as build_vessel names the parts.
std::vector<std::string> mould_part_suffixes(const Design& design) {
  std::vector<std::string> suffixes;
  const auto* vessel = std::get_if<VesselDesign>(&design.body);
  if (vessel == nullptr || !vessel->mould) return suffixes;
  for (int k = 1; k <= vessel->mould->parts; ++k) suffixes.push_back(fmt::format(".mould-side-{}.stl", k));
  if (vessel->mould->base_part) suffixes.emplace_back(".mould-base.stl");
  return suffixes;
}

double largest_coordinate(const Result& result) {
  double largest = 0.0;
  for (const Part& part : result.parts) {
    for (const Vec3& p : part.mesh.vertices) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  }
  return largest;
}

// Builds `design` within its tolerance less what writing needs. The build
// first gets all but a tenth; when the outputs' number formats (float32,
// 3MF's decimals) move vertices of a mesh this large by more than the build
// left, it builds again keeping exactly what they need: a mesh built within a
// smaller tolerance lies within twice the tolerance of the first one's
// coordinates, so that need, taken at coordinates 2 x tolerance larger, holds.
Result build_within_budget(const Design& design, const JobPlan& plan, BuildContext& context) {
  Result built = build_design(design, context);
  const double tolerance = context.common.tolerance;
  const double largest = largest_coordinate(built) + 2.0 * tolerance;
  double need = 0.0;
  for (const OutputFormat* f : plan.formats) {
    if (f->writing_error != nullptr) need = std::max(need, f->writing_error(largest, plan.export_scale));
  }
  if (need <= tolerance - built.max_deviation || need >= tolerance) return built;
  context.tolerance = tolerance - need;
  return build_design(design, context);
}

// The identity of `design`'s result: what it is, before anything is built.
void set_identity(Result& result, const DesignCommon& common) {
  result.name = common.name;
  result.design_file = common.path;
  result.units = common.units;
  result.export_units = common.export_units;
  result.parameters = common.parameters;
  result.parameter_set = common.parameter_set;
  result.tolerance = common.tolerance;
  result.notes = common.notes;
}

// The box of the product, or of the drawing of a design without a mesh.
void set_bounds(Result& result) {
  if (const Part* part = product(result); part != nullptr && !part->mesh.vertices.empty()) {
    const BoundingBox box = bounding_box(part->mesh.vertices);
    result.bbox_min = box.lo;
    result.bbox_max = box.hi;
  } else if (const auto* curve = std::get_if<CurveProducts>(&result.products);
             curve && !curve->drawing.empty()) {
    const auto [lo, hi] = cut_bounds(curve->drawing);
    result.bbox_min = Vec3(lo.x(), lo.y(), 0.0);
    result.bbox_max = Vec3(hi.x(), hi.y(), 0.0);
  }
}

TriangleSoup scaled(const TriangleSoup& soup, double factor) {
  TriangleSoup out = soup;
  for (Vec3& p : out.vertices) p *= factor;
  return out;
}

// The place of the `outputs:` entry that asked for `format` (or the list,
// for a kind's default outputs).
ErrorLocation output_entry(const DesignCommon& common, std::string_view format) {
  const auto asked = std::find_if(common.outputs.begin(), common.outputs.end(),
                                  [&](const OutputRequest& r) { return r.format == format; });
  const std::string key =
      asked != common.outputs.end()
          ? fmt::format("outputs[{}]", static_cast<std::size_t>(asked - common.outputs.begin()))
          : "outputs";
  return placed(common, ErrorLocation{key});
}

// `skip` writes the others; with none left, the job would make nothing it was asked for.
void require_something(const std::vector<SkippedOutput>& skipped, std::size_t files,
                       const DesignCommon& common) {
  if (files != 0 || skipped.empty()) return;
  std::string reasons;
  for (const SkippedOutput& s : skipped) reasons += (reasons.empty() ? "" : "; ") + s.reason;
  throw OutputError(skipped.front().format,
                    fmt::format("every output was skipped, so nothing is written: {}", reasons),
                    placed(common, ErrorLocation{"outputs"}));
}

// The job's outputs, encoded one at a time: each one's files are handed to
// the caller before the next is encoded, so a streamed output is written
// while the result it refers to lives and an output's bytes can be freed.
class Encoder {
 public:
  Encoder(const Result& result, const JobPlan& plan, StageTimings& timings)
      : result_(result),
        plan_(plan),
        watch_(timings, plan.on_stage),
        rescaled_(plan.export_scale == 1.0 || product(result) == nullptr
                      ? std::nullopt
                      : std::optional<TriangleSoup>(scaled(product(result)->mesh, plan.export_scale))) {}

  /// Encodes output `i`; its files, or none when it was skipped (skipped()).
  /// A kitchen's mesh outputs write each piece to a file of its own
  /// (NAME.piece-1.stl), not the whole top.
  std::vector<EncodedFile> encode(std::size_t i) {
    const OutputFormat& format = *plan_.formats[i];
    const DesignCommon& common = plan_.common;
    const TriangleSoup empty;
    const Part* own = product(result_);
    const TriangleSoup& exported = rescaled_ ? *rescaled_ : own != nullptr ? own->mesh : empty;
    // The encoders get the tolerance the build left unused, and the mesh in the export unit.
    const double left = common.tolerance - result_.max_deviation;
    const EncodeContext context{common, result_, exported, plan_.export_scale, left, plan_.paths[i]};
    std::vector<EncodedFile> files;
    auto keep = [&](Encoded& e) {
      const std::string path = e.suffix.empty() ? plan_.paths[i] : path_in(plan_.out_dir, common, e.suffix);
      OutputFile file{path, std::string(format.name), e.units, e.added_error, e.valid_as_written, e.parts};
      files.push_back({std::move(file), std::move(e)});
    };
    const std::vector<const Part*> pieces = parts_of(result_, PartRole::Piece);
    const bool per_piece = format.source == OutputSource::Meshes && format.block == DesignBlock::None &&
                           format.writing_error != nullptr && !pieces.empty();
    try {
      if (!per_piece) {
        for (Encoded& e : format.encode(context)) keep(e);
      }
      for (const Part* piece : per_piece ? pieces : std::vector<const Part*>{}) {
        const TriangleSoup mesh = scaled(piece->mesh, plan_.export_scale);
        const std::string suffix = "." + piece->name + std::string(format.file_suffix);
        const EncodeContext one{
            common, result_, mesh, plan_.export_scale, left, path_in(plan_.out_dir, common, suffix), piece};
        for (Encoded& e : format.encode(one)) {
          e.suffix = suffix;
          e.parts = {piece->name};
          if (e.stream) {  // it streams from `mesh`, which does not outlive this turn
            e.stream([&e](std::string_view bytes) { e.bytes.append(bytes); });
            e.stream = nullptr;
          }
          keep(e);
        }
      }
    } catch (const OutputError& e) {
      if (common.on_output_error == OutputErrorPolicy::Fail)
        throw OutputError(e.format(), e.what(), output_entry(common, format.name));
      skipped_.push_back({std::string(format.name), e.what()});
    }
    return files;
  }

  /// Ends output `i`'s stage ("encode_FORMAT"): encoding, and writing its temporary when it was written.
  void lap(std::size_t i) { watch_.lap("encode_" + std::string(plan_.formats[i]->name)); }

  const std::vector<SkippedOutput>& skipped() const { return skipped_; }

 private:
  const Result& result_;
  const JobPlan& plan_;
  StageTimer watch_;
  std::optional<TriangleSoup> rescaled_;
  std::vector<SkippedOutput> skipped_;
};

void create_folders(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    if (folder.empty()) continue;
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) throw_write_failure(folder.string(), "cannot create the output folder", ec.value());
  }
}

// The result of `design` built and required fit, as every job starts.
Result fit_result(const Design& design, const JobPlan& plan) {
  Result result = build_job(design, plan);
  require_fit(result, design.common.purpose);
  return result;
}

}  // namespace

JobPlan plan_job(const Design& design, const JobOptions& options) {
  JobPlan plan;
  plan.common = design.common;
  if (options.export_units) plan.common.export_units = *options.export_units;
  plan.formats = formats_of(design, options);
  plan.warnings = unused_block_warnings(design, options, plan.formats);
  if (options.output_file && plan.formats.size() != 1) {
    std::string names;
    for (const OutputFormat* f : plan.formats) names += (names.empty() ? "" : ", ") + std::string(f->name);
    throw InputError(
        fmt::format("the design asks for {} outputs ({}); -o {} takes one: choose it with "
                    "--export-format",
                    plan.formats.size(), names, *options.output_file));
  }
  plan.out_dir = options.out_dir;
  for (const OutputFormat* f : plan.formats) {
    plan.paths.push_back(options.output_file
                             ? *options.output_file
                             : path_in(options.out_dir, plan.common, std::string(f->file_suffix)));
    plan.wants_drawing =
        plan.wants_drawing || f->source == OutputSource::Drawing || f->source == OutputSource::Program;
    plan.wants_exact = plan.wants_exact || f->source == OutputSource::Exact;
  }
  plan.export_scale = metres_per_unit(plan.common.units) / metres_per_unit(plan.common.export_units);
  plan.on_stage = options.on_stage;
  plan.reuse = options.reuse;
  return plan;
}

std::vector<PlannedFile> planned_files(const Design& design, const JobPlan& plan) {
  std::vector<PlannedFile> files;
  for (std::size_t i = 0; i < plan.formats.size(); ++i) {
    const OutputFormat& format = *plan.formats[i];
    const std::string name(format.name);
    if (format.file_suffix.find("PART") != std::string_view::npos && plan.paths[i] != "-" &&
        plan.paths[i].find("PART") != std::string::npos) {
      for (const std::string& suffix : mould_part_suffixes(design))
        files.push_back({path_in(plan.out_dir, plan.common, suffix), name});
    } else {
      files.push_back({plan.paths[i], name});
    }
  }
  return files;
}

Result build_job(const Design& design, const JobPlan& plan) {
  Result result;
  StageTimings timings;
  StageTimer watch(timings, plan.on_stage);
  BuildContext context{plan.common, (1.0 - kOutputShare) * plan.common.tolerance, plan.wants_drawing, watch,
                       process_memory_limit()};
  context.wants_exact = plan.wants_exact;
  context.wants_master = std::any_of(plan.formats.begin(), plan.formats.end(),
                                     [](const OutputFormat* f) { return writes_master(*f); });
  context.wants_cases = std::any_of(plan.formats.begin(), plan.formats.end(),
                                    [](const OutputFormat* f) { return f->name.substr(0, 5) == "case_"; });
  context.reuse = &plan.reuse;
  result = build_within_budget(design, plan, context);
  validate_parts(result, watch);
  set_identity(result, plan.common);
  result.kind = kind_name(design);
  result.build_tolerance = context.tolerance;
  std::vector<std::string> warnings = plan.warnings;
  warnings.insert(warnings.end(), result.warnings.begin(), result.warnings.end());
  result.warnings = std::move(warnings);
  result.timings_ms = std::move(timings);
  set_bounds(result);
  return result;
}

Result build_at(const Design& design, double tolerance) {
  Result result;
  StageTimings timings;
  StageTimer watch(timings);
  const BuildContext context{design.common, tolerance, false, watch, process_memory_limit()};
  result = build_design(design, context);
  validate_parts(result, watch);
  set_identity(result, design.common);
  result.kind = kind_name(design);
  result.build_tolerance = tolerance;
  result.timings_ms = std::move(timings);
  set_bounds(result);
  return result;
}

Result build_preview(const Design& design) {
  if (std::holds_alternative<CurveDesign>(design.body)) {
    throw InputError(
        fmt::format("{}: a curve design has no mesh to preview; try `fabmesh plot`", design.common.name));
  }
  return build_at(design, design.common.tolerance);
}

Result build_draft(const Design& design) {
  if (const auto* surface = std::get_if<SurfaceDesign>(&design.body)) {
    const double tolerance = design.common.tolerance * kSurfaceDraftTolerance;
    Result result = surface_draft(*surface, tolerance);
    set_identity(result, design.common);
    result.kind = kind_name(design);
    result.tolerance = tolerance;
    result.build_tolerance = tolerance;
    set_bounds(result);
    return result;
  }
  for (double factor = kDraftTolerance;; factor /= 2.0) {
    try {
      Result result = build_at(design, design.common.tolerance * factor);
      result.tolerance = result.build_tolerance;
      require_parts_fit(result);  // the product is shown whatever its verdict
      return result;
    } catch (const ValidationFailed&) {
      if (factor / 2.0 < kLeastDraftTolerance) throw;
    }
  }
}

EncodedJob encode_job(const Result& result, const JobPlan& plan) {
  EncodedJob job;
  Encoder encoder(result, plan, job.timings_ms);
  for (std::size_t i = 0; i < plan.formats.size(); ++i) {
    for (EncodedFile& f : encoder.encode(i)) {
      if (f.encoded.stream) {
        f.encoded.stream([&](std::string_view piece) { f.encoded.bytes.append(piece); });
        f.encoded.stream = nullptr;
      }
      job.files.push_back(std::move(f));
    }
    encoder.lap(i);
  }
  job.skipped = encoder.skipped();
  require_something(job.skipped, job.files.size(), plan.common);
  return job;
}

std::vector<OutputFile> write_job(EncodedJob& encoded) {
  std::vector<std::string> paths;
  std::vector<FileWrite> writes;
  std::vector<OutputFile> files;
  for (EncodedFile& f : encoded.files) {
    paths.push_back(f.file.path);
    writes.push_back({f.file.path, std::move(f.encoded.bytes)});
    files.push_back(f.file);
  }
  create_folders(paths);
  write_files_atomically(writes);
  return files;
}

std::pair<Result, EncodedJob> prepare_job(const Design& design, const JobOptions& options) {
  const JobPlan plan = plan_job(design, options);
  Result result = fit_result(design, plan);
  EncodedJob encoded = encode_job(result, plan);
  for (const EncodedFile& f : encoded.files) result.files.push_back(f.file);
  result.skipped = encoded.skipped;
  result.timings_ms.insert(result.timings_ms.end(), encoded.timings_ms.begin(), encoded.timings_ms.end());
  return {std::move(result), std::move(encoded)};
}

Result run_job(const Design& design, const JobOptions& options) {
  const JobPlan plan = plan_job(design, options);
  Result result = fit_result(design, plan);
  // Each output goes to its temporary file as soon as it is encoded (a
  // streamed one piece by piece, never whole in memory); the temporaries are
  // renamed into place together once every output is made, and removed when
  // anything fails: all or nothing, as write_job.
  std::vector<PendingFile> pending;
  {
    Encoder encoder(result, plan, result.timings_ms);
    for (std::size_t i = 0; i < plan.formats.size(); ++i) {
      for (EncodedFile& f : encoder.encode(i)) {
        create_folders({f.file.path});
        pending.emplace_back(f.file.path);
        PendingFile& out = pending.back();
        if (f.encoded.stream) {
          f.encoded.stream([&](std::string_view piece) { out.write(piece); });
        } else {
          out.write(f.encoded.bytes);
        }
        result.files.push_back(std::move(f.file));
      }
      encoder.lap(i);
    }
    result.skipped = encoder.skipped();
  }
  require_something(result.skipped, result.files.size(), plan.common);
  StageTimer watch(result.timings_ms, options.on_stage);
  for (PendingFile& f : pending) f.finish();
  commit_files(pending);
  watch.lap("write");
  return result;
}

}  // namespace fabmesh
