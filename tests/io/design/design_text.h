#pragma once
// Helpers the design-reading tests share: a design text read as cup.yaml
// with -D texts, the message it fails with, and a text edited in one place.

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/read_design.h"

namespace fabmesh::test {

/// `text` read as the design file cup.yaml with the -D texts `defines`.
inline Design read_text(const std::string& text, const std::vector<std::string>& defines = {}) {
  std::vector<Override> overrides;
  for (const std::string& d : defines) overrides.push_back(parse_override(d));
  return parse_design(text, "cup.yaml", overrides);
}

/// The message of the FileError reading `text` throws ("no error" when it reads).
inline std::string read_error(const std::string& text, const std::vector<std::string>& defines = {}) {
  try {
    read_text(text, defines);
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

/// `text` with its first `find` replaced by `replace` (which must be there).
inline std::string replaced(std::string text, const std::string& find, const std::string& replace) {
  const std::size_t at = text.find(find);
  REQUIRE(at != std::string::npos);
  return text.replace(at, find.size(), replace);
}

}  // namespace fabmesh::test
