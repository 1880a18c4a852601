#pragma once
// Batch manifests (docs/batch.md): base designs and the override sets that
// make their variants, read and expanded into the list of variants.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "io/design/design_source.h"
#include "io/design/overrides.h"

namespace fabmesh {

/// One variant of a batch: a base design and its own parameter values.
struct Variant {
  std::size_t base = 0;  ///< index into BatchManifest::bases
  std::string name;      ///< from the name template: a plain file name, unique in the batch
  /// The variant's own values (from `variants`, `table`, `zip`, `grid`), in
  /// manifest order. Each text says where the manifest gives it, e.g.
  /// "body.wall=0.25 (sweep.yaml:9:18)": errors at the value name it so.
  std::vector<Override> overrides;
};

struct ManifestExpansion;

/// A manifest, read and checked; its variants are made on demand.
struct BatchManifest {
  std::string path;                 ///< the manifest file
  std::vector<DesignSource> bases;  ///< the `design` files, parsed once
  std::vector<std::string>
      base_labels;               ///< the `design` entries as written (relative to the manifest's folder)
  std::vector<Override> common;  ///< `set`: applied to every variant before its own values
  std::vector<std::string> parameters;  ///< the paths the variants set, in order of first appearance
  /// How many variants: for each base, the product variants x table x zip x grid.
  std::size_t variant_count() const;
  /// Variant `i` (0-based) in manifest order: for each base, the product
  /// (earlier forms and, in a grid, earlier keys vary slowest). Made on demand
  /// from the forms' value lists: a manifest's memory grows with what it
  /// writes, never with the product. \throw std::out_of_range
  Variant variant(std::size_t i) const;

  /// The forms' value lists and the name template (manifest.cpp).
  std::shared_ptr<const ManifestExpansion> expansion;
};

/// At most this many variants in one manifest.
inline constexpr std::size_t kMaxBatchVariants = 1000000;

/// Names a variant may not take: files of the batch's own in its output folder.
inline const std::vector<std::string>& reserved_variant_names() {
  static const std::vector<std::string> names{"summary.csv", "summary.jsonl", "slurm.sbatch"};
  return names;
}

/// Reads the manifest at `path` (at most 1 MiB), its base designs and its
/// table, and expands the variants. Paths in it are relative to its folder.
/// Checked here: keys, value shapes, override paths, zip lengths, ranges, the
/// variant count, name templates, that names are plain file names
/// (plain_name_problem) and unique. A variant's values are not checked here:
/// resolving it (DesignSource::resolve) does.
/// \throw FileError "path:line:column: field: message" (or the base design's or the table's location)
BatchManifest read_manifest(const std::string& path);

/// The same from the manifest's text; `path` gives messages and the folder. \throw FileError
BatchManifest parse_manifest(const std::string& text, const std::string& path);

/// Every override that makes variant `v`: the manifest's `set`, the variant's
/// own values, then its name as the design's `name`.
std::vector<Override> variant_overrides(const BatchManifest& manifest, const Variant& v);

}  // namespace fabmesh
