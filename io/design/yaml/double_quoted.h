#pragma once
// A YAML double-quoted scalar, for the texts io/design writes as YAML (the
// canonical text of a batch variant, a value the studio saves). Private to
// io/design.

#include <fmt/format.h>

#include <string>

namespace fabmesh::yaml {

/// `text` in double quotes, with a backslash before each quote and
/// backslash and every control character written \xNN: one line that any
/// YAML reader takes back as `text`, in a block or inside a flow list or map.
inline std::string double_quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      out += fmt::format("\\x{:02x}", u);
    } else {
      out += c;
    }
  }
  return out + '"';
}

}  // namespace fabmesh::yaml
