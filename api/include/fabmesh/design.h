#pragma once
// Designs: read from a YAML file or text, with `-D`-style overrides
// (docs/design-files.md describes the file).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fabmesh/units.h"

namespace fabmesh {
namespace api {

/// One override of a design value, as `fabmesh run -D key=value` gives it.
struct Override {
  /// "body.wall", "profile.points[1]", "profile.segments[0].lambda", or the
  /// name of a parameter the design declares ("height")
  std::string key;
  std::string value;  ///< YAML text: "2.5", "[1, 5]", "{mode: solid}"
};
using Overrides = std::vector<Override>;

/// One of a design's named parameters (`parameters:` in the file, see
/// docs/design-files.md "Parameters and expressions"), with the value the
/// design was read with: after overrides, its expression evaluated.
struct Parameter {
  std::string name;                ///< "height"; an override by this name sets it: {"height", "12"}
  double value = 0.0;              ///< the value used
  std::optional<double> min, max;  ///< the range the design declares, when it does
  std::optional<double> step;      ///< the step a slider would take, when declared
  std::string description;         ///< empty when none
  /// "number", "choice" ({value: shell, choices: [shell, solid]}) or "switch" (true / false).
  std::string kind = "number";
  std::string text;                  ///< a choice's value, or "true" / "false"; empty for a number
  std::vector<std::string> choices;  ///< a choice's values, in the order declared
};

namespace detail {
struct DesignData;
}

/// A design, read and checked: every key known, every value in range, its
/// outputs known. Cheap to copy (the data is shared and never changes), safe
/// to use from several threads at once.
class Design {
 public:
  std::string kind() const;                  ///< "vessel", "countertop", "surface" or "curve"
  std::string name() const;                  ///< the design's name (default: its file's stem)
  Unit units() const;                        ///< the design's model unit
  double tolerance() const;                  ///< the proven deviation the mesh may have, model units
  std::filesystem::path path() const;        ///< the file it was read from (for text: the name given)
  std::vector<std::string> outputs() const;  ///< the formats `run` writes for it: "stl", "3mf", ...
  /// The design's named parameters, in the order declared (empty when it declares none).
  std::vector<Parameter> parameters() const;
  /// The parameter set whose values were used (`parameter_set`, or the
  /// override {"parameter_set": NAME}), "" when none.
  std::string parameter_set() const;
  /// The names of the design's parameter sets (`parameter_sets:`), in file order.
  std::vector<std::string> parameter_sets() const;

  /// For the library's own implementation.
  const detail::DesignData& data() const { return *data_; }
  explicit Design(std::shared_ptr<const detail::DesignData> data) : data_(std::move(data)) {}

 private:
  std::shared_ptr<const detail::DesignData> data_;
};

/// Reads the design file at `path` with `overrides` applied in order, as
/// `fabmesh run PATH -D key=value ...` does.
/// \throw InputError naming the file, line, column and key (or the override)
///        of a malformed or out-of-range value, an unknown key, an unreadable file
Design read_design(const std::filesystem::path& path, const Overrides& overrides = {});

/// The same from YAML text. `source` names it in messages and gives the
/// default name (its stem) and the folder that relative `points_file`s are
/// read from (the current folder when it has none).
/// \throw InputError as read_design, at `source`'s lines and columns
Design parse_design(std::string_view yaml_text, const Overrides& overrides = {},
                    const std::filesystem::path& source = "design.yaml");

}  // namespace api
#ifndef FABMESH_BUILDING_LIBRARY
using namespace api;  // fabmesh::Design, fabmesh::build, ...
#endif
}  // namespace fabmesh
