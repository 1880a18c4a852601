#pragma once
// A design's parameter sets (`parameter_sets`, `parameter_set`; docs/design-files.md,
// "Parameter sets"): checked, and the chosen set's values put in place of its
// parameters' values. Private to io/design, like fields.h.

#include <yaml-cpp/yaml.h>

#include <vector>

#include "io/design/design.h"
#include "io/design/yaml/fields.h"

namespace fabmesh::yaml {

/// Whether an override path edits the sets themselves (`parameter_sets...`):
/// such overrides are applied before the chosen set is.
bool edits_parameter_sets(const std::string& override_path);

/// Checks `parameter_sets` (a map of set names to maps of declared parameters
/// to numbers or expressions) and, when `parameter_set` names one, puts each
/// of its values in place of its parameter's value (the node itself: errors at
/// it name the set's line and column).
/// \throw FileError naming file, line, column and field (or the override):
///        a set that is not a map, a name that is not plain, an entry that is
///        not a declared parameter, a value that is not a scalar, a chosen set
///        the design does not declare
void apply_parameter_set(YAML::Node root, const Fields& f);

/// The sets as written (call before resolve_parameters evaluates their expressions).
std::vector<ParameterSet> parameter_sets_of(const YAML::Node& root);

}  // namespace fabmesh::yaml
