#pragma once
// One variant's line of a batch summary (summary.csv, summary.jsonl): what it
// is (name, base design, parameter values, content key) and what became of it.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/stage_timer.h"
#include "pipeline/facts.h"
#include "pipeline/failure.h"
#include "pipeline/report.h"
#include "pipeline/result.h"

namespace fabmesh {

/// What became of a variant: the statuses of every report, whose words the
/// ledger keeps ("missing" after a merge: no shard has run it yet).
using VariantStatus = ItemStatus;

/// True for a status that stands on a rerun (ok, invalid, bad input): the
/// same key gives the same outcome. Error and environment are redone.
bool is_final(VariantStatus status);

/// The inverse of to_string. \throw InputError for another text
VariantStatus parse_variant_status(const std::string& text);

/// One output file of a variant, its path relative to the batch folder.
struct RowFile {
  std::string path;
  std::string format;
  std::string units;
  std::uint64_t bytes = 0;
  std::string sha256;  ///< of its content, 64 hex digits
};

/// One summary row (docs/batch.md). Plain data: the lead's HTML report turns these into its rows.
struct BatchRow {
  std::size_t index = 0;  ///< 0-based position in the manifest's variant list
  std::string name;
  std::string design;                                          ///< the base design as the manifest names it
  std::vector<std::pair<std::string, std::string>> overrides;  ///< the variant's own values: path, YAML text
  std::string key;  ///< 64 hex digits: SHA-256 of the resolved design and the fabmesh version
  VariantStatus status = VariantStatus::Missing;
  int exit_code = 0;
  std::string message;            ///< why it failed, or the warnings of skipped outputs
  std::optional<MeshFacts> mesh;  ///< when written (mesh_facts of its job)
  Facts build;                    ///< the builder's facts of its result (the report's `build`)
  std::vector<RowFile> files;
  std::vector<SkippedOutput> skipped;
  /// Wall ms: "resolve" (overrides, canonical text, key), "job" (the job's own
  /// stages, in the job's report too), "record" (digests, ledger), then the job's stages.
  StageTimings timings_ms;
};

/// Records what a variant's job made in its row: the mesh facts of its
/// result, its builder's facts, the outputs skipped (and why, in the message).
void record_result(BatchRow& row, const Result& result);

/// The row as one JSON object (a summary.jsonl line); timings last.
nlohmann::ordered_json row_json(const BatchRow& row);

/// The row as the facts every report shows (ItemFacts): its name, status and
/// message (an ok row without one: "valid for fabrication"; a missing one:
/// "not run yet"), mesh facts, files (relative to the batch folder) and
/// timings.
ItemFacts row_facts(const BatchRow& row);

/// The inverse of row_json. \throw InputError when a field is missing or of the wrong type
BatchRow row_from_json(const nlohmann::ordered_json& j);

/// The header line of summary.csv (with its newline): fixed columns, one column per
/// parameter, then timings.
std::string csv_header(const std::vector<std::string>& parameters);

/// The row as a summary.csv line (with its newline), in csv_header's columns.
std::string csv_line(const BatchRow& row, const std::vector<std::string>& parameters);

}  // namespace fabmesh
