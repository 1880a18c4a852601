#pragma once
// 3MF (3D Manufacturing Format, the slicers' native format) through lib3mf 1.8:
// one mesh object and one build item per body, the unit in the model.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// One body of a 3MF model: a named triangle soup.
struct ThreeMfObject {
  std::string name;   ///< the object's name attribute (may be empty)
  TriangleSoup soup;  ///< model units (ThreeMfOptions::units / ThreeMfContent::unit)
  /// Read: the id of the build item's object in the model part (0 when
  /// unknown); ignored by the writer, which numbers the objects itself.
  std::uint32_t resource_id = 0;
};

/// Options of the 3MF writer.
struct ThreeMfOptions {
  /// The model's unit: "micron", "mm", "cm", "m", "in" or "ft" (3MF's
  /// micrometer, millimeter, centimeter, meter, inch, foot). Coordinates are
  /// written as given: the caller converts.
  std::string units = "mm";
  std::string title;  ///< metadata Title (the design's name); omitted when empty
};

/// The model unit named by `units` in metres per unit (e.g. "cm" -> 0.01).
/// \throw InputError for a name that is not one of ThreeMfOptions::units'.
double threemf_metres_per_unit(const std::string& units);

/// Bound on how far lib3mf 1.8's writing moves a coordinate of magnitude at
/// most `max_abs_coordinate` (model units), Euclidean over the three axes:
/// rounding to float32, then lib3mf's truncation (toward zero, in float32
/// arithmetic) to 6 decimals, then a reader's rounding back to float32:
/// per axis 1e-6 + 3 * 2^-24 * |x| (with a margin for the float product).
double threemf_max_error(double max_abs_coordinate);

/// 3MF bytes of `objects`: one mesh object with a build item per object (no
/// transform), the model unit from options.units, metadata Title (when
/// given) and Application = "fabmesh". Vertices are stored as float32 and
/// written by lib3mf with 6 decimals (see threemf_max_error). Deterministic:
/// the zip entries carry no timestamp and the production extension's UUIDs
/// are derived from the content instead of drawn at random.
/// \throw InputError when there is no object, an object has no triangle, an
/// index is out of range, a coordinate is not finite or |x| >= 1e9 (lib3mf
/// converts coordinates to 64-bit integers of micro-units), or units is
/// unknown; std::runtime_error if lib3mf itself fails.
std::string encode_3mf(const std::vector<ThreeMfObject>& objects, const ThreeMfOptions& options);

/// What a 3MF file holds: one soup per build item.
struct ThreeMfContent {
  /// The model unit, as in ThreeMfOptions::units ("mm" when the file states none).
  std::string unit = "mm";
  double metres_per_unit = 0.001;
  /// One per build item, in build order: the item's object (a mesh, or
  /// components resolved recursively) with every transform applied, in
  /// model units. A transform with a negative determinant (a mirror)
  /// reverses the triangles' corner order so that outward stays outward.
  std::vector<ThreeMfObject> objects;
  /// What the reader tolerated, e.g. a thumbnail the package refers to but
  /// does not contain.
  std::vector<std::string> warnings;
};

/// A minimal 3MF package (content types, root relationship, stored zip
/// entries) whose 3D model part 3D/3dmodel.model is `model_xml`, unchecked:
/// for tests and fuzzing lib3mf's XML reading with well-formed packages.
std::string threemf_package(std::string_view model_xml);

/// True when `bytes` is a zip archive holding a part whose name ends in
/// ".model" (a 3MF package's 3D model part, usually 3D/3dmodel.model).
bool looks_like_3mf(std::string_view bytes);

/// Limits of the 3MF reader.
struct ThreeMfReadOptions {
  /// Most triangles (all build items, components expanded) the reader
  /// returns, and x 3 vertices; components can instance a mesh many times over.
  std::size_t max_triangles = 20000000;
};

/// Parses 3MF bytes (read from memory, no file is touched).
/// \param name the path, for messages
/// A package whose root relationships name a thumbnail part it does not
/// hold (PrusaSlicer 2.5's command-line exports) is read with an empty
/// thumbnail, and content.warnings says so.
/// \throw FileError naming the file when the bytes are not a 3MF package,
/// lib3mf refuses them, the build is empty of meshes, a coordinate is not
/// finite, components nest deeper than 64, or the result would exceed
/// options.max_triangles.
ThreeMfContent parse_3mf(std::string_view bytes, const std::string& name,
                         const ThreeMfReadOptions& options = {});

/// All objects of `content` in one soup (vertices not shared between objects).
TriangleSoup merged_soup(const ThreeMfContent& content);

}  // namespace fabmesh
