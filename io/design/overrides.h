#pragma once
// `-D path=value` overrides of design fields (OpenSCAD style).

#include <string>
#include <vector>

namespace fabmesh {

/// One override: a design field and its new value, as YAML text.
struct Override {
  std::string path;   ///< e.g. "body.wall", "profile.points[1]", "profile.segments[0].lambda"
  std::string value;  ///< YAML, e.g. "2.5", "[1, 5]", "{mode: solid}"
  /// How the user wrote it ("body.wall=2.5"), control characters escaped
  /// ("\x00"); errors at an overridden value name it as "-D body.wall=2.5"
  /// instead of a file position.
  std::string text;
};

/// Splits "path=value" at the first '='. The path is a dotted list of keys,
/// each optionally followed by [index] subscripts.
/// \throw InputError naming the text when there is no '=' or the path is malformed
Override parse_override(const std::string& text);

/// The override of `path` by the YAML text `value`, for callers that hold the
/// two apart (the studio's requests): the path is checked as parse_override
/// checks it and may not hold '=' (the value may); `text` is "path=value".
/// \throw InputError naming the override when the path is malformed
Override make_override(const std::string& path, const std::string& value);

}  // namespace fabmesh
