#pragma once
// The keys of design files, map by map: the one list the readers accept and
// the user reference (docs/design-files.md) documents.

#include <string>
#include <string_view>
#include <vector>

namespace fabmesh {

/// One kind of YAML map in a design file and the keys it accepts.
struct KeyGroup {
  std::string name;               ///< e.g. "vessel.body": the reference marks its section with it
  std::vector<std::string> keys;  ///< accepted keys, in the order the reference lists them
};

/// Every kind of map the design reader accepts, with its keys.
const std::vector<KeyGroup>& design_key_groups();

/// The group called `name`. \throw std::logic_error for an unknown name (a programming error)
const KeyGroup& key_group(std::string_view name);

}  // namespace fabmesh
