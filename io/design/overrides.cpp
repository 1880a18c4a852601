#include "io/design/overrides.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

// `text` with each control character written "\x00": messages quote an
// override, and a NUL would end the message there (an exception's what() is
// a C string).
std::string shown(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      out += fmt::format("\\x{:02x}", u);
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

Override parse_override(const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(fmt::format("-D {}: expected path=value, e.g. -D body.wall=2.5", text));
  }
  return make_override(text.substr(0, eq), text.substr(eq + 1));
}

Override make_override(const std::string& path, const std::string& value) {
  Override o{path, value, shown(path + "=" + value)};
  const std::string& text = o.text;
  if (path.empty()) throw InputError(fmt::format("-D {}: expected path=value, e.g. -D body.wall=2.5", text));
  // Keys are plain names; subscripts are [digits]; segments are separated by dots.
  bool expect_key = true;
  for (std::size_t i = 0; i < o.path.size();) {
    const char c = o.path[i];
    if (expect_key) {
      std::size_t j = i;
      while (j < o.path.size() && o.path[j] != '.' && o.path[j] != '[' && o.path[j] != ']' &&
             o.path[j] != '=')
        ++j;
      if (j == i) throw InputError(fmt::format("-D {}: empty key in path '{}'", text, o.path));
      i = j;
      expect_key = false;
    } else if (c == '.') {
      ++i;
      expect_key = true;
    } else if (c == '[') {
      const std::size_t close = o.path.find(']', i);
      const std::string digits = close == std::string::npos ? "" : o.path.substr(i + 1, close - i - 1);
      if (digits.empty() || digits.size() > 9 ||
          digits.find_first_not_of("0123456789") != std::string::npos) {
        throw InputError(fmt::format(
            "-D {}: '{}' is not a list index [N] in path '{}'", text,
            o.path.substr(i, close == std::string::npos ? std::string::npos : close - i + 1), o.path));
      }
      i = close + 1;
    } else {
      throw InputError(fmt::format("-D {}: unexpected '{}' in path '{}'", text, c, o.path));
    }
  }
  if (expect_key) throw InputError(fmt::format("-D {}: the path '{}' ends with '.'", text, o.path));
  return o;
}

}  // namespace fabmesh
