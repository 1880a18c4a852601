#pragma once
// UTF-8 validation of design text: every name and message fabmesh derives
// from a design (and its JSON report) must be valid UTF-8.

#include <cstddef>
#include <string_view>

namespace fabmesh {

/// The byte offset of the first byte of `text` that does not start a
/// well-formed UTF-8 sequence (RFC 3629: no overlong forms, no surrogates,
/// nothing above U+10FFFF), or std::string_view::npos when all of it is
/// well-formed.
std::size_t invalid_utf8_offset(std::string_view text);

}  // namespace fabmesh
