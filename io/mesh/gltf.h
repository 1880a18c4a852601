#pragma once
// glTF 2.0: binary GLB out (plain or KHR_draco_mesh_compression), GLB and
// self-contained .gltf in. glTF's unit is the metre and its up axis is +Y;
// fabmesh's models are Z-up in model units.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// Model frame (Z-up, model units) to glTF's (Y-up, metres): scaled, then
/// rotated by -90 degrees about x, (x, y, z) -> (x, z, -y). A rotation keeps
/// counter-clockwise front faces counter-clockwise.
TriangleSoup to_gltf_frame(const TriangleSoup& soup, double scale_to_metres);

/// The inverse of to_gltf_frame: (x, y, z) -> (x, -z, y), then scaled by
/// units_per_metre (e.g. 1000 for mm).
TriangleSoup from_gltf_frame(const TriangleSoup& soup, double units_per_metre);

/// A material of the GLB writer: faces drawn in one colour.
struct GlbMaterial {
  std::string name;
  std::array<double, 4> rgba{0.8, 0.8, 0.8, 1.0};  ///< baseColorFactor, linear, each in [0, 1]
};

/// Options of the GLB writer.
struct GlbOptions {
  std::string name = "mesh";      ///< the node's and the mesh's name
  double scale_to_metres = 1e-3;  ///< metres per model unit (0.001 for mm, 0.01 for cm)
  /// KHR_draco_mesh_compression: positions quantized to draco_position_bits
  /// (each vertex moves by at most draco_max_error(lo, hi, bits) of the
  /// metre-scaled, Y-up bounding box; see io/mesh/draco.h).
  bool draco = false;
  int draco_position_bits = 14;  ///< in [1, 30]
  int draco_encoding_speed = 5;  ///< 0 (smallest) .. 10 (fastest)
  int draco_decoding_speed = 5;  ///< 0 .. 10
  /// Empty (default): one primitive without a material. Else the faces are
  /// drawn by material (`check --mark`): face f with materials[face_materials[f]],
  /// one primitive per material that has faces, in material order, all
  /// sharing the one POSITION accessor. Not with draco.
  std::vector<GlbMaterial> materials;
  std::vector<std::uint32_t> face_materials;  ///< one per face when materials is not empty
};

/// GLB bytes of `soup`: one scene, one node, one mesh with one triangle
/// primitive (mode 4). Positions are float32 in metres, Y-up
/// (to_gltf_frame); the POSITION accessor's min/max are exactly the stored
/// (for Draco: the decoded) floats. Indices are uint16 when there are at most
/// 65535 vertices, else uint32 (the all-ones value, primitive restart, is
/// never used). No normals: glTF requires viewers to compute flat normals
/// when there are none, which is right for a faceted mesh. asset.generator
/// is "fabmesh". Deterministic.
/// With options.draco, the primitive carries KHR_draco_mesh_compression
/// (declared in extensionsUsed and extensionsRequired): one bufferView of
/// Draco data, accessors with count, min and max but no bufferView.
/// \throw InputError when the soup has no triangle, an index is out of range,
/// a coordinate is not finite or overflows float32 in metres, or the Draco
/// encoder refuses the mesh; RangeError for scale_to_metres <= 0, the
/// Draco options out of range, or materials with draco, face_materials not
/// one per face or naming no material.
std::string encode_glb(const TriangleSoup& soup, const GlbOptions& options);

/// One mesh instance of a glTF scene: a node with a mesh that gave triangles.
struct GltfInstance {
  /// The node's name; else its mesh's name and the node's index ("cup (node
  /// 3)"); else "node 3".
  std::string name;
  std::size_t first_vertex = 0;    ///< its vertices in GltfContent::soup start here
  std::size_t first_triangle = 0;  ///< and its triangles here; both end where the next instance's start
};

/// What parse_gltf read and what it did to it.
struct GltfContent {
  /// Every triangle of the scene, metres, in the file's frame (Y-up), each
  /// mesh instance placed by its node's global transform. Vertices are not
  /// shared between primitives.
  TriangleSoup soup;
  std::size_t primitives = 0;             ///< triangle primitives read (modes 4, 5, 6)
  std::size_t draco_primitives = 0;       ///< of which KHR_draco_mesh_compression
  std::size_t skipped_primitives = 0;     ///< points and lines (modes 0-3): no surface
  std::size_t transformed_instances = 0;  ///< mesh instances with a non-identity transform
  std::size_t mirrored_instances = 0;     ///< of which mirrored (negative determinant): winding reversed
  /// Every node instance of a mesh that gave triangles, in scene order
  /// (depth first): the soup is their concatenation.
  std::vector<GltfInstance> instances;
};

/// Limits of the glTF reader.
struct GltfReadOptions {
  /// Most triangles (and, x 3, vertices) returned: nodes can instance a
  /// mesh many times over.
  std::size_t max_triangles = 20000000;
};

/// Parses a .glb or a self-contained .gltf (JSON whose buffers are data:
/// URIs), told apart by content (GLB starts with "glTF"). Reads the default
/// scene (else scene 0; with no scene, every root node) with node transforms
/// (matrix or TRS); triangles, triangle strips and fans; POSITION as float
/// or (KHR_mesh_quantization) normalized or integer components; sparse
/// accessors; indices of any unsigned type, or none; Draco-compressed
/// primitives. Points and lines are skipped and counted. A mirrored node
/// transform reverses the winding, as glTF specifies.
/// Never touches the filesystem or network: a buffer in an external file is
/// refused with a FileError (the bytes alone must hold the model), images
/// are not decoded.
/// \param name the path, for messages
/// \throw FileError naming the file for malformed input: a bad GLB container
/// or JSON, references out of range, accessors that do not fit their
/// buffers, an index beyond the vertices, a non-finite position, a node
/// graph that is not a forest, a required extension that changes geometry
/// and is not supported (e.g. EXT_meshopt_compression), external buffers,
/// or more than options.max_triangles.
GltfContent parse_gltf(std::string_view bytes, const std::string& name, const GltfReadOptions& options = {});

}  // namespace fabmesh
