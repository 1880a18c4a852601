// A shell's inner wall for STEP: cubic Hermite pieces of a segment's offset,
// never farther from the exact offset than their proven bound.

#include "geometry/sampling/offset_bezier.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"

using namespace fabmesh;

namespace {

// The largest distance between the exact offset and the pieces over 10000
// parameters from s0 to s1.
double measured_gap(const ExactPiece& piece, const BezierApproximation& a) {
  const int samples = 10000;
  const double n = static_cast<double>(a.pieces.size());
  double gap = 0.0;
  for (int i = 0; i <= samples; ++i) {
    const double u = static_cast<double>(i) / samples;  // 0 at s0, 1 at s1
    const double s = piece.s0 + u * (piece.s1 - piece.s0);
    const std::size_t k = std::min(a.pieces.size() - 1, static_cast<std::size_t>(u * n));
    const double local = u * n - static_cast<double>(k);
    gap = std::max(gap,
                   (offset_jet(piece.segment, piece.offset, s).point - evaluate(a.pieces[k], local)).norm());
  }
  return gap;
}

}  // namespace

TEST_CASE("offset bezier: the pieces stay within their proven bound, either way round",
          "[sampling][offset_bezier]") {
  // The golden profile's second span, and a T-Bézier arc, offset by a wall inward.
  const Segment span =
      Segment::quasi_bspline_span({Vec2(1.5, 6.0), Vec2(1.0, 5.0), Vec2(2.0, 4.0), Vec2(3.0, 3.0)}, 0.0, 0.0);
  const Segment arc =
      Segment::tbezier({Vec2(3.0, 0.0), Vec2(3.0, 1.5), Vec2(1.5, 3.0), Vec2(0.0, 3.0)}, 0.5, -0.5);
  for (const Segment& segment : {span, arc}) {
    for (const double side : {1.0, -1.0}) {
      for (const auto& range : {std::pair{0.0, 1.0}, std::pair{1.0, 0.0}, std::pair{0.2, 0.7}}) {
        OffsetSpec offset;
        offset.distance = 0.3;
        offset.side = side;
        const ExactPiece piece{segment, offset, range.first, range.second};
        for (const double tolerance : {1e-3, 1e-6}) {
          const BezierApproximation a = offset_approximation(piece, tolerance);
          INFO(to_string(segment.kind())
               << " side " << side << " from " << range.first << " to " << range.second << ", tolerance "
               << tolerance << ", " << a.pieces.size() << " pieces, bound " << a.bound);
          CHECK(a.bound <= tolerance);
          CHECK(measured_gap(piece, a) <= a.bound);
          // The ends are the offset's, in the piece's direction; the pieces join with one tangent.
          CHECK((a.pieces.front().poles.front() - offset_jet(segment, offset, range.first).point).norm() <=
                1e-12);
          CHECK((a.pieces.back().poles.back() - offset_jet(segment, offset, range.second).point).norm() <=
                1e-12);
          for (std::size_t k = 1; k < a.pieces.size(); ++k) {
            CHECK(a.pieces[k - 1].poles[3] == a.pieces[k].poles[0]);
            const Vec2 in = a.pieces[k - 1].poles[3] - a.pieces[k - 1].poles[2];
            const Vec2 out = a.pieces[k].poles[1] - a.pieces[k].poles[0];
            CHECK((in - out).norm() <= 1e-12);
          }
        }
      }
    }
  }
}

TEST_CASE("offset bezier: an offset that folds is a GeometryError, not a bound",
          "[sampling][offset_bezier]") {
  // A quarter circle of radius 3 offset 4 toward its centre folds.
  const Segment arc = Segment::ellipse_arc({Vec2(0.0, 0.0), 3.0, 3.0, 0.0, 0.0, 90.0});
  OffsetSpec offset;
  offset.distance = 4.0;
  offset.side = 1.0;
  CHECK_THROWS_AS(offset_approximation({arc, offset, 0.0, 1.0}, 1e-3), GeometryError);
}
