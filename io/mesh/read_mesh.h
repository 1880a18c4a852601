#pragma once
// Any supported mesh file in: the format is told by content.

#include <cstddef>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// The mesh file formats fabmesh reads.
enum class MeshFormat { Stl, Obj, Ply, Off, Draco, ThreeMf, Glb, Gltf };

/// Tells the format of a mesh file by its content: "DRACO", "ply", "OFF"
/// magic; a zip archive ("PK\x03\x04") holding a *.model part is 3MF; "glTF"
/// magic is GLB; a JSON object with an "asset" member is glTF; a binary STL
/// by its exact size; "solid" + text for ASCII STL; OBJ records. The
/// extension only breaks ties (a binary STL whose size is wrong is still
/// recognised by ".stl", to be rejected with the size mismatch).
/// \throw FileError when the content matches no supported format.
MeshFormat detect_format(std::string_view bytes, const std::string& path);

/// Parses `bytes` in the detected format. 3MF: every build item in one soup
/// (merged_soup), in the file's unit; glTF: the scene in one soup, metres,
/// Y-up as glTF stores it. \param path for detection ties and messages
/// \throw FileError for anything malformed.
TriangleSoup parse_mesh(std::string_view bytes, const std::string& path);

/// "STL", "OBJ", "PLY", "OFF", "Draco", "3MF", "GLB" or "glTF".
const char* to_string(MeshFormat format);

/// One body of a mesh file (see MeshFile::objects).
struct MeshObject {
  std::string name;   ///< as the file names it, or by its place: see MeshFile::objects
  TriangleSoup soup;  ///< only the vertices its triangles use, in the file's order
};

/// A mesh file read: its soup, its format, and its unit when the file says
/// (3MF's unit, glTF's metres; empty for formats that carry none).
struct MeshFile {
  TriangleSoup soup;  ///< every triangle of the file (all its objects: parse_mesh's soup)
  MeshFormat format = MeshFormat::Stl;
  std::string units;
  std::vector<std::string> notes;  ///< what the reader did, e.g. "3 primitives, 1 Draco-compressed"
  /// The file's objects when it holds more than one; empty when it holds one
  /// (then `soup` is that object). An object is
  /// - 3MF: a build item, its object's components expanded and every
  ///   transform applied (items without a triangle left out); named by the
  ///   object's name attribute, else "object ID" (its resource id);
  /// - glTF/GLB: a node instance of a mesh in the scene (all the mesh's
  ///   primitives), placed by the node's global transform; named as
  ///   GltfInstance::name;
  /// - OBJ: an `o` object, and the `g` groups of one only when they are
  ///   separate shells (see parse_obj_objects); named by `o`, else `g`;
  /// - STL, PLY, OFF, Draco: always one object.
  /// `soup` holds the same triangles in the same order, objects one after
  /// the other for 3MF and glTF (as read, for OBJ).
  std::vector<MeshObject> objects;
};

/// Largest mesh file fabmesh reads (4 GiB: a binary STL of about 86 million triangles).
inline constexpr std::size_t kMaxMeshFileBytes = std::size_t{4} << 30;

/// Parses `bytes` as parse_mesh does, keeping the format, unit, notes and objects.
MeshFile parse_mesh_file(std::string_view bytes, const std::string& path);

/// Reads the regular file at `path` (at most kMaxMeshFileBytes) and parses it.
/// \throw FileError when it cannot be read, is not a regular file, or is malformed.
MeshFile read_mesh_file(const std::string& path);

/// The name a mesh read from standard input goes by in messages and reports.
inline constexpr const char* kStandardInputName = "(standard input)";

/// Reads `in` to its end (at most kMaxMeshFileBytes: a larger stream is
/// refused once that many bytes have come, without reading the rest) and
/// parses it, the format told by content as for a file: `check -`.
/// \param name for messages (kStandardInputName for standard input)
/// \throw FileError when the stream fails, is too large, or is malformed.
MeshFile read_mesh_stream(std::istream& in, const std::string& name);

/// Reads and parses the mesh file at `path` (read_mesh_file's soup).
/// \throw FileError when it cannot be read or is malformed.
TriangleSoup read_mesh(const std::string& path);

}  // namespace fabmesh
