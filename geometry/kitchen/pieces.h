#pragma once
// A kitchen's top cut into pieces at straight seams: each seam is the chord
// of a straight line through the top, each piece keeps its own cut-outs and
// knows which of its edges are seams; with `seams: auto`, the fewest seams
// that make every piece fit a slab.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/section/region.h"

namespace fabmesh {

/// What an edge of a piece is: cut to be seen, against a wall, or a joint.
enum class EdgeKind { Exposed, Wall, Seam };

/// "exposed", "wall", "seam".
const char* to_string(EdgeKind kind);

/// A seam the design gives (key `seams[i]`): the straight line through `at`
/// along `direction`; it cuts the piece of the top that `at` lies in (or on
/// the edge of), from boundary to boundary.
struct SeamSpec {
  Vec2 at{0.0, 0.0};
  Vec2 direction{0.0, 1.0};
  std::string key;  ///< "seams[1]", where errors about it are
};

/// One piece of the top: a polygon with holes (outer loop counter-clockwise,
/// holes clockwise), in the design's frame.
struct KitchenPiece {
  std::string name;  ///< "piece-1", ...
  std::vector<Vec2> outer;
  std::vector<EdgeKind> edges;  ///< edge i runs from outer[i] to outer[i + 1] (the last one closes)
  /// Where each point of `outer` lies on the exact outline (its global
  /// parameter, Region2::outer_along); a seam's end is where the exact
  /// outline crosses the seam's line (found by bisection between the
  /// parameters of the edge it cuts). NaN when the outline was not given.
  std::vector<double> along;
  std::vector<std::vector<Vec2>> holes;
  std::vector<std::size_t> hole_index;  ///< the design's hole each of `holes` is (index into Region2::holes)
  double area = 0.0;                    ///< outer minus holes
  /// A backsplash strip (backsplash_strips): a rectangle of its own, not a part of the top.
  bool strip = false;
};

/// A seam as cut: the chord between two points of the top's boundary.
struct SeamCut {
  Vec2 from{0.0, 0.0};
  Vec2 to{0.0, 0.0};
  std::string key;  ///< "seams[1]", or "seams (auto)" for a seam the search chose
  /// The least distance from the chord to a cut-out's sampled loop, less the
  /// loops' deviation from their exact curves: a proven lower bound of its
  /// distance to the exact cut-outs; infinity with none.
  double clearance = 0.0;
};

struct SplitOptions {
  double seam_clearance = 100.0;  ///< least distance from a seam to any cut-out (model units)
  double deviation = 0.0;         ///< the region's proven bound against its exact curves
  /// The region's exact outline (build_region's), for the pieces' `along`; null: none.
  const CompositeCurve* outline = nullptr;
};

/// The usable area of a slab for `seams: auto`: a piece fits when its
/// bounding box, turned as the grain allows, fits inside length x width.
struct SlabFit {
  double length = 0.0;
  double width = 0.0;
  bool grain_along = true;  ///< the piece's long side along `length` only
  /// The router cuts no sharp inside corner (cnc without dog-bones): a piece
  /// with an inside corner of 30 degrees or more must be split there too.
  bool no_inside_corners = false;
};

struct KitchenSplit {
  std::vector<KitchenPiece> pieces;  ///< named piece-1, ... in order of their lowest-leftmost point
  std::vector<SeamCut> seams;
  std::string proof;  ///< why the pieces partition the top (for reports)
};

/// Cuts `region` at `seams`, in order: each seam splits the piece its `at`
/// lies in. Edges of `region` keep `kinds` (one per outer edge, Exposed
/// when empty).
/// \throw GeometryError at the seam's key: `at` not in the top, a seam
///        running along the outline, or one that passes a cut-out closer than
///        seam_clearance (through it: "through holes[0]").
KitchenSplit split_top(const Region2& region, const std::vector<SeamSpec>& seams, const SplitOptions& options,
                       const std::vector<EdgeKind>& kinds = {});

/// The fewest seams (up to 8) that leave every piece fitting `slab`, each
/// seam at least seam_clearance from every cut-out and no piece narrower:
/// lines on from the sides of an inside corner (butt joints at an L's or a
/// U's inside corner) tried first, then cuts across a piece's long (or
/// short) side, balanced, then as far along as the slab allows. When the
/// search finds none within its bound on tries, a greedy split (each piece
/// at its first candidate that works, up to 64 seams).
/// \throw GeometryError at key `seams` naming the piece and the dimension
///        that no seam can bring within the slab.
KitchenSplit auto_split(const Region2& region, const SlabFit& slab, const SplitOptions& options,
                        const std::vector<EdgeKind>& kinds = {});

/// A piece's exact outer boundary, running the outline's way: the stretches
/// of the exact outline between its seams (whole segments kept; a line or an
/// elliptic arc cut where a seam ends, exactly) and the seams as lines
/// between their exact ends. `reversed`: the region's outer loop runs
/// against the outline (Region2::reversed[0]).
/// \throw GeometryError when a seam ends inside a free-form segment
///        (T-Bézier, H-Bézier, B-spline, NURBS), whose part has no exact
///        form of its own here, naming the segment.
CompositeCurve exact_piece_outline(const KitchenPiece& piece, const CompositeCurve& outline, bool reversed);

/// The edge kinds of `region`'s outer loop: Wall where the exact outline's
/// segment is marked a wall (`wall_segment[i]`, one per outline segment),
/// Exposed elsewhere; each edge lies in the segment of its middle parameter.
std::vector<EdgeKind> outline_edge_kinds(const Region2& region, const std::vector<bool>& wall_segment);

/// Backsplash strips along the pieces' wall edges: one per straight run of
/// consecutive wall edges of a piece (its points within `tolerance` of the
/// run's chord), `height` x the run's length, named backsplash-1, ... in the
/// pieces' order; its long bottom edge, which stands on the top, marked
/// Seam (a joint, cut straight and square), the rest Exposed. A run that is not straight gets none: its
/// length goes into `curved` (for a warning).
std::vector<KitchenPiece> backsplash_strips(const std::vector<KitchenPiece>& pieces, double height,
                                            double tolerance, std::vector<std::string>& curved);

/// The lengths of a piece's exposed, wall and seam edges, in that order.
std::array<double, 3> edge_lengths(const KitchenPiece& piece);

/// Whether a piece's bounding box fits `slab` in a turn the grain allows.
bool fits_slab(const std::vector<Vec2>& outer, const SlabFit& slab);

}  // namespace fabmesh
