#pragma once
// fabmesh's one DXF reader: an ASCII DXF drawing's header units and the
// entities of its ENTITIES section, read strictly from the group codes
// (io/dxf/dxf_groups.h). The whole file must be there: every section ends
// with ENDSEC, the drawing with EOF, every POLYLINE with SEQEND, and every
// count a polyline or spline announces agrees with the entries that follow.
// The outlines of designs (io/design/dxf_loops.h) and the tests reading back
// the DXF fabmesh writes both use it.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// One entity of the ENTITIES section, as the file gives it (group codes in
/// brackets; what an entity lacks stays at its default). Entities of block
/// definitions (BLOCKS) are not read.
struct DxfEntity {
  std::string type;               ///< the entity's name as written: LINE, ARC, LWPOLYLINE, TEXT, ...
  std::string layer = "0";        ///< [8]
  std::string handle;             ///< [5] upper-case hexadecimal; empty when absent (or not hexadecimal)
  std::size_t line = 0;           ///< the line of its `0 TYPE` group
  bool paper_space = false;       ///< [67] = 1
  Vec3 extrusion{0.0, 0.0, 1.0};  ///< [210, 220, 230]
  /// LINE: start [10] and end [11]; ARC, CIRCLE: the centre [10] (in the
  /// entity's own coordinates); ELLIPSE: the centre [10] and the end of the
  /// major axis relative to it [11]; LWPOLYLINE: the vertices [10, 20] at
  /// the elevation [38]; POLYLINE: its VERTEX entities' points [10], raised by
  /// the polyline's elevation (a spline frame's control points, VERTEX flag
  /// 16, left out); SPLINE: the control points [10].
  std::vector<Vec3> points;
  /// Polylines: the bulge [42] of the span after each vertex (0 when none).
  std::vector<double> bulges;
  /// LWPOLYLINE [38], POLYLINE [30]: the height of the polyline's plane
  /// (already added to its points' z).
  double elevation = 0.0;
  double radius = 0.0;          ///< ARC, CIRCLE: the radius [40]; ELLIPSE: minor to major axis ratio [40]
  double start = 0.0;           ///< ARC: start angle in degrees [50]; ELLIPSE: start parameter [41]
  double end = 0.0;             ///< ARC: end angle in degrees [51]; ELLIPSE: end parameter [42]
  int flags = 0;                ///< [70]: polylines (1 closed, 16 | 64 a mesh), SPLINE (1 closed, 4 rational)
  int degree = 0;               ///< SPLINE [71]
  std::vector<double> knots;    ///< SPLINE [40]
  std::vector<double> weights;  ///< SPLINE [41], one per control point, or none (all 1)
  std::size_t fit_points = 0;   ///< SPLINE: how many fit points [11]
};

/// How messages name `entity`: "LINE #2F" by its handle, "LINE (line 12)" without one.
std::string dxf_entity_name(const DxfEntity& entity);

/// What a drawing's HEADER gives.
struct DxfHeader {
  std::optional<int> insunits;  ///< $INSUNITS [70], when the header has it
};

/// Called with each entity in file order; the entity is reused for the next.
using DxfEntitySink = std::function<void(const DxfEntity&)>;

/// At most this many entities, polyline vertices, control points and knots in one drawing.
inline constexpr std::size_t kMaxDxfItems = 1000000;

/// Reads the ASCII DXF text `bytes`, hands each entity of its ENTITIES
/// section to `sink` in file order and returns its header. `path` names the
/// file in messages. \throw FileError "path:line: ..." naming the group code
/// and entity where there is one: not a DXF (an empty file, a binary DXF, a
/// line that is no group code), a number that does not parse whole or is not
/// finite, a section without ENDSEC or a drawing without EOF (a file cut
/// short), a VERTEX outside a POLYLINE or a POLYLINE without SEQEND, a count
/// (LWPOLYLINE [90], SPLINE [72, 73]) that disagrees with the entries that
/// follow or exceeds the file's lines, more than kMaxDxfItems items
DxfHeader read_dxf(std::string_view bytes, const std::string& path, const DxfEntitySink& sink);

/// Every entity of `bytes`, in file order (read_dxf, collected).
/// \throw FileError as read_dxf
std::vector<DxfEntity> read_dxf_entities(std::string_view bytes, const std::string& path);

}  // namespace fabmesh
