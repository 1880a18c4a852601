#pragma once
// One design through the stages, each a function of its inputs:
//
//   plan_job    design, options        -> JobPlan   (formats, files, warnings)
//   build_job   design, plan           -> Result    (parts built and validated)
//   require_fit result                 -> throws ValidationFailed unless fit to write
//   encode_job  result, plan           -> EncodedJob (every output's bytes, or why skipped)
//   write_job   encoded                -> the files, all or nothing
//
// `run` composes them (run_job: each output written to its temporary file as
// soon as it is encoded), as do `batch`, the studio (build_job alone, or
// build_draft) and the library.

#include <optional>
#include <string>
#include <vector>

#include "geometry/core/stage_timer.h"
#include "io/design/design.h"
#include "io/file.h"
#include "pipeline/output_table.h"
#include "pipeline/plane_memo.h"
#include "pipeline/result.h"

namespace fabmesh {

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
  /// Where a countertop may take its work in the plane from a batch's earlier
  /// variants, and keep it for the later ones (pipeline/plane_memo.h).
  PlaneReuse reuse;
};

/// One file a job will write.
struct PlannedFile {
  std::string path;
  std::string format;
};

/// What a job will do, known before it builds.
struct JobPlan {
  DesignCommon common;  ///< the design's, with the export unit the options ask for
  std::vector<const OutputFormat*> formats;
  /// Where each format's file goes (mould_stl's files are named per part
  /// there: one path ending in ".mould-PART.stl" stands for them).
  std::vector<std::string> paths;
  std::string out_dir;
  /// Warnings about the design's own `outputs` list: a `mould:` or `cnc:`
  /// block for which it asks for no output, so that block is not built.
  std::vector<std::string> warnings;
  double export_scale = 1.0;   ///< export units per model unit
  bool wants_drawing = false;  ///< an output draws the design (the builders make the drawing)
  bool wants_exact = false;    ///< an output writes the exact shape (step)
  StageObserver on_stage;
  PlaneReuse reuse;  ///< the options'
};

/// The job of `design` under `options`: its formats (the design's outputs,
/// or --export-format's one, and the pictures options.also_formats adds),
/// their files and the warnings its outputs list deserves.
/// \throw FileError at a bad `outputs` entry; InputError when `-o FILE` would take several
JobPlan plan_job(const Design& design, const JobOptions& options);

/// The files the plan writes, one per output (one per mould part for
/// mould_stl), as write_job names them, before anything is built.
std::vector<PlannedFile> planned_files(const Design& design, const JobPlan& plan);

/// Builds `design` within its tolerance less what the plan's outputs need
/// for writing, and validates every part (validate_parts). Does no I/O; an
/// invalid mesh is a Result that is not fit() (see require_fit).
/// \throw InputError (a bad design, geometry that cannot be built)
Result build_job(const Design& design, const JobPlan& plan);

/// Builds `design` at `tolerance` (all of it for the meshes: nothing is kept
/// for writing) and validates every part: what a preview shows.
/// \throw as build_job
Result build_at(const Design& design, double tolerance);

/// The design built for a preview (`fabmesh preview`): build_at its own
/// tolerance. \throw as build_job; InputError for a curve design (no mesh)
Result build_preview(const Design& design);

/// A draft of `design` to show at once (the studio's): built at the coarsest
/// tolerance its builder accepts, 32 down to 4 times the design's (the
/// result's tolerance is the one used); a surface's sheet alone at twice its
/// tolerance, thickened (surface_draft). Nothing proven: no verdict.
/// \throw as build_job
Result build_draft(const Design& design);

/// One output of a result, encoded: its files' bytes and facts.
struct EncodedFile {
  OutputFile file;  ///< path, format, units, added error, valid as written, parts
  Encoded encoded;  ///< the bytes (or a stream over the result's meshes)
};

/// A result's outputs, encoded and not written.
struct EncodedJob {
  std::vector<EncodedFile> files;
  std::vector<SkippedOutput> skipped;
  StageTimings timings_ms;  ///< "encode_FORMAT" each
};

/// Encodes every output of `plan` from `result` (which must be fit: see
/// require_fit). An output that cannot be made within the tolerance is
/// skipped (EncodedJob::skipped) or fails the job, as the design's
/// `on_output_error` says. A streamed output (a large STL) refers to
/// `result`'s meshes. Does no I/O.
/// \throw OutputError (fail policy, or every output skipped)
EncodedJob encode_job(const Result& result, const JobPlan& plan);

/// Writes the encoded files, all or nothing (write_files_atomically),
/// creating their folders when missing; returns the files written.
/// \throw FileError / MachineError
std::vector<OutputFile> write_job(EncodedJob& encoded);

/// plan, build, require_fit, encode and write, with the same guarantees
/// (nothing written unless valid, all outputs or none, umask, fsync) but
/// without holding the outputs in memory: each goes to its temporary file as
/// it is encoded (a large STL in pieces, Encoded::stream), and the
/// temporaries are renamed into place together at the end, or removed when
/// anything fails. The result's files and timings say what was written.
/// \throw InputError (bad design, OutputError), ValidationFailed (an invalid mesh), FileError
Result run_job(const Design& design, const JobOptions& options);

/// The same, encoded in memory and not written (what `-o -` prints, what the
/// library's build reports): the result with the files it would write.
/// \throw as run_job
std::pair<Result, EncodedJob> prepare_job(const Design& design, const JobOptions& options);

}  // namespace fabmesh
