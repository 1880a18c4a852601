#pragma once
// One design through the stages: build and validate (no I/O), encode every
// output, then write them all or none.

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geometry/core/stage_timer.h"
#include "geometry/validation/validate.h"
#include "io/design/design.h"
#include "io/file.h"
#include "pipeline/built_mesh.h"

namespace fabmesh {

struct OutputFormat;

struct JobOptions {
  std::string out_dir = "out";  ///< created when missing
  /// Replaces the design's export unit (`--export-units`) when set.
  std::optional<std::string> export_units;
  /// Replaces the design's outputs by this one format (`--export-format`, `-o FILE.ext`) when set.
  std::optional<std::string> export_format;
  /// The path of the single output (`-o FILE.ext`) instead of out_dir/NAME.ext; "-" is standard output.
  std::optional<std::string> output_file;
  /// Formats added to the design's own (e.g. "png" and "plot" for `run --report`)
  /// where the design's kind and content allow them; unknown names are ignored.
  std::vector<std::string> also_formats;
  /// Told after each stage of the job ("curve", "build", "validate", "encode_stl",
  /// "write", ...), from the thread that runs it: progress of a long run.
  StageObserver on_stage;
  /// Told the design's mesh, curves and validation as soon as they are built
  /// and validated, before the job judges them or encodes anything (the
  /// library hands them to its caller, valid or not).
  std::function<void(const BuiltMesh&)> on_built;
  /// False: build and validate only, as for any output (the same mesh), and
  /// encode none of them: the report then has no outputs, files or skipped
  /// outputs (the studio's interactive build: its export encodes them).
  bool encode = true;
};

/// One file a job wrote.
struct OutputFile {
  std::string path;
  std::string format;
  std::string units;         ///< the unit of its coordinates
  double added_error = 0.0;  ///< how far writing moved any vertex at most, model units
  std::optional<bool> valid_as_written = std::nullopt;  ///< mesh outputs: Encoded::valid_as_written
};

/// An output the job could not make (and skipped, by the design's policy).
struct SkippedOutput {
  std::string format;
  std::string reason;
};

/// What one job did.
struct JobReport {
  std::string name;
  std::string kind;
  std::string units;
  std::string export_units;
  std::vector<std::string> outputs;  ///< paths written (or to be written, for a prepared job)
  std::vector<OutputFile> files;     ///< the same with their format, unit and added error
  std::vector<SkippedOutput> skipped;
  std::vector<std::string> notes;  ///< DesignCommon::notes: how the design's files were read
  /// DesignCommon::parameters: the design's named parameters with the values used.
  std::vector<DesignParameter> parameters;
  /// What the design asks for that deserves a look, e.g. a `mould:` block no
  /// output uses (unused_block_warnings). Shown in the report (`warnings`).
  std::vector<std::string> warnings;
  ValidationReport validation;
  MeshPurpose purpose = MeshPurpose::Fabrication;
  double max_deviation = 0.0;  ///< proven bound of the mesh against the exact shape, model units
  double tolerance = 0.0;
  /// The share of the tolerance the build was given (the rest is kept for
  /// writing the outputs: a tenth, or what their number formats need when
  /// that is more), model units.
  double build_tolerance = 0.0;
  std::vector<ToleranceShare> tolerance_shares;  ///< how the builders divided build_tolerance (BuiltMesh)
  Vec3 bbox_min = Vec3::Zero(), bbox_max = Vec3::Zero();  ///< of the mesh, model units
  nlohmann::json build;  ///< builder facts, e.g. {"angular_segments": 128, "section_points": 90}
  StageTimings timings_ms;
};

/// A job built, validated and encoded, with nothing written yet.
struct PreparedJob {
  JobReport report;
  std::vector<FileWrite> files;  ///< every output's path and bytes
  StageObserver on_stage;        ///< JobOptions::on_stage, for write_job's stage
};

/// The formats a job of `design` writes under `options`: the design's outputs
/// (or --export-format's one), and the pictures options.also_formats adds.
/// \throw FileError at a bad `outputs` entry
std::vector<const OutputFormat*> job_formats(const Design& design, const JobOptions& options);

/// Builds, validates and encodes `design` into its outputs' bytes. Does no
/// I/O. A mesh that is not valid for fabrication stops the job here; an open
/// surface is written only when the design's purpose is `view`. An output
/// that cannot be made within the tolerance is skipped (reported) or fails
/// the job, as the design's `on_output_error` says.
/// \throw InputError (bad design, OutputError), ValidationFailed (an invalid mesh)
PreparedJob prepare_job(const Design& design, const JobOptions& options);

/// Writes a prepared job's files, all or nothing (write_files_atomically),
/// creating their folder when missing. \throw FileError
JobReport write_job(PreparedJob job);

/// prepare_job then write_job, with the same guarantees (nothing written
/// unless valid, all outputs or none, umask, fsync) but without holding the
/// outputs in memory: each goes to its temporary file as it is encoded (a
/// large STL in pieces, Encoded::stream), and the temporaries are renamed
/// into place together at the end, or removed when anything fails. Stage
/// "encode_FORMAT" then includes writing to the temporary; "write" is the
/// flush and the renames. \throw as prepare_job and write_job
JobReport run_job(const Design& design, const JobOptions& options);

}  // namespace fabmesh
