#pragma once
// PLY (Stanford polygon format): ascii, binary_little_endian and
// binary_big_endian; the vertex and face elements.

#include <string>
#include <string_view>

#include "geometry/core/types.h"
#include "geometry/mesh/soup.h"

namespace fabmesh {

/// Parses a PLY file: x, y, z of the `vertex` element (any numeric type) and
/// the `vertex_indices` (or `vertex_index`) list of the `face` element,
/// fan-triangulated. Other elements and properties are read and ignored.
/// \param name the path, for messages
/// \throw FileError for a malformed header, counts larger than the file can
/// hold, truncated data, a non-finite coordinate or an index out of range.
TriangleSoup parse_ply(std::string_view bytes, const std::string& name);

/// binary_little_endian PLY bytes of `soup` (double coordinates: exact).
/// \throw InputError when an index is out of range.
std::string encode_ply(const TriangleSoup& soup);

/// Writes `soup` (or `mesh`) as binary PLY to `path`, atomically. \throw FileError
void write_ply(const TriangleSoup& soup, const std::string& path);
void write_ply(const Mesh& mesh, const std::string& path);

}  // namespace fabmesh
