#pragma once
// Wavefront OBJ: vertices and faces (other records are ignored).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/core/types.h"
#include "geometry/mesh/halfedge_mesh.h"

namespace fabmesh {

/// Parses the `v` and `f` records of an OBJ file. Face corners may be
/// `v`, `v/vt`, `v//vn` or `v/vt/vn`; indices are 1-based or negative
/// (relative to the vertices read so far). Polygons are fan-triangulated.
/// \param name the path, for messages
/// \throw FileError naming the line for a malformed number, a face with fewer
/// than 3 corners, or an index that refers to no vertex.
TriangleSoup parse_obj(std::string_view bytes, const std::string& name);

/// An OBJ file's triangles and the object each belongs to.
struct ObjContent {
  TriangleSoup soup;                       ///< as parse_obj returns it
  std::vector<std::string> object_names;   ///< one per object, in the order of their first face
  std::vector<std::uint32_t> face_object;  ///< per triangle of soup: its index in object_names
};

/// Parses an OBJ file as parse_obj does and tells its objects apart. Every
/// `o` record starts an object; faces before the first `o` form one too.
/// Within an object, its `g` groups (a `g` record's whole rest of line names
/// one; "default" before any) are separate objects only when they are
/// separate shells: groups that share a vertex (the same index, or two
/// vertices of exactly equal finite coordinates, as check's weld merges
/// them) are one object. So a body split into material groups stays one
/// object, and bodies written as disjoint groups are apart. An object is
/// named by its `o` name; one of several shells of an `o` (or of the file
/// without `o`) by its first group's name ("part/shell" under a named `o`).
/// Objects without faces are left out. 	hrow FileError as parse_obj
ObjContent parse_obj_objects(std::string_view bytes, const std::string& name);

/// OBJ text of `soup` (coordinates in shortest round-trip form: exact).
/// \throw InputError when an index is out of range.
std::string encode_obj(const TriangleSoup& soup);

/// Writes `soup` (or `mesh`) as OBJ to `path`, atomically. \throw FileError
void write_obj(const TriangleSoup& soup, const std::string& path);
void write_obj(const Mesh& mesh, const std::string& path);

}  // namespace fabmesh
