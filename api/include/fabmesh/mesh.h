#pragma once
// Triangle meshes as plain arrays, read from and written to mesh files, and
// judged valid or not with the same proofs as `fabmesh check`.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fabmesh/units.h"

namespace fabmesh {
namespace api {

using Point = std::array<double, 3>;
using Triangle = std::array<std::uint32_t, 3>;  ///< vertex indices, counter-clockwise seen from outside

/// An indexed triangle mesh.
struct Mesh {
  std::vector<Point> vertices;
  std::vector<Triangle> triangles;
  /// The unit of the coordinates: as the file states it (3MF, glTF), or
  /// none for formats that carry none (STL, OBJ, PLY, OFF, Draco).
  std::optional<Unit> units;
};

/// A mesh given by pointers into the caller's arrays (numpy's, say): `vertex_count` x 3
/// doubles and `triangle_count` x 3 indices (64- or 32-bit: set one of the two
/// pointers), rows contiguous. The call that reads it copies it once; the
/// arrays must outlive that call.
struct MeshView {
  const double* vertices = nullptr;
  std::size_t vertex_count = 0;
  const std::int64_t* triangles = nullptr;
  const std::int32_t* triangles32 = nullptr;
  std::size_t triangle_count = 0;
};

/// What `validate` and `check` may do.
struct ValidationOptions {
  /// Merge vertices closer than this first (an STL's copies of one corner
  /// are merged at 0, exact equality), as `fabmesh check --weld-tolerance`.
  double weld_tolerance = 0.0;
  /// Gives up the self-intersection test after this many seconds (the mesh
  /// is then not called valid), as `fabmesh check --max-seconds`; 0: no limit.
  double max_seconds = 600.0;
};

/// The kinds of defect a mesh can have (docs/validity.md).
enum class DefectKind {
  Empty,                    ///< no faces at all
  NonFiniteVertex,          ///< a coordinate is NaN or infinite
  BoundaryEdge,             ///< an edge with one face (the mesh is not closed)
  NonManifoldEdge,          ///< an edge with three or more faces
  NonManifoldVertex,        ///< a vertex whose faces form more than one fan
  InconsistentOrientation,  ///< two faces traverse their shared edge the same way
  InsideOut,                ///< closed, but the signed volume is not positive
  InvertedComponent,        ///< of several components, one inside no other faces inward
  NestedSameOrientation,    ///< a component faces the way of the innermost one containing it
  DegenerateFace,           ///< zero area
  DuplicateFace,            ///< another face has the same three vertices
  SelfIntersection,         ///< two faces meet away from their shared vertices and edges
};

/// The kind as the JSON reports name it: "boundary_edge", "inverted_component", ...
const char* to_string(DefectKind kind);

/// One kind of defect found: its kind, how many, and a few places (edge
/// midpoints, vertices or face centroids).
struct Defect {
  DefectKind kind = DefectKind::Empty;
  std::size_t count = 0;
  std::vector<Point> examples;
};

/// The verdict on one mesh, as `fabmesh check` gives it (docs/validity.md).
struct ValidationReport {
  bool valid = false;       ///< watertight, manifold, consistently oriented outward, no self-intersection
  bool watertight = false;  ///< no boundary and no non-manifold edge
  bool manifold = false;    ///< no non-manifold edge or vertex
  bool oriented_outward = false;
  bool self_intersecting = false;
  std::size_t vertices = 0, triangles = 0, components = 0;
  std::size_t boundary_edges = 0, non_manifold_edges = 0, non_manifold_vertices = 0;
  std::size_t degenerate_faces = 0;
  std::optional<long> genus;  ///< when closed and manifold
  double volume = 0.0;        ///< signed enclosed volume, the mesh's units cubed
  double area = 0.0;          ///< surface area, the mesh's units squared
  std::vector<Defect> defects;
  /// check_file of a file that could not be read: why (the command line's
  /// message); `valid` is false and the counts are 0. Empty otherwise.
  std::string error;
  /// The same facts as one item of `fabmesh check --json` (docs/reports.md),
  /// timings included, as JSON text.
  std::string to_json() const { return json_; }

  /// For the library's own implementation: the JSON to_json returns.
  void set_json(std::string json) { json_ = std::move(json); }

 private:
  std::string json_;
};

/// Validates `mesh` after welding as `options` say: topology, orientation,
/// nesting of components, exact self-intersection test. An invalid mesh is a
/// report with `valid` false, not an exception.
/// \throw InputError ("triangles") for an index outside the vertices, or
///        ("vertices") for arrays of no rows where rows were promised
ValidationReport validate(const MeshView& mesh, const ValidationOptions& options = {});
/// The same for a Mesh.
ValidationReport validate(const Mesh& mesh, const ValidationOptions& options = {});

/// Reads a mesh file (STL, OBJ, PLY, OFF, 3MF, glTF/GLB, Draco), by its
/// content, as `fabmesh check` does; a file of several objects gives them
/// all in one mesh. \throw InputError naming the file (and line where known)
Mesh read_mesh(const std::filesystem::path& path);

/// Reads and validates a mesh file exactly as `fabmesh check FILE`: each
/// object of a multi-object file judged on its own, then whether they
/// interpenetrate (the report's counts, volume and area are then the sums
/// over the objects, and `json` has each). An unreadable file is a report
/// with `valid` false and its `error`, as the command line's item (docs/reports.md).
ValidationReport check_file(const std::filesystem::path& path, const ValidationOptions& options = {});

/// How write_mesh writes.
struct WriteOptions {
  /// The unit of the mesh's coordinates, stated in files that carry one
  /// (3MF, glTF: converted to metres); none: Mesh::units, or mm.
  std::optional<Unit> units;
  /// .drc only: no vertex moves by more than this through quantization,
  /// the mesh's units; > 0.
  double draco_tolerance = 1e-3;
};

/// Writes `mesh` to `path` in the format its extension names (.stl, .obj,
/// .ply, .off, .3mf, .glb, .drc; any case), all or nothing (a temporary file
/// renamed into place). Nothing is validated: write what `validate` passed.
/// \throw InputError for an unknown extension, a bad index or a coordinate
///        that is not finite ("vertices"), MachineError when the file cannot be written
void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const WriteOptions& options = {});

}  // namespace api
#ifndef FABMESH_BUILDING_LIBRARY
using namespace api;  // fabmesh::Design, fabmesh::build, ...
#endif
}  // namespace fabmesh
