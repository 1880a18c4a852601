#pragma once
// A batch's plan: every variant of a manifest with its content key, and the
// plan's digest. Every run and shard of one manifest computes the same plan;
// merging a batch's shards needs only the plan and the ledgers.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "io/design/manifest.h"

namespace fabmesh {

/// One variant of the plan.
struct PlannedVariant {
  std::string name;
  std::string design;                                          ///< the base as the manifest names it
  std::vector<std::pair<std::string, std::string>> overrides;  ///< its own values: path, YAML text
  std::string key;                                             ///< 64 hex digits (variant_key)
};

/// Every variant of a manifest, in manifest order.
struct BatchPlan {
  std::string manifest;                 ///< the manifest's path as given
  std::vector<std::string> parameters;  ///< the paths the variants set (summary columns)
  std::vector<PlannedVariant> variants;
  std::string digest;  ///< 64 hex digits over the variants' names and keys, in order
};

/// The content key of a variant: SHA-256 of a format tag, the fabmesh version
/// and the canonical text of its resolved design (DesignSource::canonical:
/// the design after every override, its name included, with the bytes of the
/// files it reads; never the design file's own path), as 64 hex digits.
std::string variant_key(const std::string& canonical);

/// The plan of `manifest`: each variant's key, computed in parallel (in the
/// caller's TBB arena). A variant whose overrides cannot be applied (a path
/// through a missing list entry) gets a key from its base's canonical text
/// and its override texts; running it reports the error.
BatchPlan plan_batch(const BatchManifest& manifest);

/// The plan as JSON text (the file .batch/plan-DIGEST.json of a batch folder).
std::string plan_text(const BatchPlan& plan);

/// Reads a plan written by plan_text. \throw FileError
BatchPlan read_plan(const std::string& path);

/// Writes the plan to `folder`/plan-DIGEST.json unless that file exists
/// (its name fixes its content: writers of one plan write the same bytes).
/// \throw FileError
void save_plan(const BatchPlan& plan, const std::string& folder);

/// The path of the plan with `digest` in `folder`.
std::string plan_path(const std::string& folder, const std::string& digest);

}  // namespace fabmesh
