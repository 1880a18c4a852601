#include "geometry/sampling/offset_curve.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/error_checks.h"

namespace fabmesh {
namespace {

// Ends layout: |o''|, |r'|, |r''|, |r'''|, k.
enum End { O2 = 0, Speed = 1, R2 = 2, R3 = 3, Curvature = 4 };

// Pieces shorter than this cannot be split usefully (parameters are in [0, 1]).
constexpr double kShortestPiece = 1e-9;

std::string near(const Vec2& p) { return fmt::format("({:.6g}, {:.6g})", p.x(), p.y()); }

}  // namespace

OffsetJet offset_jet(const Segment& segment, const OffsetSpec& offset, double s) {
  const CurveJet j = segment.jet(s);
  const double sigma = j[1].norm();
  if (!(sigma > 0.0)) {
    throw GeometryError(ErrorLocation{},
                        fmt::format("{}: the curve stops (zero speed) at {}, so its {} offset is "
                                    "undefined there",
                                    offset.where, near(j[0]), offset.what));
  }
  const Vec2 t = j[1] / sigma;
  const Vec2 n(-t.y(), t.x());
  // Turning rate theta' = cross(r', r'') / |r'|^2 and its derivative, in s.
  const double c = cross2(j[1], j[2]);
  const double c1 = cross2(j[1], j[3]);
  const double sigma1 = t.dot(j[2]);
  const double theta1 = c / (sigma * sigma);
  const double theta2 = c1 / (sigma * sigma) - 2.0 * c * sigma1 / (sigma * sigma * sigma);
  const double w = offset.distance * offset.side;
  // N' = -theta' T, N'' = -theta'' T - theta'^2 N.
  OffsetJet out;
  out.point = j[0] + w * n;
  out.d1 = j[1] - w * theta1 * t;
  out.d2 = j[2] + w * (-theta2 * t - theta1 * theta1 * n);
  out.speed = sigma;
  out.k = offset.side * c / (sigma * sigma * sigma);
  return out;
}

OffsetChordBound::OffsetChordBound(const Segment& segment, const OffsetSpec& offset)
    : segment_(&segment), offset_(offset) {
  require_positive(offset.what, offset.distance);
  if (segment.kind() != SegmentKind::Line) {
    m3_ = third_derivative_bound(segment);
    m4_ = segment.fourth_derivative_bound();
  }
}

ChordBound::Ends OffsetChordBound::at(double s) const {
  const OffsetJet o = offset_jet(*segment_, offset_, s);
  if (o.k * offset_.distance >= 1.0) {
    const Vec2 p = segment_->point(s);
    throw GeometryError(ErrorLocation{"wall", {}, {p.x(), p.y()}},
                        fmt::format("{} is too thick for the profile: its radius of curvature is "
                                    "{:.6g} at {} ({}), so the inner surface would fold over",
                                    offset_.what, 1.0 / o.k, near(p), offset_.where));
  }
  const CurveJet j = segment_->jet(s);
  Ends e{};
  e[O2] = o.d2.norm();
  e[Speed] = o.speed;
  e[R2] = j[2].norm();
  e[R3] = j[3].norm();
  e[Curvature] = o.k;
  return e;
}

double OffsetChordBound::bound(double s0, double s1, const Ends& a, const Ends& b) const {
  const double h = s1 - s0, half = 0.5 * h, d = offset_.distance;
  const double inf = std::numeric_limits<double>::infinity();
  // Bounds over the piece: each from its end values and the next derivative's bound.
  const double m3 = std::min(m3_, std::max(a[R3], b[R3]) + half * m4_);
  const double m2 = std::max(a[R2], b[R2]) + half * m3;
  const double sigma = std::min(a[Speed], b[Speed]) - half * m2;
  const bool unsplittable = h <= kShortestPiece;
  if (!(sigma > 0.0)) {
    if (unsplittable) {
      throw GeometryError(
          ErrorLocation{},
          fmt::format("{}: the curve's speed cannot be bounded away from zero near {}, so its {} "
                      "offset cannot be proven",
                      offset_.where, near(segment_->point(s0)), offset_.what));
    }
    return inf;
  }
  // |k'| <= |cross(r', r''')| / |r'|^3 + 3 |cross(r', r'')| |r'|' / |r'|^4.
  const double k_slope = m3 / (sigma * sigma) + 3.0 * m2 * m2 / (sigma * sigma * sigma);
  const double k_sup = std::max(a[Curvature], b[Curvature]) + half * k_slope;
  if (k_sup * d >= 1.0) {
    if (unsplittable) {
      const Vec2 p = segment_->point(s0);
      throw GeometryError(ErrorLocation{"wall", {}, {p.x(), p.y()}},
                          fmt::format("{} is too thick for the profile: near {} ({}) its radius of "
                                      "curvature cannot be proven larger than the wall",
                                      offset_.what, near(p), offset_.where));
    }
    return inf;
  }
  const double s2 = sigma * sigma, s3 = s2 * sigma;
  const double direct = m2 + d * (m3 / sigma + 3.0 * m2 * m2 / s2);
  const double normal3 = m4_ / sigma + 10.0 * m2 * m3 / s2 + 15.0 * m2 * m2 * m2 / s3;
  const double mean_value = std::max(a[O2], b[O2]) + half * (m3 + d * normal3);
  return h * h / 8.0 * std::min(direct, mean_value);
}

}  // namespace fabmesh
