#pragma once
// PLY (Stanford polygon format): ascii, binary_little_endian and
// binary_big_endian; the vertex and face elements.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/core/types.h"
#include "geometry/mesh/halfedge_mesh.h"

namespace fabmesh {

/// Parses a PLY file: x, y, z of the `vertex` element (any numeric type) and
/// the `vertex_indices` (or `vertex_index`) list of the `face` element,
/// fan-triangulated. Other elements and properties are read and ignored.
/// \param name the path, for messages
/// \throw FileError for a malformed header, counts larger than the file can
/// hold, truncated data, a non-finite coordinate or an index out of range.
TriangleSoup parse_ply(std::string_view bytes, const std::string& name);

/// Options of the PLY writer.
struct PlyOptions {
  /// false (default): `float` coordinates (float32), which every PLY reader
  /// takes (draco_encoder, among others, refuses double); true: `double`,
  /// exact.
  bool double_precision = false;
  /// Empty (default), or one colour per face (red, green, blue): written as
  /// the face properties `uchar red`, `uchar green`, `uchar blue` after the
  /// indices (`check --mark`).
  std::vector<std::array<std::uint8_t, 3>> face_colours;
};

/// binary_little_endian PLY bytes of `soup`: vertex x, y, z (float32 unless
/// options.double_precision) and faces as `list uchar uint vertex_indices`
/// (with options.face_colours, then red, green, blue).
/// \throw InputError when an index is out of range, a coordinate is not
/// finite in the chosen precision, or face_colours is neither empty nor one per face.
std::string encode_ply(const TriangleSoup& soup, const PlyOptions& options = {});

/// Writes `soup` (or `mesh`) as binary PLY to `path`, atomically.
/// \throw as encode_ply, and FileError when the file cannot be written.
void write_ply(const TriangleSoup& soup, const std::string& path, const PlyOptions& options = {});
void write_ply(const Mesh& mesh, const std::string& path, const PlyOptions& options = {});

}  // namespace fabmesh
