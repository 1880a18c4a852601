#pragma once
// What a job will write, known before it runs: the files its outputs go to
// (to refuse two designs of one run writing one file) and the warnings its
// outputs list deserves (a `mould:` or `cnc:` block nothing uses).

#include <string>
#include <vector>

#include "io/design/design.h"
#include "pipeline/job.h"
#include "pipeline/outputs.h"

namespace fabmesh {

/// One file a job will write.
struct PlannedFile {
  std::string path;
  std::string format;
};

/// The files `design`'s job writes under `options` (one per output; one per
/// mould part for mould_stl), as write_job names them.
/// \throw FileError at a bad `outputs` entry (resolve_outputs)
std::vector<PlannedFile> planned_files(const Design& design, const JobOptions& options);

/// Warnings about the design's own `outputs` list: a `mould:` or `cnc:`
/// block for which it asks for no output, so that block is not built
/// ("cup.yaml:12:1: mould: ... add mould_stl, mould_3mf or mould_step to `outputs`").
/// None when the formats come from the command line (`--export-format`,
/// `-o FILE.ext`) or are the kind's defaults.
std::vector<std::string> unused_block_warnings(const Design& design, const JobOptions& options,
                                               const std::vector<const OutputFormat*>& formats);

}  // namespace fabmesh
