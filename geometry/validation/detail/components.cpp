// Components as shells: labels, signed volumes, and nesting by ray parity.
// A ray is a segment from a vertex of one component to a point outside the
// soup's bounding box; the faces it may meet come from a small bounding-volume
// hierarchy over the face boxes (median splits, a conservative slab test);
// each is classified with exact predicates, and a segment that meets any face
// other than transversally through its interior is abandoned for another
// direction.

#include "geometry/validation/detail/components.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mpzf.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "geometry/core/disjoint_sets.h"
#include "geometry/mesh/bounding_box.h"

namespace fabmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

bool index_degenerate(const std::array<std::uint32_t, 3>& t) {
  return t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
}

Point point(const Vec3& v) { return Point(v.x(), v.y(), v.z()); }

/// A box in double precision: lo > hi when empty.
struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void grow(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
};

/// A bounding-volume hierarchy over boxes (of faces, of components), for
/// segment queries.
class BoxTree {
 public:
  /// The hierarchy over the non-empty boxes of `boxes`, known by their index.
  explicit BoxTree(std::vector<Box> boxes) : boxes_(std::move(boxes)) {
    for (std::uint32_t i = 0; i < boxes_.size(); ++i) {
      if (boxes_[i].lo.x() <= boxes_[i].hi.x()) order_.push_back(i);
    }
    if (order_.empty()) return;
    nodes_.resize(1);
    build(0, 0, order_.size());
  }

  /// Calls visit(index) for every box the segment from p to q may meet:
  /// every box it meets, and perhaps a few within `margin`.
  template <class Visit>
  void query(const Vec3& p, const Vec3& q, double margin, Visit&& visit) const {
    if (nodes_.empty()) return;
    std::vector<std::size_t> stack{0};
    while (!stack.empty()) {
      const Node& node = nodes_[stack.back()];
      stack.pop_back();
      if (!segment_meets(p, q, node.box, margin)) continue;
      if (node.count > 0) {
        for (std::size_t i = node.first; i < node.first + node.count; ++i) {
          if (segment_meets(p, q, boxes_[order_[i]], margin)) visit(order_[i]);
        }
      } else {
        stack.push_back(node.first);
        stack.push_back(node.first + 1);
      }
    }
  }

 private:
  static constexpr std::size_t kLeafSize = 4;

  /// A leaf (count > 0: order_[first, first + count)) or an inner node
  /// (count == 0: children first and first + 1).
  struct Node {
    Box box;
    std::size_t first = 0;
    std::size_t count = 0;
  };

  /// Builds the subtree over order_[begin, end) into nodes_[index].
  void build(std::size_t index, std::size_t begin, std::size_t end) {
    Box box;
    Box centres;
    for (std::size_t i = begin; i < end; ++i) {
      const Box& b = boxes_[order_[i]];
      box.grow(b);
      const Vec3 c = 0.5 * (b.lo + b.hi);
      centres.grow({c, c});
    }
    nodes_[index].box = box;
    if (end - begin <= kLeafSize) {
      nodes_[index].first = begin;
      nodes_[index].count = end - begin;
      return;
    }
    int axis = 0;
    const Vec3 extent = centres.hi - centres.lo;
    if (extent.y() > extent[axis]) axis = 1;
    if (extent.z() > extent[axis]) axis = 2;
    const std::size_t middle = begin + (end - begin) / 2;
    const auto centre = [&](std::uint32_t i) { return boxes_[i].lo[axis] + boxes_[i].hi[axis]; };
    std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(begin),
                     order_.begin() + static_cast<std::ptrdiff_t>(middle),
                     order_.begin() + static_cast<std::ptrdiff_t>(end),
                     [&](std::uint32_t a, std::uint32_t b) {
                       return centre(a) != centre(b) ? centre(a) < centre(b) : a < b;
                     });
    const std::size_t left = nodes_.size();
    nodes_.resize(left + 2);
    nodes_[index].first = left;
    build(left, begin, middle);
    build(left + 1, middle, end);
  }

  /// Whether the segment from p to q meets `box` grown by `margin` on every
  /// side (slab test). The margin exceeds the rounding of this test, so a
  /// segment that meets the box exactly is never dismissed.
  static bool segment_meets(const Vec3& p, const Vec3& q, const Box& box, double margin) {
    double t0 = 0.0;
    double t1 = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double lo = box.lo[k] - margin;
      const double hi = box.hi[k] + margin;
      const double d = q[k] - p[k];
      if (d == 0.0) {
        if (p[k] < lo || p[k] > hi) return false;
        continue;
      }
      double a = (lo - p[k]) / d;
      double b = (hi - p[k]) / d;
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
      if (t0 > t1) return false;
    }
    return true;
  }

  std::vector<Box> boxes_;            ///< by index; empty ones are not in the tree
  std::vector<std::uint32_t> order_;  ///< indices of the non-empty boxes, grouped by leaf
  std::vector<Node> nodes_;           ///< node 0 the root
};

/// Classifies the segment pq against the triangle abc, exactly: Cross when
/// it passes through the triangle's interior from one side of its plane to
/// the other, Touch when it meets the closed triangle any other way (at an
/// edge, a vertex, or within its plane), Miss otherwise.
SegmentMeeting classify(const Point& p, const Point& q, const Point& a, const Point& b, const Point& c) {
  const CGAL::Orientation side_p = CGAL::orientation(a, b, c, p);
  const CGAL::Orientation side_q = CGAL::orientation(a, b, c, q);
  const Kernel::Triangle_3 triangle(a, b, c);
  if (side_p == CGAL::COPLANAR && side_q == CGAL::COPLANAR) {
    return CGAL::do_intersect(Kernel::Segment_3(p, q), triangle) ? SegmentMeeting::Touch
                                                                 : SegmentMeeting::Miss;
  }
  if (side_p == CGAL::COPLANAR) return triangle.has_on(p) ? SegmentMeeting::Touch : SegmentMeeting::Miss;
  if (side_q == CGAL::COPLANAR) return triangle.has_on(q) ? SegmentMeeting::Touch : SegmentMeeting::Miss;
  if (side_p == side_q) return SegmentMeeting::Miss;
  // The segment crosses the plane at one interior point: where the line pq meets it.
  const CGAL::Orientation s1 = CGAL::orientation(p, q, a, b);
  const CGAL::Orientation s2 = CGAL::orientation(p, q, b, c);
  const CGAL::Orientation s3 = CGAL::orientation(p, q, c, a);
  const bool has_positive = s1 == CGAL::POSITIVE || s2 == CGAL::POSITIVE || s3 == CGAL::POSITIVE;
  const bool has_negative = s1 == CGAL::NEGATIVE || s2 == CGAL::NEGATIVE || s3 == CGAL::NEGATIVE;
  if (has_positive && has_negative) return SegmentMeeting::Miss;
  const bool on_border = s1 == CGAL::COPLANAR || s2 == CGAL::COPLANAR || s3 == CGAL::COPLANAR;
  return on_border ? SegmentMeeting::Touch : SegmentMeeting::Cross;
}

/// splitmix64: a fixed, platform-independent sequence of 64-bit values.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// The box of each face in a component (faces in none get an empty box).
std::vector<Box> face_boxes(const TriangleSoup& soup, const ComponentLabels& labels) {
  std::vector<Box> boxes(soup.triangles.size());
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    if (labels.face_component[f] == ComponentLabels::kNone) continue;
    for (const std::uint32_t v : soup.triangles[f]) boxes[f].grow({soup.vertices[v], soup.vertices[v]});
  }
  return boxes;
}

/// Casts rays from the vertices of one component at a time.
class RayCaster {
 public:
  RayCaster(const TriangleSoup& soup, const ComponentLabels& labels)
      : soup_(soup),
        labels_(labels),
        tree_(face_boxes(soup, labels)),
        candidate_(labels.count, 0),
        parity_(labels.count, 0) {}

  /// Which of `candidates` (components other than the one `from` is a
  /// vertex of, whose boxes hold `from`) contain `from`, ascending; nullopt
  /// when the segment in direction k touches one of their faces other than
  /// transversally. The segment ends outside the candidates' boxes: only
  /// their faces count.
  std::optional<std::vector<std::size_t>> containers(const Vec3& from,
                                                     const std::vector<std::size_t>& candidates,
                                                     const std::vector<Box>& boxes, std::size_t k) {
    Box reach_box{from, from};
    for (const std::size_t c : candidates) reach_box.grow(boxes[c]);
    // A power of two: with the dyadic directions, a segment from a vertex on a
    // coarse grid ends exactly on the line it means (the tests rely on it).
    const double reach = std::exp2(std::ceil(std::log2(2.0 * (reach_box.hi - reach_box.lo).norm() + 1.0)));
    const std::array<double, 3> d = ray_direction(k);
    Vec3 to = from + reach * Vec3(d[0], d[1], d[2]);
    while (!outside(to, reach_box)) to = from + 2.0 * (to - from);  // rounding aside, the first is outside
    const double scale = std::max(
        {reach_box.lo.cwiseAbs().maxCoeff(), reach_box.hi.cwiseAbs().maxCoeff(), to.cwiseAbs().maxCoeff()});
    const Point p = point(from);
    const Point q = point(to);
    bool touched = false;
    for (const std::size_t c : candidates) candidate_[c] = 1;
    tree_.query(from, to, 1e-9 * scale, [&](std::uint32_t f) {
      const std::uint32_t c = labels_.face_component[f];
      if (touched || !candidate_[c]) return;
      const auto& t = soup_.triangles[f];
      const SegmentMeeting m = classify(p, q, point(soup_.vertices[t[0]]), point(soup_.vertices[t[1]]),
                                        point(soup_.vertices[t[2]]));
      if (m == SegmentMeeting::Touch) touched = true;
      if (m == SegmentMeeting::Cross) parity_[c] ^= 1;
    });
    std::vector<std::size_t> inside;
    for (const std::size_t c : candidates) {
      if (parity_[c] != 0) inside.push_back(c);
      parity_[c] = 0;
      candidate_[c] = 0;
    }
    if (touched) return std::nullopt;
    return inside;
  }

 private:
  static bool outside(const Vec3& v, const Box& box) {
    for (int k = 0; k < 3; ++k) {
      if (v[k] < box.lo[k] || v[k] > box.hi[k]) return true;
    }
    return false;
  }

  const TriangleSoup& soup_;
  const ComponentLabels& labels_;
  BoxTree tree_;                 ///< over the face boxes
  std::vector<char> candidate_;  ///< per component: a candidate of the current segment
  std::vector<char> parity_;     ///< per component: crossings so far, mod 2
};

/// The bounding box of each component.
std::vector<Box> component_boxes(const TriangleSoup& soup, const ComponentLabels& labels) {
  std::vector<Box> boxes(labels.count);
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const std::uint32_t c = labels.face_component[f];
    if (c == ComponentLabels::kNone) continue;
    for (const std::uint32_t v : soup.triangles[f]) boxes[c].grow({soup.vertices[v], soup.vertices[v]});
  }
  return boxes;
}

}  // namespace

ComponentLabels label_components(const TriangleSoup& soup) {
  const std::size_t nv = soup.vertices.size();
  DisjointSets<std::uint32_t> parts(nv);
  for (const auto& t : soup.triangles) {
    if (index_degenerate(t)) continue;
    parts.unite(t[0], t[1]);
    parts.unite(t[1], t[2]);
  }
  ComponentLabels labels;
  std::vector<std::uint32_t> component(nv, ComponentLabels::kNone);  // by root vertex
  std::vector<char> used(nv, 0);
  for (const auto& t : soup.triangles) {
    if (!index_degenerate(t)) {
      for (const std::uint32_t v : t) used[v] = 1;
    }
  }
  // The root of a set is its smallest vertex, so numbering roots in vertex
  // order numbers components by their lowest vertex.
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (!used[v] || parts.find(v) != v) continue;
    component[v] = static_cast<std::uint32_t>(labels.count++);
    labels.lowest_vertex.push_back(v);
  }
  labels.faces.assign(labels.count, 0);
  labels.face_component.assign(soup.triangles.size(), ComponentLabels::kNone);
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const auto& t = soup.triangles[f];
    if (index_degenerate(t)) continue;
    const std::uint32_t c = component[parts.find(t[0])];
    labels.face_component[f] = c;
    ++labels.faces[c];
  }
  return labels;
}

std::vector<double> component_volumes(const TriangleSoup& soup, const ComponentLabels& labels) {
  std::vector<double> volume6(labels.count, 0.0);
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const std::uint32_t c = labels.face_component[f];
    if (c == ComponentLabels::kNone) continue;
    const Vec3& centre = soup.vertices[labels.lowest_vertex[c]];
    const auto& t = soup.triangles[f];
    volume6[c] += (soup.vertices[t[0]] - centre)
                      .dot((soup.vertices[t[1]] - centre).cross(soup.vertices[t[2]] - centre));
  }
  for (double& v : volume6) v /= 6.0;
  return volume6;
}

namespace {

/// The exact volume signs of `count` components, `component_of(f)` the
/// component of face f (or ComponentLabels::kNone), each about its
/// `lowest_vertex` with `faces` faces.
template <class ComponentOf>
std::vector<int> volume_signs(const TriangleSoup& soup, std::size_t count,
                              const std::vector<std::uint32_t>& lowest_vertex,
                              const std::vector<std::size_t>& faces, ComponentOf component_of) {
  // Each term t = a . (b x c) (a, b, c the corners less the centre) is
  // computed within 1e-15 times its permanent, the sum of the magnitudes of
  // its six products (a few roundings of relative size 2^-53 each), and a
  // sum of n terms within (n - 1) 2^-53 of the sum of their magnitudes.
  std::vector<double> sum(count, 0.0);
  std::vector<double> magnitude(count, 0.0);  // sum of the permanents
  const auto corners = [&](std::size_t f, std::uint32_t c) {
    const Vec3& centre = soup.vertices[lowest_vertex[c]];
    const auto& t = soup.triangles[f];
    return std::array<Vec3, 3>{soup.vertices[t[0]] - centre, soup.vertices[t[1]] - centre,
                               soup.vertices[t[2]] - centre};
  };
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const std::uint32_t c = component_of(f);
    if (c == ComponentLabels::kNone) continue;
    const auto [a, b, d] = corners(f, c);
    sum[c] += a.dot(b.cross(d));
    const Vec3 x = a.cwiseAbs(), y = b.cwiseAbs(), z = d.cwiseAbs();
    magnitude[c] += x[0] * (y[1] * z[2] + y[2] * z[1]) + x[1] * (y[0] * z[2] + y[2] * z[0]) +
                    x[2] * (y[0] * z[1] + y[1] * z[0]);
  }
  std::vector<int> sign(count, 0);
  std::vector<char> exact(count, 0);
  for (std::size_t c = 0; c < count; ++c) {
    const double n = static_cast<double>(faces[c]);
    const double bound = 1.01 * (1e-15 + n * 0x1p-53) * magnitude[c];  // the terms' own errors included
    if (std::abs(sum[c]) > bound) {
      sign[c] = sum[c] > 0 ? 1 : -1;
    } else {
      exact[c] = 1;
    }
  }
  if (std::find(exact.begin(), exact.end(), 1) == exact.end()) return sign;
  // The exact sums, only for the components the bound left open. The
  // differences of corners are exact as Mpzf, and so are their products.
  std::vector<CGAL::Mpzf> total(count, CGAL::Mpzf(0));
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const std::uint32_t c = component_of(f);
    if (c == ComponentLabels::kNone || !exact[c]) continue;
    const Vec3& centre = soup.vertices[lowest_vertex[c]];
    std::array<std::array<CGAL::Mpzf, 3>, 3> m;
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        m[i][k] = CGAL::Mpzf(soup.vertices[soup.triangles[f][i]][k]) - CGAL::Mpzf(centre[k]);
      }
    }
    total[c] = total[c] + m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  for (std::size_t c = 0; c < count; ++c) {
    if (exact[c]) sign[c] = static_cast<int>(CGAL::sign(total[c]));
  }
  return sign;
}

}  // namespace

std::vector<int> component_volume_signs(const TriangleSoup& soup, const ComponentLabels& labels) {
  return volume_signs(soup, labels.count, labels.lowest_vertex, labels.faces,
                      [&](std::size_t f) { return labels.face_component[f]; });
}

int total_volume_sign(const TriangleSoup& soup) {
  std::vector<std::size_t> faces{0};
  std::vector<std::uint32_t> centre;
  for (const auto& t : soup.triangles) {
    if (index_degenerate(t)) continue;
    if (faces[0]++ == 0) centre = {t[0]};
  }
  if (faces[0] == 0) return 0;
  return volume_signs(soup, 1, centre, faces,
                      [&](std::size_t f) {
                        return index_degenerate(soup.triangles[f]) ? ComponentLabels::kNone
                                                                   : std::uint32_t{0};
                      })
      .front();
}

SegmentMeeting segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                                      const Vec3& c) {
  return classify(point(p), point(q), point(a), point(b), point(c));
}

std::array<double, 3> ray_direction(std::size_t k) {
  std::array<double, 3> d{};
  for (std::size_t i = 0; i < 3; ++i) {
    const std::uint64_t bits = mix(3 * k + i);
    // 0.5 + m / 2^17 with m < 2^16: a dyadic rational in [0.5, 1), and a sign.
    const double magnitude = 0.5 + static_cast<double>(bits & 0xffffu) / 131072.0;
    d[i] = (bits >> 63) != 0 ? -magnitude : magnitude;
  }
  return d;
}

Nesting nest_components(const TriangleSoup& soup, const ComponentLabels& labels) {
  constexpr std::size_t kDirections = 32;
  constexpr std::size_t kStarts = 16;  // vertices of a component to cast from, at most
  Nesting nesting;
  nesting.depth.assign(labels.count, 0);
  nesting.determined.assign(labels.count, 1);
  nesting.inside.assign(labels.count, std::nullopt);
  if (labels.count < 2) return nesting;
  // The start points of each component's rays: its first distinct vertices, in face order.
  std::vector<std::vector<std::uint32_t>> starts(labels.count);
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const std::uint32_t c = labels.face_component[f];
    if (c == ComponentLabels::kNone || starts[c].size() >= kStarts) continue;
    for (const std::uint32_t v : soup.triangles[f]) {
      if (starts[c].size() < kStarts && std::find(starts[c].begin(), starts[c].end(), v) == starts[c].end()) {
        starts[c].push_back(v);
      }
    }
  }
  // Another component can contain a vertex of C only if its box holds it:
  // those are C's candidates, found with a hierarchy over the component boxes.
  const std::vector<Box> boxes = component_boxes(soup, labels);
  const BoxTree box_tree(boxes);
  std::optional<RayCaster> caster;  // built at the first candidate: separate parts need none
  std::vector<std::vector<std::size_t>> containers(labels.count);
  for (std::size_t c = 0; c < labels.count; ++c) {
    std::optional<std::vector<std::size_t>> found;
    for (std::size_t attempt = 0; !found && attempt < starts[c].size() * kDirections; ++attempt) {
      const Vec3& from = soup.vertices[starts[c][attempt / kDirections]];
      std::vector<std::size_t> candidates;
      box_tree.query(from, from, 0.0, [&](std::uint32_t d) {
        if (d != c) candidates.push_back(d);
      });
      if (candidates.empty()) {
        found.emplace();
        break;
      }
      std::sort(candidates.begin(), candidates.end());
      ++nesting.rays;
      if (!caster) caster.emplace(soup, labels);
      found = caster->containers(from, candidates, boxes, attempt % kDirections);
      if (!found) ++nesting.retries;
    }
    if (!found) {
      nesting.determined[c] = 0;  // every ray touched: C meets another component, or nearly so
      continue;
    }
    containers[c] = std::move(*found);
    nesting.depth[c] = containers[c].size();
  }
  // The containers of a component are nested in one another: the innermost has the greatest depth.
  for (std::size_t c = 0; c < labels.count; ++c) {
    for (const std::size_t d : containers[c]) {
      if (!nesting.inside[c] || nesting.depth[d] > nesting.depth[*nesting.inside[c]]) nesting.inside[c] = d;
    }
  }
  return nesting;
}

}  // namespace fabmesh
