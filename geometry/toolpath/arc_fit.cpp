#include "geometry/toolpath/arc_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace fabmesh {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

Vec2 left_normal(const Vec2& t) { return Vec2(-t.y(), t.x()); }
double angle_of(const Vec2& v) { return std::atan2(v.y(), v.x()); }

// How far round an arc (in its own sense, radians from its start) the point
// of its circle at `angle` lies, in [0, 2 pi).
double turn_to(const PathPiece& p, double angle) {
  const double a0 = angle_of(p.from - p.center);
  double d = std::fmod(p.sweep >= 0.0 ? angle - a0 : a0 - angle, kTwoPi);
  if (d < 0.0) d += kTwoPi;
  return d;
}

// Whether the point of an arc's circle at `angle` is on the arc (ends included).
bool on_arc(const PathPiece& p, double angle) {
  const double d = turn_to(p, angle);
  return d <= std::abs(p.sweep) || d >= kTwoPi - 1e-15;
}

// Whether it lies strictly between the arc's ends.
bool inside_arc(const PathPiece& p, double angle) {
  const double d = turn_to(p, angle);
  return d > 1e-12 && d < std::abs(p.sweep) - 1e-12;
}

double segment_distance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 == 0.0 ? 0.0 : std::clamp((q - a).dot(d) / len2, 0.0, 1.0);
  return (a + t * d - q).norm();
}

// One piece of the replaced chain measured against a fitted piece: how far
// it advances along the fit (radians about an arc's centre, in the arc's
// sense; length along a line), and its largest distance from the fit's
// circle or line. nullopt: it does not advance monotonically.
struct Step {
  double advance = 0.0;
  double deviation = 0.0;
};

std::optional<Step> about_centre(const Vec2& c, double radius, double sense, const PathPiece& p) {
  const Vec2 a = p.from - c, b = p.to - c;
  if (a.squaredNorm() == 0.0 || b.squaredNorm() == 0.0) return std::nullopt;
  const double cr = cross2(a, b), dt = a.dot(b);
  if (cr == 0.0 && dt < 0.0) return std::nullopt;  // through the centre
  const double advance = std::atan2(cr, dt) * sense;
  if (advance < 0.0) return std::nullopt;
  double far = std::max(a.norm(), b.norm());
  double near = std::min(a.norm(), b.norm());
  if (p.kind == PieceKind::Line) {
    near = segment_distance(c, p.from, p.to);  // |p - c| is convex along a line
    return Step{advance, std::max(far - radius, radius - near)};
  }
  // An arc about q of radius rho, with c outside its circle (so it subtends less than a half
  // turn from c): its angle about c is monotone unless it holds a point where a line from c
  // touches the circle.
  const Vec2 w = p.center - c;
  const double dist = w.norm(), rho = piece_radius(p);
  if (!(dist > rho * (1.0 + 1e-9))) return std::nullopt;
  const double base = angle_of(-w), off = std::acos(rho / dist);
  if (inside_arc(p, base + off) || inside_arc(p, base - off)) return std::nullopt;
  if (on_arc(p, angle_of(w))) far = std::max(far, dist + rho);  // the circle's point farthest from c
  if (on_arc(p, angle_of(-w))) near = std::min(near, dist - rho);
  return Step{advance, std::max(far - radius, radius - near)};
}

std::optional<Step> along_line(const Vec2& s, const Vec2& d, const PathPiece& p) {
  const double advance = (p.to - p.from).dot(d);
  if (advance < 0.0) return std::nullopt;
  auto off = [&](const Vec2& q) { return std::abs(cross2(d, q - s)); };
  double dev = std::max(off(p.from), off(p.to));  // linear along a line
  if (p.kind == PieceKind::Arc) {
    // Monotone unless the arc's tangent turns across d's normal; extreme where it is parallel to d.
    if (inside_arc(p, angle_of(d)) || inside_arc(p, angle_of(-d))) return std::nullopt;
    const Vec2 n = left_normal(d);
    const double rho = piece_radius(p);
    for (const Vec2& u : {n, Vec2(-n)}) {
      if (on_arc(p, angle_of(u))) dev = std::max(dev, off(p.center + rho * u));
    }
  }
  return Step{advance, dev};
}

// The arc from p with unit tangent t through q (a line when straight);
// nullopt for half a turn or more, or a radius over max_radius.
std::optional<PathPiece> tangent_piece(const Vec2& p, const Vec2& t, const Vec2& q, std::size_t segment,
                                       double max_radius) {
  const Vec2 w = q - p;
  const double len2 = w.squaredNorm();
  if (len2 == 0.0) return std::nullopt;
  const double cr = cross2(t, w), dt = t.dot(w);
  if (!(dt > 0.0)) return std::nullopt;
  if (std::abs(cr) <= 1e-13 * std::sqrt(len2)) return line_piece(p, q, PieceRole::Offset, segment);
  const double radius = len2 / (2.0 * std::abs(cr));
  if (radius > max_radius) return std::nullopt;
  PathPiece arc = arc_piece(p + left_normal(t) * (len2 / (2.0 * cr)), p, 2.0 * std::atan2(cr, dt),
                            PieceRole::Offset, segment);
  arc.to = q;
  return arc;
}

// The biarc from p0 (tangent t0) to p1 (tangent t1) whose two arcs have
// equal tangent lengths d: control points p0 + d t0 and p1 - d t1, joined
// at their midpoint.
std::optional<std::vector<PathPiece>> biarc(const Vec2& p0, const Vec2& t0, const Vec2& p1, const Vec2& t1,
                                            std::size_t segment, double max_radius) {
  const Vec2 v = p1 - p0;
  const double len2 = v.squaredNorm();
  if (len2 == 0.0) return std::nullopt;
  const double len = std::sqrt(len2);
  if (std::abs(cross2(t0, v)) <= 1e-13 * len && std::abs(cross2(t1, v)) <= 1e-13 * len && t0.dot(v) > 0.0 &&
      t1.dot(v) > 0.0) {
    return std::vector<PathPiece>{line_piece(p0, p1, PieceRole::Offset, segment)};
  }
  const double denom = 2.0 * (1.0 - t0.dot(t1));
  double d = 0.0;
  if (denom < 1e-12) {
    const double vt = v.dot(t1);
    if (!(vt > 0.0)) return std::nullopt;
    d = len2 / (4.0 * vt);
  } else {
    const double vt = v.dot(t0 + t1);
    d = (-vt + std::sqrt(vt * vt + denom * len2)) / denom;
  }
  if (!(d > 0.0) || !std::isfinite(d)) return std::nullopt;
  const Vec2 q1 = p0 + d * t0, q2 = p1 - d * t1;
  const Vec2 m = 0.5 * (q1 + q2);
  const Vec2 tm = q2 - q1;
  if (tm.squaredNorm() == 0.0 || (m - p0).norm() <= 1e-9 * len || (p1 - m).norm() <= 1e-9 * len)
    return std::nullopt;
  const auto a = tangent_piece(p0, t0, m, segment, max_radius);
  const auto b = tangent_piece(m, tm.normalized(), p1, segment, max_radius);
  if (!a || !b) return std::nullopt;
  if (a->kind == PieceKind::Line && b->kind == PieceKind::Line)
    return std::vector<PathPiece>{line_piece(p0, p1, PieceRole::Offset, segment)};
  return std::vector<PathPiece>{*a, *b};
}

// The chain split where it first crosses the line through m normal to tm
// (from behind to ahead); nullopt when it does not.
std::optional<std::pair<std::vector<PathPiece>, std::vector<PathPiece>>> split_at_normal(
    const std::vector<PathPiece>& chain, const Vec2& m, const Vec2& tm) {
  auto f = [&](const Vec2& p) { return (p - m).dot(tm); };
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const PathPiece& p = chain[k];
    const double len = piece_length(p);
    if (len == 0.0) continue;
    const double fa = f(p.from), fb = f(p.to);
    std::optional<double> at;
    if (p.kind == PieceKind::Line) {
      if (fa <= 0.0 && fb > 0.0) at = len * (-fa) / (fb - fa);
    } else if (fa <= 0.0) {
      // centre + rho u(phi) on the normal: u . tm = (m - centre) . tm / rho
      const double rho = piece_radius(p);
      const double k_cos = (m - p.center).dot(tm) / rho;
      if (std::abs(k_cos) <= 1.0) {
        const double base = angle_of(tm), off = std::acos(k_cos);
        for (double phi : {base + off, base - off}) {
          if (!on_arc(p, phi)) continue;
          const double u = std::min(turn_to(p, phi), std::abs(p.sweep)) * rho;
          if (!at || u < *at) at = u;
        }
      }
    }
    if (!at) continue;
    std::vector<PathPiece> first(chain.begin(), chain.begin() + static_cast<std::ptrdiff_t>(k));
    std::vector<PathPiece> second;
    const double eps = 1e-12 * (1.0 + len);
    if (*at <= eps) {
      second.push_back(p);
    } else if (*at >= len - eps) {
      first.push_back(p);
    } else {
      auto [before, after] = split_piece(p, *at);
      first.push_back(before);
      second.push_back(after);
    }
    second.insert(second.end(), chain.begin() + static_cast<std::ptrdiff_t>(k) + 1, chain.end());
    return std::pair{std::move(first), std::move(second)};
  }
  return std::nullopt;
}

// The proven distance between fitted pieces (one, or a biarc's two) and the chain they replace.
double fit_deviation_of(const std::vector<PathPiece>& fit, const std::vector<PathPiece>& chain) {
  if (fit.size() == 1) return fit_deviation(fit[0], chain);
  const Vec2 m = fit[0].to;
  const auto halves = split_at_normal(chain, m, piece_tangent(fit[1], 0.0));
  if (!halves) return INFINITY;
  return std::max(fit_deviation(fit[0], halves->first), fit_deviation(fit[1], halves->second));
}

bool fittable(const PathPiece& p, const ArcFitOptions& o) {
  if (p.role == PieceRole::Offset) return p.kind == PieceKind::Line;
  return p.role == PieceRole::Corner && p.kind == PieceKind::Arc && std::abs(p.sweep) <= o.max_corner_turn;
}

// Pieces of a run, its lines cut in halves. Fitted pieces join where the
// run's pieces join, or at the middle of a line with the line's tangent: there
// the curve the line was taken from (a digitised curve, an offset curve) has
// the line's direction. A line of length L between turns a and b (radians,
// to the left, of one sign) is a chord of that curve standing about
// s = L min(a, b) / 8 from it at its middle (L a / 8 for points on a circle
// turning a at each); the closest circle runs s / 2 beyond the chord, so
// a joint may move that far off it along its normal (at most the tolerance),
// which halves the fit's distance from both the points and the chords.
struct Halves {
  std::vector<PathPiece> pieces;
  std::vector<std::size_t> origin;  ///< the run's piece each came from
  std::vector<std::size_t> joints;  ///< indices into pieces where a fit may start or end
  std::vector<Vec2> shift;          ///< per joint: how far off the path a fit may join there
};

Halves halve(const std::vector<PathPiece>& run, double tolerance) {
  Halves h;
  h.joints.push_back(0);
  h.shift.push_back(Vec2::Zero());
  std::vector<std::size_t> lines;
  for (std::size_t k = 0; k < run.size(); ++k) {
    if (run[k].kind == PieceKind::Line && piece_length(run[k]) > 0.0) lines.push_back(k);
  }
  auto turn = [&](std::size_t from, std::size_t to) {
    const Vec2 a = (run[from].to - run[from].from).normalized(), b = (run[to].to - run[to].from).normalized();
    return std::atan2(cross2(a, b), a.dot(b));
  };
  std::size_t li = 0;
  for (std::size_t k = 0; k < run.size(); ++k) {
    const PathPiece& p = run[k];
    const double len = piece_length(p);
    if (p.kind == PieceKind::Line && len > 0.0) {
      const double before = li > 0 ? turn(lines[li - 1], k) : 0.0;
      const double after = li + 1 < lines.size() ? turn(k, lines[li + 1]) : 0.0;
      ++li;
      // The lesser turn: a long line beside a curve's first point is straight, not a chord.
      const double least = before * after > 0.0 ? std::min(std::abs(before), std::abs(after)) : 0.0;
      const double sag = std::clamp((before > 0.0 ? 1.0 : -1.0) * len * least / 8.0, -tolerance, tolerance);
      const Vec2 d = (p.to - p.from) / len;
      auto [a, b] = split_piece(p, 0.5 * len);
      h.pieces.push_back(a);
      h.origin.push_back(k);
      h.joints.push_back(h.pieces.size());
      h.shift.push_back(0.5 * sag * Vec2(d.y(), -d.x()));  // to the right of a left turn
      h.pieces.push_back(b);
    } else {
      h.pieces.push_back(p);
    }
    h.origin.push_back(k);
    h.joints.push_back(h.pieces.size());  // the joint after the piece, on the path
    h.shift.push_back(Vec2::Zero());
  }
  h.shift.back() = Vec2::Zero();  // the run's ends stay on the path
  return h;
}

void fit_run(const std::vector<PathPiece>& run, const ArcFitOptions& o, ArcFitResult& out) {
  const Halves h = halve(run, o.tolerance);
  const std::size_t n = h.pieces.size(), q = h.joints.size() - 1;
  auto vertex = [&](std::size_t j, bool shifted) {
    const std::size_t i = h.joints[j];
    const Vec2 p = i < n ? h.pieces[i].from : h.pieces.back().to;
    return shifted ? Vec2(p + h.shift[j]) : p;
  };
  // The tangent at a joint: the path's where it runs on smoothly (the ends, a line's middle, a
  // line meeting the tool's arc), the mean of the two at a kink (a slight concave turn).
  auto tangent = [&](std::size_t j) {
    const std::size_t i = h.joints[j];
    Vec2 out_t = i < n ? piece_tangent(h.pieces[i], 0.0) : Vec2::Zero();
    Vec2 in_t = i > 0 ? piece_tangent(h.pieces[i - 1], piece_length(h.pieces[i - 1])) : Vec2::Zero();
    if (i == 0) return out_t;
    if (i == n) return in_t;
    const Vec2 mean = in_t + out_t;
    return mean.squaredNorm() > 0.0 ? Vec2(mean.normalized()) : out_t;
  };
  // The biarc from joint k to joint m (each on the path or moved off it) and its proven deviation.
  auto fit = [&](std::size_t k, bool sk, std::size_t m, bool sm, std::vector<PathPiece>* pieces) {
    const auto b = biarc(vertex(k, sk), tangent(k), vertex(m, sm), tangent(m), h.pieces[h.joints[k]].segment,
                         o.max_radius);
    if (!b) return std::numeric_limits<double>::infinity();
    const std::vector<PathPiece> chain(h.pieces.begin() + static_cast<std::ptrdiff_t>(h.joints[k]),
                                       h.pieces.begin() + static_cast<std::ptrdiff_t>(h.joints[m]));
    const double dev = fit_deviation_of(*b, chain);
    if (pieces) *pieces = *b;
    return dev;
  };
  // The farthest joint m > k for which fits(m) holds (doubling, then bisecting), among all
  // joints and among the lines' middles (in a curve the fits end well only there, so the
  // search over all joints alone stops early); k when none.
  std::vector<std::size_t> middles;
  for (std::size_t j = 1; j <= q; ++j) {
    if (j == q || (h.joints[j] > 0 && h.origin[h.joints[j] - 1] == h.origin[h.joints[j]]))
      middles.push_back(j);
  }
  auto reach_in = [&](std::size_t k, const std::vector<std::size_t>& ends, const auto& fits) {
    const std::size_t first =
        static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), k) - ends.begin());
    if (first == ends.size() || !fits(ends[first])) return k;
    std::size_t good = first, miss = ends.size();
    while (good + 1 < ends.size()) {
      const std::size_t probe = std::min(ends.size() - 1, first + 2 * (good - first) + 1);
      if (fits(ends[probe])) {
        good = probe;
      } else {
        miss = probe;
        break;
      }
    }
    while (miss - good > 1 && good + 1 < ends.size()) {
      const std::size_t mid = good + (miss - good) / 2;
      (fits(ends[mid]) ? good : miss) = mid;
    }
    return ends[good];
  };
  std::vector<std::size_t> all(q);
  for (std::size_t j = 0; j < q; ++j) all[j] = j + 1;
  auto reach = [&](std::size_t k, const auto& fits) {
    return std::max(reach_in(k, all, fits), reach_in(k, middles, fits));
  };
  // The path's own pieces from h.pieces[i0, i1), halves of one line joined again.
  auto keep = [&](std::size_t i0, std::size_t i1) {
    for (std::size_t i = i0; i < i1; ++i) {
      if (i + 1 < i1 && h.origin[i + 1] == h.origin[i]) {
        out.pieces.push_back(run[h.origin[i]]);
        ++i;
      } else {
        out.pieces.push_back(h.pieces[i]);
      }
    }
  };
  std::size_t k = 0, kept_from = 0;
  bool sk = false;  // the fit before ended off the path at joint k
  while (k < q) {
    const double tol = o.tolerance;
    // A fit may end off the path only where the next can leave from there and come back onto it.
    // Off the path only where that goes further than on it.
    const std::size_t on = reach(k, [&](std::size_t j) { return fit(k, sk, j, false, nullptr) <= tol; });
    std::size_t m = reach(k, [&](std::size_t j) { return fit(k, sk, j, j < q, nullptr) <= tol; });
    bool sm = m > on && m < q && h.shift[m].squaredNorm() > 0.0 && fit(m, true, m + 1, false, nullptr) <= tol;
    if (!sm) m = on;
    if (m == k) {  // nothing fits from here (never after a fit that ended off the path)
      ++k;
      sk = false;
      continue;
    }
    std::vector<PathPiece> pieces;
    const double dev = fit(k, sk, m, sm, &pieces);
    const std::size_t i0 = h.joints[k], i1 = h.joints[m];
    // Worth it with fewer pieces than the path's own over the span (the whole pieces it
    // touches), or where the fit before or after joins off the path.
    const std::size_t touched = h.origin[i1 - 1] - h.origin[i0] + 1;
    if (!sk && !sm && pieces.size() >= touched) {
      k = m;
      continue;
    }
    keep(kept_from, i0);
    for (const PathPiece& p : pieces) (p.kind == PieceKind::Arc ? out.arcs : out.lines) += 1;
    out.deviation = std::max(out.deviation, dev);
    out.pieces.insert(out.pieces.end(), pieces.begin(), pieces.end());
    kept_from = i1;
    k = m;
    sk = sm;
  }
  keep(kept_from, n);
}

}  // namespace

double fit_deviation(const PathPiece& fitted, const std::vector<PathPiece>& chain) {
  double advance = 0.0, dev = 0.0, expected = 0.0, scale = 0.0, per_advance = 1.0;
  std::optional<Step> step;
  for (const PathPiece& p : chain) {
    if (piece_length(p) == 0.0) continue;
    if (fitted.kind == PieceKind::Arc) {
      step = about_centre(fitted.center, piece_radius(fitted), fitted.sweep >= 0.0 ? 1.0 : -1.0, p);
    } else {
      const Vec2 d = fitted.to - fitted.from;
      if (d.squaredNorm() == 0.0) return INFINITY;
      step = along_line(fitted.from, d.normalized(), p);
    }
    if (!step) return INFINITY;
    advance += step->advance;
    dev = std::max(dev, step->deviation);
  }
  if (fitted.kind == PieceKind::Arc) {
    if (std::abs(fitted.sweep) > M_PI) return INFINITY;
    expected = std::abs(fitted.sweep);
    per_advance = piece_radius(fitted);  // an angle's mismatch at the ends, as a distance
    scale = fitted.center.norm() + per_advance;
  } else {
    expected = piece_length(fitted);
    scale = fitted.from.norm() + expected;
  }
  const double mismatch = std::abs(advance - expected) * per_advance;
  const double rounding = 1e-12 * (1.0 + scale);
  if (mismatch > 1e-6 * (1.0 + scale)) return INFINITY;  // not the same span: a wrong winding or split
  // Ends matched up to `mismatch`: the correspondence's ends are that much further apart.
  return dev + mismatch + rounding;
}

ArcFitResult fit_arcs(const std::vector<PathPiece>& path, const ArcFitOptions& o) {
  ArcFitResult out;
  std::size_t i = 0;
  while (i < path.size()) {
    if (!fittable(path[i], o)) {
      out.pieces.push_back(path[i++]);
      continue;
    }
    std::size_t j = i;
    while (j < path.size() && fittable(path[j], o)) ++j;
    const std::size_t written = out.pieces.size(), fitted = out.arcs + out.lines;
    fit_run(std::vector<PathPiece>(path.begin() + static_cast<std::ptrdiff_t>(i),
                                   path.begin() + static_cast<std::ptrdiff_t>(j)),
            o, out);
    // The run's pieces less those written as they were (a line cut by a fit's end counts as kept).
    const std::size_t made = out.pieces.size() - written, new_fits = out.arcs + out.lines - fitted;
    out.replaced += (j - i) - (made - new_fits);
    i = j;
  }
  for (std::size_t k = 1; k < out.pieces.size(); ++k) out.pieces[k].from = out.pieces[k - 1].to;
  return out;
}

}  // namespace fabmesh
