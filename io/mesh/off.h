#pragma once
// OFF (Object File Format): counts, vertices, polygon faces.

#include <string>
#include <string_view>

#include "geometry/core/soup.h"
#include "geometry/core/types.h"
#include "geometry/mesh/halfedge_mesh.h"

namespace fabmesh {

/// Parses an ASCII OFF file: "OFF", then "V F E", V lines "x y z", F lines
/// "n i1 ... in" (extra values such as colours ignored; polygons
/// fan-triangulated; '#' starts a comment). \param name the path, for messages
/// \throw FileError naming the line for a bad header, counts larger than the
/// file can hold, a malformed or missing line, an index out of range.
TriangleSoup parse_off(std::string_view bytes, const std::string& name);

/// OFF text of `soup` (coordinates in shortest round-trip form: exact).
/// \throw InputError when an index is out of range.
std::string encode_off(const TriangleSoup& soup);

/// Writes `soup` (or `mesh`) as OFF to `path`, atomically. \throw FileError
void write_off(const TriangleSoup& soup, const std::string& path);
void write_off(const Mesh& mesh, const std::string& path);

}  // namespace fabmesh
