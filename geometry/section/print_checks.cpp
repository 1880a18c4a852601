#include "geometry/section/print_checks.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <tuple>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/sampling/offset_bezier.h"
#include "geometry/sampling/offset_curve.h"

namespace fabmesh {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSamples = 128;     // per piece, before refining
constexpr int kRefineSteps = 80;  // golden section / bisection: far below a double's resolution of [0, 1]
constexpr int kDrawSamples = 24;  // per piece of a run

// A point of the profile to 6 significant digits of the vessel's size
// `extent`: a coordinate below them (a refined maximum 1e-7 above the
// foot) is written 0, not in exponent form.
std::string at(const Vec2& p, double extent) {
  const auto shown = [extent](double x) { return std::abs(x) < 1e-6 * extent ? 0.0 : x; };
  return fmt::format("(r {:.6g}, z {:.6g})", shown(p.x()), shown(p.y()));
}

// One piece of the boundary, walked from u = 0 to 1 (s from s0 to s1).
struct Piece {
  ExactPiece exact;
  PrintFace face = PrintFace::Outer;
};

struct Jet {
  Vec2 point{0.0, 0.0};
  Vec2 tangent{0.0, 0.0};  // along the walk
};

Jet eval(const Piece& piece, double u) {
  const ExactPiece& e = piece.exact;
  const double s = e.s0 + u * (e.s1 - e.s0);
  const double dir = e.s1 >= e.s0 ? 1.0 : -1.0;
  if (e.offset.distance == 0.0) {
    const CurveJet j = e.segment.jet(s);
    return {j[0], dir * j[1]};
  }
  // The offset's tangent, o' (parallel to the segment's where the offset does not fold).
  const OffsetJet o = offset_jet(e.segment, e.offset, s);
  return {o.point, dir * o.d1};
}

// The sine of the angle from vertical of the face at `j` when it looks down (t_r > 0), else <= 0.
double lean(const Jet& j) {
  const double n = j.tangent.norm();
  return n > 0.0 ? j.tangent.x() / n : -1.0;
}

// The walk with the material on the left: the profile upward (a closed
// profile counter-clockwise), then a shell's rim and inner wall from the rim down.
std::vector<Piece> boundary(const CompositeCurve& profile, const VesselSection& section) {
  const std::vector<Segment>& segments = profile.segments();
  bool forward = true;
  if (profile.closed()) {
    double area = 0.0;  // twice the signed area of a fine polygon on the curve: its sign is the orientation
    Vec2 prev = segments.front().point(0.0);
    for (const Segment& s : segments) {
      for (int i = 1; i <= 64; ++i) {
        const Vec2 p = s.point(i / 64.0);
        area += prev.x() * p.y() - p.x() * prev.y();
        prev = p;
      }
    }
    forward = area > 0.0;
  } else {
    forward = segments.back().point(1.0).y() > segments.front().point(0.0).y();
  }
  std::vector<Piece> pieces;
  if (forward) {
    for (const Segment& s : segments) pieces.push_back({{s, {}, 0.0, 1.0}, PrintFace::Outer});
  } else {
    for (auto s = segments.rbegin(); s != segments.rend(); ++s)
      pieces.push_back({{*s, {}, 1.0, 0.0}, PrintFace::Outer});
  }
  if (section.inner_wall && !section.inner_wall->points.empty()) {
    const Vec2 top = eval(pieces.back(), 1.0).point;
    const Vec2 inner_top = section.inner_wall->points.front().point;
    if (top != inner_top) pieces.push_back({{Segment::line(top, inner_top), {}, 0.0, 1.0}, PrintFace::Rim});
    for (ExactPiece& e : inner_wall_exact_pieces(*section.inner_wall, profile))
      pieces.push_back({std::move(e), PrintFace::Inner});
  }
  return pieces;
}

// The largest value of f over [0, 1] and where: the best of kSamples + 1
// samples, refined by golden-section search between its neighbours.
std::pair<double, double> maximise(const std::function<double(double)>& f) {
  int best = 0;
  double best_value = -std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kSamples; ++i) {
    const double v = f(static_cast<double>(i) / kSamples);
    if (v > best_value) best_value = v, best = i;
  }
  double a = std::max(0, best - 1) / static_cast<double>(kSamples);
  double b = std::min(kSamples, best + 1) / static_cast<double>(kSamples);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int k = 0; k < kRefineSteps && b - a > 0.0; ++k) {
    if (fc >= fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a), fd = f(d);
    }
  }
  const double u = 0.5 * (a + b);
  const double v = f(u);
  if (v >= best_value) return {v, u};
  return {best_value, static_cast<double>(best) / kSamples};
}

// The u in [a, b] where `inside` changes, inside(a) != inside(b): bisection.
double crossing(const std::function<bool(double)>& inside, double a, double b) {
  const bool at_a = inside(a);
  for (int k = 0; k < kRefineSteps; ++k) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    (inside(m) == at_a ? a : b) = m;
  }
  return at_a ? a : b;  // the last place inside
}

// A stretch of one piece beyond the limit: [u0, u1].
struct Span {
  std::size_t piece = 0;
  double u0 = 0.0, u1 = 0.0;
};

double degrees(double sine) { return std::asin(std::clamp(sine, 0.0, 1.0)) * 180.0 / kPi; }

}  // namespace

const char* to_string(PrintFace face) {
  switch (face) {
    case PrintFace::Outer:
      return "outer wall";
    case PrintFace::Rim:
      return "rim";
    case PrintFace::Inner:
      return "inner wall";
  }
  return "?";
}

PrintCheck check_print(const CompositeCurve& profile, const VesselSection& section,
                       const PrintOptions& options) {
  if (!(options.max_overhang_deg > 0.0 && options.max_overhang_deg < 90.0))
    throw RangeError("print.max_overhang_deg", options.max_overhang_deg,
                     fmt::format("max_overhang_deg = {} must be in (0, 90)", options.max_overhang_deg));
  if (!(options.min_wall > 0.0))
    throw RangeError("print.min_wall", options.min_wall,
                     fmt::format("min_wall = {} must be > 0", options.min_wall));
  if (options.bed && !(options.bed->minCoeff() > 0.0))
    throw RangeError("print.bed", options.bed->minCoeff(), "the bed's sizes must be > 0");
  const std::vector<Piece> pieces = boundary(profile, section);
  PrintCheck out;
  out.limit_deg = options.max_overhang_deg;

  // Each piece's own measures are independent of the others': they are
  // found by blocks of pieces at once, then gathered in the pieces' order,
  // so what is reported does not depend on how the work was shared.
  const auto each_piece = [&](const auto& measure) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pieces.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i) measure(i);
                      });
  };

  // The bed's height (the lowest place) and the extent: exact extremes of r and z.
  std::vector<std::array<double, 3>> extremes(pieces.size());  // lowest z, highest z, largest r
  each_piece([&](std::size_t i) {
    const Piece& p = pieces[i];
    extremes[i] = {-maximise([&](double u) { return -eval(p, u).point.y(); }).first,
                   maximise([&](double u) { return eval(p, u).point.y(); }).first,
                   maximise([&](double u) { return eval(p, u).point.x(); }).first};
  });
  double z_low = std::numeric_limits<double>::infinity();
  double z_high = -z_low, r_high = 0.0;
  for (const auto& [low, high, r] : extremes) {
    z_low = std::min(z_low, low);
    z_high = std::max(z_high, high);
    r_high = std::max(r_high, r);
  }
  // On the bed within the rounding of the heights.
  const double on_bed = z_low + 1e-12 * std::max({1.0, std::abs(z_low), z_high - z_low});
  out.size = Vec3(2.0 * r_high, 2.0 * r_high, z_high - z_low);

  // The steepest place of each piece off the bed, and the stretches beyond
  // the limit (each piece sampled, their ends bisected).
  const auto lean_off_bed = [&](const Piece& p, double u) {
    const Jet j = eval(p, u);
    return j.point.y() > on_bed ? lean(j) : -1.0;
  };
  const double limit = std::sin(options.max_overhang_deg * kPi / 180.0);
  struct PieceLean {
    double sine = 0.0, u = 0.0;
    std::vector<Span> spans;
  };
  std::vector<PieceLean> leans(pieces.size());
  each_piece([&](std::size_t i) {
    const Piece& p = pieces[i];
    PieceLean& l = leans[i];
    std::tie(l.sine, l.u) = maximise([&](double v) { return lean_off_bed(p, v); });
    const auto beyond = [&](double u) { return lean_off_bed(p, u) > limit; };
    bool was = beyond(0.0);
    double start = 0.0;
    for (int k = 1; k <= kSamples; ++k) {
      const double a = static_cast<double>(k - 1) / kSamples, b = static_cast<double>(k) / kSamples;
      const bool is = beyond(b);
      if (is != was) {
        const double c = crossing(beyond, a, b);
        if (is) {
          start = c;
        } else {
          l.spans.push_back({i, start, c});
        }
      }
      was = is;
    }
    if (was) l.spans.push_back({i, start, 1.0});
  });
  std::optional<Overhang> steepest[3];
  std::vector<Span> spans;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const Piece& p = pieces[i];
    std::optional<Overhang>& s = steepest[static_cast<int>(p.face)];
    if (!s) s = Overhang{};
    const double angle = degrees(leans[i].sine);
    if (angle > s->angle_deg) *s = Overhang{angle, eval(p, leans[i].u).point};
    spans.insert(spans.end(), leans[i].spans.begin(), leans[i].spans.end());
  }
  out.outer = steepest[0].value_or(Overhang{});
  out.rim = steepest[1] && steepest[1]->angle_deg > 0.0 ? steepest[1] : std::nullopt;
  out.inner = steepest[2];

  // Spans that run on from one piece into the next (or round a closed profile) are one run.
  std::vector<std::vector<Span>> runs;
  for (const Span& s : spans) {
    const bool joins = !runs.empty() && runs.back().back().piece + 1 == s.piece &&
                       runs.back().back().u1 == 1.0 && s.u0 == 0.0 &&
                       pieces[s.piece].face == pieces[s.piece - 1].face;
    if (joins) {
      runs.back().push_back(s);
    } else {
      runs.push_back({s});
    }
  }
  if (runs.size() > 1 && profile.closed() && !section.inner_wall && runs.front().front().piece == 0 &&
      runs.front().front().u0 == 0.0 && runs.back().back().piece + 1 == pieces.size() &&
      runs.back().back().u1 == 1.0) {
    runs.back().insert(runs.back().end(), runs.front().begin(), runs.front().end());
    runs.erase(runs.begin());
  }
  for (const std::vector<Span>& run : runs) {
    OverhangRun r;
    r.face = pieces[run.front().piece].face;
    r.from = eval(pieces[run.front().piece], run.front().u0).point;
    r.to = eval(pieces[run.back().piece], run.back().u1).point;
    r.width = r.to.x() - r.from.x();
    for (const Span& s : run) {
      const Piece& p = pieces[s.piece];
      for (int k = 0; k <= kDrawSamples; ++k) {
        const Vec2 q = eval(p, s.u0 + (s.u1 - s.u0) * k / kDrawSamples).point;
        if (r.points.empty() || r.points.back() != q) r.points.push_back(q);
      }
      const auto [sine, u] = maximise([&](double v) { return lean_off_bed(p, s.u0 + (s.u1 - s.u0) * v); });
      r.max_angle_deg = std::max(r.max_angle_deg, degrees(sine));
    }
    out.runs.push_back(std::move(r));
  }
  for (std::size_t i = 0; i < out.runs.size(); ++i) {
    if (!out.widest_ledge || out.runs[i].width > out.runs[*out.widest_ledge].width) out.widest_ledge = i;
  }

  if (!std::isnan(section.min_clearance)) {
    out.min_wall = section.min_clearance;
    out.min_wall_where = section.clearance_where;
  }

  // The findings against the limits.
  const std::string& u = options.units;
  const double extent = out.size.maxCoeff();
  if (!out.runs.empty()) {
    std::size_t steepest_run = 0;
    for (std::size_t i = 1; i < out.runs.size(); ++i) {
      if (out.runs[i].max_angle_deg > out.runs[steepest_run].max_angle_deg) steepest_run = i;
    }
    const OverhangRun& s = out.runs[steepest_run];
    const OverhangRun& w = out.runs[*out.widest_ledge];
    const Overhang& at_most = s.face == PrintFace::Outer   ? out.outer
                              : s.face == PrintFace::Inner ? *out.inner
                                                           : *out.rim;
    out.findings.push_back(
        {"print.max_overhang_deg",
         fmt::format("the {} overhangs {:.4g} degrees from vertical at {}, beyond max_overhang_deg {:g} "
                     "({} unsupported {}; the widest ledge {:.4g} {} on the {}, from {} to {})",
                     to_string(s.face), at_most.angle_deg, at(at_most.at, extent), options.max_overhang_deg,
                     out.runs.size(), out.runs.size() == 1 ? "stretch" : "stretches", w.width, u,
                     to_string(w.face), at(w.from, extent), at(w.to, extent))});
  }
  if (!std::isnan(out.min_wall) && out.min_wall < options.min_wall) {
    out.findings.push_back(
        {"print.min_wall", fmt::format("the wall is {:.4g} {} thick (normal to the wall) "
                                       "between the {}, thinner than min_wall {:g} {}",
                                       out.min_wall, u, out.min_wall_where, options.min_wall, u)});
  }
  if (options.bed) {
    const Vec3& bed = *options.bed;
    const double diameter = out.size.x();
    out.fits_bed = diameter <= std::min(bed.x(), bed.y()) && out.size.z() <= bed.z();
    if (!*out.fits_bed) {
      out.findings.push_back(
          {"print.bed", fmt::format("the vessel ({:.6g} {} across, {:.6g} {} tall) does not fit the bed "
                                    "{:g} x {:g} x {:g} {}",
                                    diameter, u, out.size.z(), u, bed.x(), bed.y(), bed.z(), u)});
    }
  }
  return out;
}

}  // namespace fabmesh
