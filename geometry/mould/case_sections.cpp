#include "geometry/mould/case_sections.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/disjoint_sets.h"
#include "geometry/core/errors.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/volume.h"
#include "geometry/mould/case_pins.h"
#include "geometry/repair/exact_booleans.h"
#include "geometry/validation/validate.h"

namespace fabmesh {
namespace {

// The fewest equal cells of `length` that each fit `bed` with a pin of
// `pin` on one end (when cut); 0 when none do.
int cells_along(double length, double bed, double pin) {
  if (length <= bed) return 1;
  const double room = bed * (1.0 - 1e-9) - pin;
  if (!(room > 0.0)) return 0;
  auto n = static_cast<int>(std::ceil(length / room));
  while (length / n > room) ++n;
  return n;
}

// The point of [from, to] farthest from every value of `levels` (sorted).
double farthest_from(const std::vector<double>& levels, double from, double to) {
  const auto distance = [&](double x) {
    const auto above = std::lower_bound(levels.begin(), levels.end(), x);
    double d = std::numeric_limits<double>::infinity();
    if (above != levels.end()) d = *above - x;
    if (above != levels.begin()) d = std::min(d, x - *(above - 1));
    return d;
  };
  double best = 0.5 * (from + to), best_distance = distance(best);
  std::vector<double> candidates{from, to};
  for (auto it = std::lower_bound(levels.begin(), levels.end(), from); it != levels.end() && *it <= to;
       ++it) {
    if (it + 1 != levels.end()) candidates.push_back(std::clamp(0.5 * (*it + *(it + 1)), from, to));
    if (it != levels.begin()) candidates.push_back(std::clamp(0.5 * (*(it - 1) + *it), from, to));
  }
  for (double x : candidates) {
    const double d = distance(x);
    if (d > best_distance) {
      best = x;
      best_distance = d;
    }
  }
  return best;
}

constexpr int kMostSections = 64;

// A triangle of the piece clipped to the slab from <= p[a] <= to and seen
// along a: a convex polygon in the plane's coordinates (b, c) = (a + 1, a + 2).
using Polygon = std::vector<Vec2>;

Vec2 in_plane(const Vec3& p, int a) { return {p[(a + 1) % 3], p[(a + 2) % 3]}; }

// `poly` (points of one plane) less what lies beyond the plane p[a] = at on
// the side `keep_above` does not keep.
std::vector<Vec3> clipped(const std::vector<Vec3>& poly, int a, double at, bool keep_above) {
  std::vector<Vec3> out;
  const auto kept = [&](const Vec3& p) { return keep_above ? p[a] >= at : p[a] <= at; };
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec3& p = poly[i];
    const Vec3& q = poly[(i + 1) % poly.size()];
    if (kept(p)) out.push_back(p);
    if (kept(p) != kept(q)) out.push_back(p + (at - p[a]) / (q[a] - p[a]) * (q - p));
  }
  return out;
}

std::vector<Polygon> seen_along(const TriangleSoup& s, int a, double from, double to) {
  std::vector<Polygon> out;
  for (const auto& t : s.triangles) {
    const Vec3 &p = s.vertices[t[0]], &q = s.vertices[t[1]], &r = s.vertices[t[2]];
    if (std::max({p[a], q[a], r[a]}) < from || std::min({p[a], q[a], r[a]}) > to) continue;
    std::vector<Vec3> poly = clipped(clipped({p, q, r}, a, from, true), a, to, false);
    if (poly.empty()) continue;
    Polygon seen;
    for (const Vec3& v : poly) seen.push_back(in_plane(v, a));
    out.push_back(std::move(seen));
  }
  return out;
}

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// Whether p is farther than `r` from the convex polygon `poly` (seen along
// a: a point, a segment or a polygon of either orientation).
bool clear_of(const Polygon& poly, const Vec2& p, double r) {
  double near = std::numeric_limits<double>::infinity();
  int positive = 0, negative = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2& u = poly[i];
    const Vec2& v = poly[(i + 1) % poly.size()];
    near = std::min(near, segment_distance(p, u, v));
    const double cross = (v - u).x() * (p - u).y() - (v - u).y() * (p - u).x();
    positive += cross > 0.0 ? 1 : 0;
    negative += cross < 0.0 ? 1 : 0;
  }
  const bool inside = poly.size() >= 3 && (positive == 0 || negative == 0);
  return !inside && near > r;
}

// The piece's section by the plane p[a] = at, as segments in (b, c): each
// triangle crossing it (a corner on the plane counted above it) gives one,
// each crossing point computed from its edge's lower-numbered end, so that
// the segments close into loops on shared points.
struct Slice {
  std::vector<std::pair<Vec2, Vec2>> segments;
  std::vector<std::size_t> loop;    // each segment's loop
  std::vector<double> loop_extent;  // each loop's bounding box area (of nested loops, the inner is smaller)
};

Slice slice(const TriangleSoup& s, int a, double at) {
  Slice out;
  std::map<std::pair<double, double>, std::uint32_t> ids;
  std::vector<std::array<std::uint32_t, 2>> ends;
  const auto id_of = [&](const Vec2& p) {
    return ids.emplace(std::make_pair(p.x(), p.y()), static_cast<std::uint32_t>(ids.size())).first->second;
  };
  for (const auto& t : s.triangles) {
    std::vector<Vec2> crossings;
    for (int e = 0; e < 3; ++e) {
      std::uint32_t i = t[e], j = t[(e + 1) % 3];
      if (j < i) std::swap(i, j);
      const Vec3& p = s.vertices[i];
      const Vec3& q = s.vertices[j];
      if ((p[a] >= at) != (q[a] >= at)) {
        crossings.push_back(in_plane(p + (at - p[a]) / (q[a] - p[a]) * (q - p), a));
      }
    }
    if (crossings.size() != 2) continue;
    out.segments.emplace_back(crossings[0], crossings[1]);
    ends.push_back({id_of(crossings[0]), id_of(crossings[1])});
  }
  DisjointSets<std::uint32_t> sets(ids.size());
  for (const auto& e : ends) sets.unite(e[0], e[1]);
  std::map<std::uint32_t, std::size_t> dense;
  std::vector<std::array<double, 4>> boxes;  // lo b, lo c, hi b, hi c
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < ends.size(); ++n) {
    const auto [it, fresh] = dense.emplace(sets.find(ends[n][0]), dense.size());
    if (fresh) boxes.push_back({inf, inf, -inf, -inf});
    out.loop.push_back(it->second);
    std::array<double, 4>& box = boxes[it->second];
    for (const Vec2& p : {out.segments[n].first, out.segments[n].second}) {
      box = {std::min(box[0], p.x()), std::min(box[1], p.y()), std::max(box[2], p.x()),
             std::max(box[3], p.y())};
    }
  }
  for (const auto& box : boxes) out.loop_extent.push_back((box[2] - box[0]) * (box[3] - box[1]));
  return out;
}

// The material region of the section that p lies in: the innermost of the
// loops around it (the region's outer loop); none when p is outside the
// section (even-odd, a ray along +b).
std::optional<std::size_t> region_of(const Slice& section, const Vec2& p) {
  std::vector<bool> around(section.loop_extent.size(), false);
  for (std::size_t n = 0; n < section.segments.size(); ++n) {
    const auto& [u, v] = section.segments[n];
    if ((u.y() > p.y()) == (v.y() > p.y())) continue;
    const double x = u.x() + (p.y() - u.y()) / (v.y() - u.y()) * (v.x() - u.x());
    if (x > p.x()) around[section.loop[n]] = !around[section.loop[n]];
  }
  std::optional<std::size_t> innermost;
  std::size_t count = 0;
  for (std::size_t l = 0; l < around.size(); ++l) {
    if (!around[l]) continue;
    ++count;
    if (!innermost || section.loop_extent[l] < section.loop_extent[*innermost]) innermost = l;
  }
  if (count % 2 == 0) return std::nullopt;
  return innermost;
}

// Whether the point p lies inside the closed surface `s` (ray parity along
// a direction no face of a case runs along).
bool encloses(const TriangleSoup& s, const Vec3& p) {
  const Vec3 d = Vec3(0.5772156649, 0.6180339887, 0.5317515).normalized();
  bool in = false;
  for (const auto& t : s.triangles) {
    const Vec3& v0 = s.vertices[t[0]];
    const Vec3 e1 = s.vertices[t[1]] - v0, e2 = s.vertices[t[2]] - v0, q = d.cross(e2);
    const double det = e1.dot(q);
    if (det == 0.0) continue;
    const Vec3 r = p - v0;
    const double u = r.dot(q) / det;
    if (u < 0.0 || u > 1.0) continue;
    const Vec3 w = r.cross(e1);
    const double v = d.dot(w) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    if (e2.dot(w) / det > 0.0) in = !in;
  }
  return in;
}

// `s` in its connected solids (triangles sharing a vertex), each with its
// own vertices, in the order of their first triangles.
std::vector<TriangleSoup> solids_of(const TriangleSoup& s) {
  DisjointSets<std::uint32_t> sets(s.vertices.size());
  for (const auto& t : s.triangles) {
    sets.unite(t[0], t[1]);
    sets.unite(t[0], t[2]);
  }
  std::map<std::uint32_t, std::size_t> which;
  std::vector<TriangleSoup> out;
  std::vector<std::map<std::uint32_t, std::uint32_t>> index;
  for (const auto& t : s.triangles) {
    const auto [it, fresh] = which.emplace(sets.find(t[0]), out.size());
    if (fresh) {
      out.emplace_back();
      index.emplace_back();
    }
    TriangleSoup& solid = out[it->second];
    std::array<std::uint32_t, 3> moved{};
    for (int e = 0; e < 3; ++e) {
      const auto [v, added] =
          index[it->second].emplace(t[e], static_cast<std::uint32_t>(solid.vertices.size()));
      if (added) solid.vertices.push_back(s.vertices[t[e]]);
      moved[e] = v->second;
    }
    solid.triangles.push_back(moved);
  }
  return out;
}

// Whether the section's loops reach into the rectangle lo..hi.
bool reaches(const Slice& section, const Vec2& lo, const Vec2& hi) {
  return std::any_of(section.segments.begin(), section.segments.end(), [&](const auto& s) {
    const Vec2 a = s.first.cwiseMin(s.second), b = s.first.cwiseMax(s.second);
    return (a.array() <= hi.array()).all() && (b.array() >= lo.array()).all();
  });
}

// The smallest height of a triangle of `s` over its longest side: how thin
// its thinnest sliver is.
double thinnest(const TriangleSoup& s) {
  double least = std::numeric_limits<double>::infinity();
  for (const auto& t : s.triangles) {
    const Vec3 &a = s.vertices[t[0]], &b = s.vertices[t[1]], &c = s.vertices[t[2]];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (longest > 0.0) least = std::min(least, (b - a).cross(c - a).norm() / longest);
  }
  return least;
}

std::string size_text(const Vec3& s) { return fmt::format("{:.6g} x {:.6g} x {:.6g}", s.x(), s.y(), s.z()); }

// The piece cut into the cells between the planes `at` (each axis: the
// box's ends and the cuts), as cut_case_piece promises, `out` holding the
// cells' counts.
SectionedPiece cut_at(const TriangleSoup& printed, const std::string& name, const Vec3& bed,
                      const CaseOptions& options, SectionedPiece out,
                      const std::array<std::vector<double>, 3>& at) {
  const BoundingBox box = bounding_box(printed.vertices);
  const Vec3 size = box.size();
  const CasePin pin = case_pin(options);
  const double margin = case_pin_margin(options);
  const double w = options.wall;
  const auto cells_on = [&](int i) { return static_cast<std::size_t>(out.counts[i]); };
  const auto index = [&](const std::array<int, 3>& c) {
    return (static_cast<std::size_t>(c[2]) * cells_on(1) + static_cast<std::size_t>(c[1])) * cells_on(0) +
           static_cast<std::size_t>(c[0]);
  };
  const std::size_t cell_count = cells_on(0) * cells_on(1) * cells_on(2);
  std::vector<CaseSection> cells(cell_count);
  std::vector<TriangleSoup> solids(cell_count);
  for (int z = 0; z < out.counts[2]; ++z) {
    for (int y = 0; y < out.counts[1]; ++y) {
      for (int x = 0; x < out.counts[0]; ++x) {
        const std::array<int, 3> c{x, y, z};
        CaseSection& s = cells[index(c)];
        s.cell = c;
        std::array<std::array<double, 2>, 3> range{};
        for (int i = 0; i < 3; ++i) {
          s.lo[i] = at[i][c[i]];
          s.hi[i] = at[i][c[i] + 1];
          // Past the piece on its outer sides, so that only the cuts cut.
          range[i] = {c[i] == 0 ? s.lo[i] - w : s.lo[i], c[i] + 1 == out.counts[i] ? s.hi[i] + w : s.hi[i]};
        }
        solids[index(c)] =
            block_of(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), range[0], range[1], range[2]);
      }
    }
  }

  // The joints' pins, each placed with a point inside its foot and one in
  // the material beside its hole (to find the solids they belong to).
  struct Placed {
    std::size_t lower, upper;
    Vec3 in_foot, beside_hole;
  };
  std::vector<Placed> placed;
  std::vector<std::vector<TriangleSoup>> added(cell_count), removed(cell_count);
  double extra = 0.0;  // what the pins stand out, less the holes
  const double keep = pin.hole_radius + pin.hole_depth + 2.0 * margin;
  const double clear = pin.hole_radius + margin;
  const double step = w / 8.0;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int k = 1; k < out.counts[a]; ++k) {
      const double h = at[a][k];
      const std::vector<Polygon> near =
          seen_along(printed, a, h - pin.buried - margin, h + pin.hole_depth + margin);
      const auto section = slice(printed, a, h);
      for (int ic = 0; ic < out.counts[c]; ++ic) {
        for (int ib = 0; ib < out.counts[b]; ++ib) {
          const Vec2 lo(at[b][ib], at[c][ic]), hi(at[b][ib + 1], at[c][ic + 1]);
          if (!reaches(section, lo, hi)) continue;
          // Where a pin may stand: keep off the other cuts (their pins).
          const Vec2 from(ib > 0 ? lo.x() + keep : lo.x(), ic > 0 ? lo.y() + keep : lo.y());
          const Vec2 to(ib + 1 < out.counts[b] ? hi.x() - keep : hi.x(),
                        ic + 1 < out.counts[c] ? hi.y() - keep : hi.y());
          // Candidates by the region of the section they lie in.
          std::map<std::size_t, std::vector<Vec2>> found;
          const auto try_at = [&](const Vec2& p) {
            if (!(p.array() >= from.array()).all() || !(p.array() <= to.array()).all()) return;
            for (const Polygon& poly : near) {
              if (!clear_of(poly, p, clear)) return;
            }
            if (const std::optional<std::size_t> region = region_of(section, p)) found[*region].push_back(p);
          };
          for (int line = 0; line < 4; ++line) {
            // Half a wall inside the piece's box: along c at fixed b, then along b at fixed c.
            const int fixed = line < 2 ? 0 : 1;
            const int axis = fixed == 0 ? b : c;
            const double value = line % 2 == 0 ? box.lo[axis] + w / 2.0 : box.hi[axis] - w / 2.0;
            const double start = fixed == 0 ? from.y() : from.x(), end = fixed == 0 ? to.y() : to.x();
            const int steps = std::max(0, static_cast<int>(std::floor((end - start) / step)));
            for (int m = 0; m <= steps; ++m) {
              const double t = start + (end - start) * (steps == 0 ? 0.5 : static_cast<double>(m) / steps);
              try_at(fixed == 0 ? Vec2(value, t) : Vec2(t, value));
            }
          }
          // And half a wall inside every face the cut crosses (a wall's
          // middle, wherever the piece's walls run).
          for (const auto& [u, v] : section.segments) {
            const double length = (v - u).norm();
            if (!(length > 0.0)) continue;
            const Vec2 along = (v - u) / length, across(-along.y(), along.x());
            const auto count = static_cast<int>(std::floor(length / step));
            for (int m = 0; m <= count; ++m) {
              const Vec2 q = u + (count == 0 ? 0.5 * length : length * m / count) * along;
              try_at(q + w / 2.0 * across);
              try_at(q - w / 2.0 * across);
            }
          }
          // Two pins in each region with room for them, as far apart as it allows.
          std::vector<Vec2> chosen;
          for (const auto& [region, points] : found) {
            if (points.size() < 2) continue;
            const auto [p0, p1] = farthest_pair(points);
            chosen.push_back(points[p0]);
            chosen.push_back(points[p1]);
          }
          if (chosen.empty()) {
            throw GeometryError(
                "print.bed", fmt::format("{} ({} standing) has no room for two pins across its cut at {} "
                                         "= {:.6g} (between {:.6g} and {:.6g} along {}, {:.6g} and {:.6g} "
                                         "along {}), which its sections for the bed {} need",
                                         name, size_text(size), "xyz"[a], h, lo.x(), hi.x(), "xyz"[b], lo.y(),
                                         hi.y(), "xyz"[c], size_text(bed)));
          }
          std::array<int, 3> lower{}, upper{};
          lower[a] = k - 1;
          upper[a] = k;
          lower[b] = upper[b] = ib;
          lower[c] = upper[c] = ic;
          Vec3 e_a = Vec3::Zero(), e_b = Vec3::Zero(), e_c = Vec3::Zero();
          e_a[a] = e_b[b] = e_c[c] = 1.0;
          for (const Vec2& at_pin : chosen) {
            Vec3 base = Vec3::Zero();
            base[a] = h;
            base[b] = at_pin.x();
            base[c] = at_pin.y();
            const Vec3 foot = base - pin.buried * e_a;
            TriangleSoup stud =
                pin_prism(foot, e_b, e_c, e_a, pin.radius, pin.buried + pin.height, pin.sides);
            TriangleSoup hole =
                pin_prism(foot, e_b, e_c, e_a, pin.hole_radius, pin.buried + pin.hole_depth, pin.sides);
            extra += signed_volume(stud) * pin.height / (pin.buried + pin.height) -
                     signed_volume(hole) * pin.hole_depth / (pin.buried + pin.hole_depth);
            added[index(lower)].push_back(std::move(stud));
            removed[index(upper)].push_back(std::move(hole));
            placed.push_back({index(lower), index(upper), base - 0.5 * pin.buried * e_a,
                              base + 0.5 * pin.hole_depth * e_a + (pin.hole_radius + 0.5 * margin) * e_b});
            CasePin joint = pin;
            joint.base = base;
            joint.axis = e_a;
            out.pins.push_back(joint);
          }
        }
      }
    }
  }

  std::string why;
  std::optional<std::vector<TriangleSoup>> cut = cut_cells(printed, solids, added, removed, &why);
  if (!cut) {
    throw GeometryError("print.bed",
                        fmt::format("{} could not be cut into sections for the bed: {}", name, why));
  }
  out.volume = signed_volume(printed);
  double sum = 0.0;
  const double sliver = std::min(1e-6 * size.maxCoeff(), 0.5 * thinnest(printed));
  for (std::size_t i = 0; i < cell_count; ++i) {
    const CaseSection& cell = cells[i];
    const auto cell_text = [&] {
      return fmt::format("[{}, {}, {}]", cell.cell[0] + 1, cell.cell[1] + 1, cell.cell[2] + 1);
    };
    // A cell may hold several solids (a case's walls apart within it): each a section.
    for (TriangleSoup& solid : solids_of((*cut)[i])) {
      CaseSection s = cell;
      s.soup = std::move(solid);
      // Hair-short edges (two cuts' points, or a cut's and a pin's, a hair
      // apart) collapse, when the section stays valid without them: no
      // point moves, and the sections' volumes are checked below as before.
      if (thinnest(s.soup) < sliver) without_hairs(s.soup, options.tolerance);
      // A sliver the cut still left (a cut plane near an edge of the piece,
      // two planes crossing near one) would fold when the section is moved
      // or written in single precision: the cut is tried elsewhere.
      if (const double thin = thinnest(s.soup); thin < sliver) {
        throw GeometryError("print.bed",
                            fmt::format("{}: a section of its cell {} for the bed {} has a sliver "
                                        "{:.3g} thin",
                                        name, cell_text(), size_text(bed), thin));
      }
      if (!validate(s.soup).valid()) {
        throw GeometryError("print.bed", fmt::format("{}: a section of its cell {} for the bed {} is not a "
                                                     "valid solid once its points are rounded",
                                                     name, cell_text(), size_text(bed)));
      }
      for (const Placed& j : placed) {
        if (j.lower == i && encloses(s.soup, j.in_foot)) ++s.pins;
        if (j.upper == i && encloses(s.soup, j.beside_hole)) ++s.holes;
      }
      const double volume = signed_volume(s.soup);
      if (s.pins + s.holes < 2) {
        throw GeometryError(
            "print.bed", fmt::format("{}: a section of its cell {} for the bed {} (of volume {:.4g}) has {} "
                                     "pins or holes to register it, where it needs two",
                                     name, cell_text(), size_text(bed), volume, s.pins + s.holes));
      }
      sum += volume;
      out.sections.push_back(std::move(s));
    }
  }
  std::size_t pins = 0, holes = 0;
  for (const CaseSection& s : out.sections) {
    pins += s.pins;
    holes += s.holes;
  }
  if (pins != placed.size() || holes != placed.size()) {
    throw GeometryError("print.bed",
                        fmt::format("{}: its sections carry {} pins and {} holes of its {} joints' "
                                    "pins",
                                    name, pins, holes, placed.size()));
  }
  out.volume_error = std::abs(sum - (out.volume + extra));
  if (!(out.volume_error <= 1e-9 * std::abs(out.volume))) {
    throw GeometryError("print.bed",
                        fmt::format("{}: its sections hold {:.12g} where the piece, its pins and holes hold "
                                    "{:.12g}: a pin or a hole reaches out of the material",
                                    name, sum, out.volume + extra));
  }
  for (const CaseSection& s : out.sections) {
    const Vec3 section_size = bounding_box(s.soup.vertices).size();
    if (!fits_bed(section_size, bed)) {
      throw GeometryError(
          "print.bed",
          fmt::format("{}: its section [{}, {}, {}] ({}) does not fit the bed {}", name, s.cell[0] + 1,
                      s.cell[1] + 1, s.cell[2] + 1, size_text(section_size), size_text(bed)));
    }
  }
  return out;
}

}  // namespace

bool fits_bed(const Vec3& size, const Vec3& bed) {
  return size.z() <= bed.z() &&
         ((size.x() <= bed.x() && size.y() <= bed.y()) || (size.x() <= bed.y() && size.y() <= bed.x()));
}

SectionedPiece cut_case_piece(const TriangleSoup& printed, const std::string& name, const Vec3& bed,
                              const CaseOptions& options) {
  const BoundingBox box = bounding_box(printed.vertices);
  const Vec3 size = box.size();
  const CasePin pin = case_pin(options);

  // The fewest cells, the bed as it is or turned a quarter.
  SectionedPiece out;
  int best = 0;
  for (bool turned : {false, true}) {
    const Vec3 b(turned ? bed.y() : bed.x(), turned ? bed.x() : bed.y(), bed.z());
    std::array<int, 3> n{};
    for (int i = 0; i < 3; ++i) n[i] = cells_along(size[i], b[i], pin.height);
    const int total = n[0] * n[1] * n[2];
    if (total > 0 && (best == 0 || total < best)) {
      best = total;
      out.counts = n;
      out.turned = turned;
    }
  }
  if (best == 0) {
    // Bad input, not a piece to write whole: no section could hold a pin.
    double shortest = bed.minCoeff();
    for (int i = 0; i < 3; ++i) {
      if (cells_along(size[i], bed[i], pin.height) == 0) shortest = bed[i];
    }
    throw RangeError("print.bed", shortest,
                     fmt::format("{} ({} standing) cannot be cut into sections that fit the bed {}: the bed "
                                 "is no longer than a section's pin ({:.4g} tall: half of case.wall) along "
                                 "an axis the piece exceeds it; use a larger bed or a thinner case.wall",
                                 name, size_text(size), size_text(bed), pin.height),
                     ErrorLocation{"print.bed"});
  }
  if (best > kMostSections) {
    throw GeometryError("print.bed", fmt::format("{} ({} standing) would take {} sections to fit the bed {} "
                                                 "(at most {}): print it on a larger printer",
                                                 name, size_text(size), best, size_text(bed), kMostSections));
  }

  // The cells' bounds along each axis: the box's ends and the cuts, each
  // near its equal share, moved as far from the piece's vertices as the
  // bed's room allows (a plane through or near a vertex would leave slivers
  // that rounding can fold). Where a section falls apart, or a joint has no
  // room for its pins, the cuts are tried again elsewhere in that room.
  const Vec3 room(out.turned ? bed.y() : bed.x(), out.turned ? bed.x() : bed.y(), bed.z());
  std::array<std::vector<double>, 3> levels;
  for (int i = 0; i < 3; ++i) {
    for (const Vec3& v : printed.vertices) levels[i].push_back(v[i]);
    std::sort(levels[i].begin(), levels[i].end());
  }
  std::optional<GeometryError> first;
  for (double shift : {0.0, -0.75, 0.75, -0.375, 0.375, -0.5625, 0.5625, -0.1875, 0.1875}) {
    std::array<std::vector<double>, 3> at;
    for (int i = 0; i < 3; ++i) {
      at[i].push_back(box.lo[i]);
      const double share = size[i] / out.counts[i];
      const double slack = std::clamp(room[i] * (1.0 - 1e-9) - pin.height - share, 0.0, share / 2.0) / 2.0;
      // Near the share moved by `shift` of the room, within a quarter of it.
      for (int k = 1; k < out.counts[i]; ++k) {
        // (each axis moved a different share, so that no two cuts cross on a diagonal of the piece)
        const double centre = box.lo[i] + share * k + shift * (1.0 - 0.25 * i) * slack;
        at[i].push_back(farthest_from(levels[i], centre - slack / 4.0, centre + slack / 4.0));
      }
      at[i].push_back(box.hi[i]);
    }
    try {
      return cut_at(printed, name, bed, options, out, at);
    } catch (const GeometryError& e) {
      if (!first) first = e;
    }
  }
  throw *first;
}

}  // namespace fabmesh
