#pragma once
// Wavefront OBJ: vertices and faces (other records are ignored).

#include <string>
#include <string_view>

#include "geometry/core/types.h"
#include "geometry/mesh/soup.h"

namespace fabmesh {

/// Parses the `v` and `f` records of an OBJ file. Face corners may be
/// `v`, `v/vt`, `v//vn` or `v/vt/vn`; indices are 1-based or negative
/// (relative to the vertices read so far). Polygons are fan-triangulated.
/// \param name the path, for messages
/// \throw FileError naming the line for a malformed number, a face with fewer
/// than 3 corners, or an index that refers to no vertex.
TriangleSoup parse_obj(std::string_view bytes, const std::string& name);

/// OBJ text of `soup` (coordinates in shortest round-trip form: exact).
/// \throw InputError when an index is out of range.
std::string encode_obj(const TriangleSoup& soup);

/// Writes `soup` (or `mesh`) as OBJ to `path`, atomically. \throw FileError
void write_obj(const TriangleSoup& soup, const std::string& path);
void write_obj(const Mesh& mesh, const std::string& path);

}  // namespace fabmesh
