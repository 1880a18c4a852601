#pragma once
// A batch's plan: every variant of a manifest with its content key, and the
// plan's digest. Every run and shard of one manifest computes the same plan;
// merging a batch's shards needs only the plan and the ledgers.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
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

/// Every variant of a manifest with its key, in manifest order. A plan of a
/// manifest (plan_batch) makes each variant from the manifest on demand and
/// keeps 48 bytes a variant (its key and a hash of its name), so a batch's
/// memory does not grow with its size beyond that; a plan read from its file
/// (read_plan, for --merge) holds every variant.
class BatchPlan {
 public:
  std::string manifest;                 ///< the manifest's path as given
  std::vector<std::string> parameters;  ///< the paths the variants set (summary columns)
  std::string digest;                   ///< 64 hex digits over the variants' names and keys, in order

  std::size_t size() const { return keys_.size(); }
  /// Variant `i`: name, base, values and key.
  PlannedVariant variant(std::size_t i) const;
  std::string name(std::size_t i) const;
  std::string key(std::size_t i) const;  ///< 64 hex digits
  /// The index of the variant named `name`, if the plan has one.
  std::optional<std::size_t> find(const std::string& name) const;

 private:
  friend BatchPlan plan_batch(const BatchManifest& manifest);
  friend BatchPlan read_plan(const std::string& path);
  void index_names();

  const BatchManifest* source_ = nullptr;  ///< plan_batch's manifest (outlives the plan)
  std::vector<PlannedVariant> read_;       ///< read_plan's variants
  std::vector<std::array<std::uint8_t, 32>> keys_;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> names_;  ///< (hash of the name, index), sorted
};

/// The content key of a variant: SHA-256 of a format tag, the fabmesh version
/// and the canonical text of its resolved design (DesignSource::canonical:
/// the design after every override, its name included, with the bytes of the
/// files it reads; never the design file's own path), as 64 hex digits.
std::string variant_key(const std::string& canonical);

/// The plan of `manifest` (which must outlive it): each variant's key,
/// computed in parallel (in the caller's TBB arena). A variant whose overrides cannot be applied (a path
/// through a missing list entry) gets a key from its base's canonical text
/// and its override texts; running it reports the error.
BatchPlan plan_batch(const BatchManifest& manifest);

/// Reads a plan written by save_plan. \throw FileError
BatchPlan read_plan(const std::string& path);

/// Writes the plan as JSON to `folder`/plan-DIGEST.json, a variant at a time,
/// unless that file exists (its name fixes its content: writers of one plan
/// write the same bytes).
/// \throw FileError
void save_plan(const BatchPlan& plan, const std::string& folder);

/// The path of the plan with `digest` in `folder`.
std::string plan_path(const std::string& folder, const std::string& digest);

}  // namespace fabmesh
