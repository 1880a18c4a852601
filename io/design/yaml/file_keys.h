#pragma once
// The design keys whose values name a file a reader reads. Private to
// io/design: the canonical text of a batch variant puts those files' bytes
// in place of their names (canonical_tree.h), and the studio lets an
// override name only files the design already names (file_references.h).
// A design key that reads a file must be listed here.

#include <algorithm>
#include <iterator>
#include <string_view>
#include <utility>

namespace fabmesh::yaml {

/// {the key of the map (or of the list of maps) that holds it, the key itself}.
inline constexpr std::pair<std::string_view, std::string_view> kFileKeys[] = {
    {"polyline", "file"}, {"outline", "dxf"}, {"holes", "dxf"}};

/// True when `key`, in a map under `parent_key` (a list's entries are under
/// the list's key), names a file.
inline bool is_file_key(std::string_view parent_key, std::string_view key) {
  return std::any_of(std::begin(kFileKeys), std::end(kFileKeys),
                     [&](const auto& fk) { return key == fk.second && parent_key == fk.first; });
}

}  // namespace fabmesh::yaml
