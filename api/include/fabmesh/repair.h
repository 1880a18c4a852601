#pragma once
// Meshes from elsewhere made valid for fabrication, as `fabmesh repair` does
// (docs/repair.md): every change recorded with where, the distance moved
// measured, nothing dropped unsaid.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fabmesh/mesh.h"

namespace fabmesh {
namespace api {

/// What a repair may do (the command line's options).
struct RepairOptions {
  /// Refuse (RepairReport::valid false) when the result would be farther than
  /// this from the input (the mesh's units); 0: no limit. With `wrap`, it also
  /// sets the wrap's alpha (half of it) and offset (a quarter).
  double max_deviation = 0.0;
  /// Replace the mesh by a closed surface wrapped around it (CGAL alpha
  /// wrapping): lossy by design, its distance measured. Only when asked.
  bool wrap = false;
  /// Merge border vertices closer than this (the mesh's units); < 0: chosen
  /// from the data and reported (RepairReport::weld_distance); 0: none.
  double weld_distance = -1.0;
  bool fill_holes = true;      ///< fill holes (else a mesh with holes is refused)
  double max_seconds = 600.0;  ///< time budget of each self-intersection test (0: none)
};

/// One place a repair step acted on: indices into the mesh given (when the
/// place is one of its faces or vertices) and a point.
struct RepairPlace {
  std::optional<std::size_t> face;
  std::optional<std::size_t> vertex;
  Point point{};
  std::string detail;
};

/// One kind of repair step and where it acted ("weld", "degenerate_face",
/// "duplicate_face", "stitch", "non_manifold_edge", "non_manifold_vertex",
/// "orientation", "hole_fill", "drop_component", "self_intersection",
/// "union", "outward", "wrap").
struct RepairStep {
  std::string step;
  std::size_t count = 0;
  std::string detail;
  std::vector<RepairPlace> places;  ///< the first 20
};

/// A component removed, with its size and why.
struct DroppedComponent {
  std::size_t faces = 0;
  std::optional<std::size_t> first_face;
  double area = 0.0;
  Point min{}, max{};
  std::string why;
};

/// What a repair did and got.
struct RepairReport {
  bool valid = false;    ///< `mesh` is valid for fabrication and within max_deviation
  bool changed = false;  ///< false: the input was valid already (returned welded)
  Mesh mesh;             ///< the result (its units those of the input); the input welded when not valid
  std::vector<RepairStep> steps;
  std::vector<DroppedComponent> dropped;
  double weld_distance = 0.0;  ///< the border weld's distance (0: none)
  /// Proven bound of the two-sided distance between input and result (the
  /// mesh's units; docs/repair.md explains the bound).
  double distance = 0.0;
  std::size_t components_before = 0, components_after = 0;
  double volume_before = 0.0, volume_after = 0.0, area_before = 0.0, area_after = 0.0;
  /// What could not be mended, one line each with where; empty when valid.
  std::vector<std::string> unresolved;
  ValidationReport after;  ///< the result's verdict, as `validate` gives it
  /// The same facts as the command line's `repair --json` item, as JSON text.
  std::string to_json() const { return json_; }

  /// For the library's own implementation: the JSON to_json returns.
  void set_json(std::string json) { json_ = std::move(json); }

 private:
  std::string json_;
};

/// Repairs `mesh` (docs/repair.md). A mesh that cannot be mended is a report
/// with `valid` false and its `unresolved` lines, not an exception.
/// \throw InputError for an empty mesh, a non-finite coordinate, an index
///        out of range, or a negative option
RepairReport repair(const MeshView& mesh, const RepairOptions& options = {});
/// The same for a Mesh (its units kept in the result).
RepairReport repair(const Mesh& mesh, const RepairOptions& options = {});

/// Repairs the mesh file `input` and writes the result to `output` (its
/// ending names the format: .3mf, .stl, .obj, .ply, .off), exactly as
/// `fabmesh repair INPUT -o OUTPUT`: read back and validated before it is
/// written, all or nothing. Returns the command line's `--json` item as
/// JSON text; its "exit_code" is 0 when written, 1 when refused (nothing
/// written). \throw InputError when `input` cannot be read or `output`
/// names no format repair writes, MachineError when it cannot be written
std::string repair_file(const std::filesystem::path& input, const std::filesystem::path& output,
                        const RepairOptions& options = {});

}  // namespace api
#ifndef FABMESH_BUILDING_LIBRARY
using namespace api;
#endif
}  // namespace fabmesh
