#include "geometry/sampling/offset_bezier.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

constexpr int kCells = 16;  // cells per piece for the proof

// sup |p''| over the piece, in s: 6 max |second difference| / h^2.
double second_derivative_bound(const BezierPiece& p, double h) {
  const double d0 = (p.poles[2] - 2.0 * p.poles[1] + p.poles[0]).norm();
  const double d1 = (p.poles[3] - 2.0 * p.poles[2] + p.poles[1]).norm();
  return 6.0 * std::max(d0, d1) / (h * h);
}

// The proven bound of |o - p| over [a, b].
double piece_bound(const Segment& segment, const OffsetSpec& offset, const OffsetChordBound& chord,
                   const BezierPiece& p, double a, double b) {
  const double h = b - a, cell = h / kCells;
  const double p2 = second_derivative_bound(p, h);
  double at_ends = 0.0, inside = 0.0;
  ChordBound::Ends previous = chord.at(a);
  for (int i = 0; i <= kCells; ++i) {
    const double s = i == kCells ? b : a + i * cell;
    const double w = (s - a) / h;
    at_ends = std::max(at_ends, (offset_jet(segment, offset, s).point - evaluate(p, w)).norm());
    if (i == 0) continue;
    const double s_prev = a + (i - 1) * cell;
    const ChordBound::Ends ends = chord.at(s);
    inside = std::max(inside, chord.bound(s_prev, s, previous, ends) + cell * cell / 8.0 * p2);
    previous = ends;
  }
  return at_ends + inside;
}

}  // namespace

std::vector<ExactPiece> exact_pieces(const CompositeCurve& curve) {
  std::vector<ExactPiece> pieces;
  for (const Segment& s : curve.segments()) pieces.push_back({s, {}, 0.0, 1.0});
  return pieces;
}

BezierApproximation offset_approximation(const ExactPiece& piece, double tolerance, int max_pieces) {
  if (!(tolerance > 0.0)) {
    throw RangeError("tolerance", tolerance,
                     fmt::format("the approximation's tolerance must be > 0, not {}", tolerance));
  }
  const double lo = std::min(piece.s0, piece.s1), hi = std::max(piece.s0, piece.s1);
  const OffsetChordBound chord(piece.segment, piece.offset);
  for (int n = 1; n <= max_pieces; n *= 2) {
    BezierApproximation out;
    const double h = (hi - lo) / n;
    OffsetJet start = offset_jet(piece.segment, piece.offset, lo);
    for (int i = 0; i < n && out.bound <= tolerance; ++i) {
      const double a = lo + i * h, b = i + 1 == n ? hi : lo + (i + 1) * h;
      const OffsetJet end = offset_jet(piece.segment, piece.offset, b);
      out.pieces.push_back(hermite_cubic(start.point, start.d1, end.point, end.d1, b - a));
      out.bound =
          std::max(out.bound, piece_bound(piece.segment, piece.offset, chord, out.pieces.back(), a, b));
      start = end;
    }
    if (out.bound > tolerance) continue;
    if (piece.s0 > piece.s1) {  // run the other way: pieces and their poles reversed
      std::reverse(out.pieces.begin(), out.pieces.end());
      for (BezierPiece& p : out.pieces) std::reverse(p.poles.begin(), p.poles.end());
    }
    return out;
  }
  throw GeometryError(piece.offset.what,
                      fmt::format("approximating the offset of a {} segment ({} {}) within {:.3g} needs more "
                                  "than {} cubic pieces",
                                  to_string(piece.segment.kind()), piece.offset.what, piece.offset.distance,
                                  tolerance, max_pieces));
}

}  // namespace fabmesh
