#pragma once
// The steps of reading a design, for io/design's readers that resolve one
// parsed tree many times (design_source.h): text to tree, overrides into the
// tree, tree to Design. Private to io/design, like fields.h.

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "io/design/design.h"
#include "io/design/overrides.h"
#include "io/design/yaml/fields.h"

namespace fabmesh::yaml {

/// The root map of a design file's text (one YAML document).
/// \throw FileError naming the line and column of a YAML error, or a root that is not a map
YAML::Node load_design_tree(const std::string& text, const std::string& path);

/// Puts each override's value at its path in `root` (in place, in order) and
/// returns where each value came from, for messages.
/// \throw FileError naming the override (bad YAML value, path through a missing entry or a non-map)
std::vector<OverrideOrigin> apply_overrides(YAML::Node root, const std::string& path,
                                            const std::vector<Override>& overrides);

/// Resolves the design's `parameters` (in declaration order, each value,
/// min, max and step a number or an expression over the others) and puts
/// the value of every expression (a scalar starting with '=') anywhere else
/// in the tree in its place, in place: the node keeps its mark and its
/// override origin, so later errors at it name the expression's place.
/// \throw FileError naming the file, line, column and field (or the override)
///        of a bad parameter or expression
std::vector<DesignParameter> resolve_parameters(const YAML::Node& root, const Fields& f);

/// The tag of a node whose text a choice or a switch put there ("=mode"):
/// readers may tell a value the design varies from one it writes.
inline constexpr const char* kChosenTag = "!fabmesh-chosen";

/// Whether `node` is a switch's value: plain true or false (YAML 1.2's
/// spellings: true, True, TRUE, ...); a quoted "true" is a text.
bool is_switch_value(const YAML::Node& node);

/// Reads and validates the design of a tree with overrides applied (see
/// read_design): resolves its parameters and expressions (resolve_parameters),
/// then reads it.
/// \throw FileError naming file, line, column and field, or the override
Design read_design_tree(const YAML::Node& root, const std::string& path, std::vector<OverrideOrigin> origins);

}  // namespace fabmesh::yaml
