#pragma once
// Changing values in a design file's text without touching anything else:
// what `fabmesh studio` saves. The comments, the order of keys, the quoting
// and layout of every other value stay byte for byte as the user wrote them.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "io/design/overrides.h"

namespace fabmesh {

/// Where the text of one value is in a design file: the bytes [begin, end)
/// hold the scalar as written (quotes included), at 1-based `line` and `column`.
struct ValueSpan {
  std::size_t begin = 0, end = 0;
  int line = 0, column = 0;
};

/// The span of the value `path` names in the YAML `text` (of file `file`,
/// for messages). `path` is a -D path ("body.wall", "profile.lambdas[1]"), or
/// the name of a declared parameter ("height": its value, under `value:`
/// when the parameter is declared with a range), as `-D` reads it.
/// \throw FileError when the text is not YAML, the path is not in it, or its
///        value is neither a scalar nor a list in brackets written on one line
///        (a block scalar, a map, a list of `- ` items)
ValueSpan value_span(const std::string& text, const std::string& file, const std::string& path);

/// `text` with the value of each override's path (value_span) replaced by its
/// value text as given (Override::value: a number, or YAML such as "\"=w / 2\"").
/// Everything else is left as it was. Two overrides of one value: the last wins.
/// A list written as `- item` lines (each item a scalar or a [list] on its
/// own line) is changed item by item into a new list given as one flow list
/// (a point added or deleted): the items kept keep their lines and comments,
/// new items get lines of their own indented as their neighbours.
/// \throw FileError as value_span, or when a value text is not one line
/// A value at a top-level key the text does not write yet (`parameter_set`)
/// is added as a new last line `key: value`.
std::string edit_values(const std::string& text, const std::string& file,
                        const std::vector<Override>& values);

/// The entries of the map at `path` (a -D path, "outline.segments[1]") in
/// `text`, in the order written, each value as YAML on one line that reads
/// back the same anywhere (numbers plain, other scalars double-quoted, lists
/// and maps in flow style): a composite's segment as the studio rewrites it
/// when a segment is added or deleted.
/// \throw FileError when the text is not YAML or has no map at the path
std::vector<std::pair<std::string, std::string>> flow_entries(const std::string& text,
                                                              const std::string& file,
                                                              const std::string& path);

/// `text` with the parameter set `name` added to its `parameter_sets`, its
/// values (parameter, value as YAML on one line) in order: as the map's last
/// entry, on its own line in a block map or before the closing brace of a
/// flow map, or as a new `parameter_sets:` at the end. Everything else is
/// left as it was; the result reads as the old design plus the set.
/// 	hrow FileError when the design has a set of that name already, or the
///        set cannot be added in the file's layout
std::string add_parameter_set(const std::string& text, const std::string& file, const std::string& name,
                              const std::vector<std::pair<std::string, std::string>>& values);

}  // namespace fabmesh
