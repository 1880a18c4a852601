#pragma once
// STL: binary and ASCII triangle soups.

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

#include "geometry/core/soup.h"
#include "geometry/core/types.h"
#include "geometry/mesh/halfedge_mesh.h"

namespace fabmesh {

/// Parses an STL file, binary or ASCII (told apart by content: a binary file
/// is exactly 84 + 50 * N bytes for the N its header states; an ASCII file
/// starts with "solid" and is text). Every triangle gets three fresh
/// vertices (weld afterwards). \param name the path, for messages
/// \throw FileError when malformed: truncated or lying binary size, a bad
/// token, a non-finite coordinate.
TriangleSoup parse_stl(std::string_view bytes, const std::string& name);

/// True when `bytes` has the exact size of a binary STL for its stated count.
bool is_binary_stl(std::string_view bytes);

/// True when `bytes` starts with "solid" followed by text (an ASCII STL).
bool looks_like_ascii_stl(std::string_view bytes);

/// Binary STL bytes of `soup` (coordinates rounded to float32, normals from
/// the corner order). \throw InputError when an index is out of range.
std::string encode_stl(const TriangleSoup& soup);

/// The same bytes as encode_stl(soup), handed to `sink` in consecutive
/// pieces of at most about `piece_bytes` (whole 50-byte records; the 84-byte
/// header with the first piece), so a large file never has to be held in
/// memory whole. A piece's bytes are valid only during its call.
/// \throw InputError as encode_stl (before `sink` is first called), anything `sink` throws
void encode_stl_pieces(const TriangleSoup& soup, const std::function<void(std::string_view)>& sink,
                       std::size_t piece_bytes = std::size_t{4} << 20);

/// Writes `soup` (or `mesh`) as binary STL to `path`, atomically.
/// \throw FileError when the file cannot be written.
void write_stl(const TriangleSoup& soup, const std::string& path);
void write_stl(const Mesh& mesh, const std::string& path);

}  // namespace fabmesh
