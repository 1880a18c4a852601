#pragma once
// Typed access to YAML fields with errors that name file, line, column and
// field. Private to io/design (yaml-cpp is a private dependency of
// fabmesh::io): only the readers of io/design/yaml include it.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <initializer_list>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/core/types.h"
#include "io/design/design.h"
#include "io/design/schema.h"

namespace fabmesh::yaml {

/// A value that came from a `-D` override: its YAML subtree and how the user wrote it.
struct OverrideOrigin {
  YAML::Node value;
  std::string text;  ///< "body.wall=2.5"
};

/// An ErrorLocation at design key `key`, given where the design has it (no
/// `place`: a FileError's message already names it).
ErrorLocation at_key(const std::string& key, const KeySource& where);

/// The file being read; makes errors and labels with locations.
class Fields {
 public:
  explicit Fields(std::string path, std::vector<OverrideOrigin> overrides = {})
      : path_(std::move(path)), overrides_(std::move(overrides)) {}
  const std::string& path() const { return path_; }

  /// "path:line:column" of a node (1-based), "-D path=value" for a node an
  /// override put there, or the path alone when the node has no mark.
  std::string location(const YAML::Node& node) const;
  /// Where `node` is, as text (location) and as data: file, line and column,
  /// or the override that put it there. `holds_keys` is left false.
  KeySource source(const YAML::Node& node) const;
  /// "path:line:column: field" for a node (1-based line and column), or
  /// "-D path=value: field" for a node an override put there.
  std::string label(const YAML::Node& node, const std::string& field) const;
  /// A FileError at `node` for `field`.
  [[noreturn]] void fail(const YAML::Node& node, const std::string& field, const std::string& message) const;
  /// The same for a map key, whose origin is its value's (`value`: the key's entry).
  [[noreturn]] void fail_key(const YAML::Node& key, const YAML::Node& value, const std::string& field,
                             const std::string& message) const;

  /// The child `key` of a map; a FileError at the map when it is missing.
  YAML::Node required(const YAML::Node& parent, const char* key, const std::string& field) const;
  /// Requires a map whose keys are all in `allowed` (design_key_groups()),
  /// each key a plain scalar given once.
  void require_map(const YAML::Node& node, const std::string& field, const KeyGroup& allowed) const;
  /// Requires a sequence of at least `min_size` entries.
  void require_list(const YAML::Node& node, const std::string& field, std::size_t min_size = 0) const;

  /// A finite number of magnitude at most kMaxDesignNumber (io/design/number_limits.h).
  double number(const YAML::Node& node, const std::string& field) const;
  double number_or(const YAML::Node& parent, const char* key, const std::string& field,
                   double fallback) const;
  std::string text(const YAML::Node& node, const std::string& field) const;

  /// Records a fact about how the design's files were read (e.g. a header
  /// row skipped), for DesignCommon::notes and so the report.
  void note(std::string text) const { notes_.push_back(std::move(text)); }
  const std::vector<std::string>& notes() const { return notes_; }
  /// Records a file the design reads besides itself (a DXF drawing, a CSV of
  /// points), once, for DesignCommon::inputs.
  void input(const std::string& path) const {
    if (std::find(inputs_.begin(), inputs_.end(), path) == inputs_.end()) inputs_.push_back(path);
  }
  const std::vector<std::string>& inputs() const { return inputs_; }
  std::string text_or(const YAML::Node& parent, const char* key, const std::string& field,
                      const std::string& fallback) const;
  /// One of `choices`.
  std::string choice(const YAML::Node& node, const std::string& field,
                     const std::vector<std::string>& choices) const;
  /// A work budget (`max_triangles`): a whole number in [1, 2e9], or `fallback` when absent.
  std::size_t budget_or(const YAML::Node& parent, const char* key, std::size_t fallback) const;
  /// A whole number in [lo, hi].
  long integer(const YAML::Node& node, const std::string& field, long lo, long hi) const;
  bool boolean_or(const YAML::Node& parent, const char* key, const std::string& field, bool fallback) const;
  Vec2 point2(const YAML::Node& node, const std::string& field) const;
  std::vector<Vec2> points2(const YAML::Node& node, const std::string& field, std::size_t min_size = 0) const;
  Vec3 point3(const YAML::Node& node, const std::string& field) const;

  /// Runs `check` and turns an InputError from it into a FileError at `node`.
  /// A FileError about this design file passes unchanged; one about another
  /// file (a points CSV the node names) is located at the node too:
  /// "design.yaml:5:7: curve.segments[0].polyline.file: points.csv:3: ...".
  template <class F>
  void checked(const YAML::Node& node, const std::string& field, F&& check) const {
    try {
      check();
    } catch (const FileError& e) {
      if (e.path() == path_) throw;
      fail(node, field, e.what());
    } catch (const InputError& e) {
      fail(node, field, e.what());
    }
  }

 private:
  /// The override `node` belongs to (it is, or is inside, an override's value), if any.
  const OverrideOrigin* origin_of(const YAML::Node& node) const;

  std::string path_;
  std::vector<OverrideOrigin> overrides_;
  mutable std::vector<std::string> notes_;   ///< note(): facts found while reading, not state
  mutable std::vector<std::string> inputs_;  ///< input(): the other files read
};

}  // namespace fabmesh::yaml
