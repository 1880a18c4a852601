#include "geometry/mesh/interpenetration.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <memory>
#include <utility>

#include "geometry/mesh/bounding_box.h"

namespace fabmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Surface = CGAL::Surface_mesh<Point>;
using Face = Surface::Face_index;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Surface>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Side = CGAL::Side_of_triangle_mesh<Surface, Kernel, CGAL::Default, Tree>;

Point to_point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

/// One solid made ready for queries: its surface, a tree of its faces and
/// its inside test.
class Solid {
 public:
  explicit Solid(const TriangleSoup& soup) : box_(used_box(soup)) {
    std::vector<Surface::Vertex_index> vertex;
    vertex.reserve(soup.vertices.size());
    for (const Vec3& p : soup.vertices) vertex.push_back(surface_.add_vertex(to_point(p)));
    for (const auto& t : soup.triangles) {
      triangles_.push_back(
          {to_point(soup.vertices[t[0]]), to_point(soup.vertices[t[1]]), to_point(soup.vertices[t[2]])});
      used_.push_back(to_point(soup.vertices[t[0]]));
      used_.push_back(to_point(soup.vertices[t[1]]));
      used_.push_back(to_point(soup.vertices[t[2]]));
      // A valid solid is an oriented 2-manifold: add_face cannot refuse it;
      // a refused face would only leave the trees without it.
      surface_.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]);
    }
    tree_ = std::make_unique<Tree>(faces(surface_).first, faces(surface_).second, surface_);
    tree_->build();
    side_ = std::make_unique<Side>(*tree_);
  }

  const BoundingBox& box() const { return box_; }
  const Surface& surface() const { return surface_; }
  const std::vector<Point>& corners() const { return used_; }
  const std::vector<std::array<Point, 3>>& triangles() const { return triangles_; }

  /// True when `p` is strictly inside (exact predicates) and, with contact > 0,
  /// farther than `contact` from the surface.
  bool strictly_inside(const Point& p, double contact) const {
    if ((*side_)(p) != CGAL::ON_BOUNDED_SIDE) return false;
    if (contact <= 0.0) return true;
    if (!distances_ready_) {
      tree_->accelerate_distance_queries();
      distances_ready_ = true;
    }
    return tree_->squared_distance(p) > contact * contact;
  }

  /// The faces whose triangles meet `query` (a segment or a triangle).
  template <class Query>
  std::vector<std::array<Point, 3>> meeting(const Query& query) const {
    std::vector<Face> hits;
    tree_->all_intersected_primitives(query, std::back_inserter(hits));
    std::vector<std::array<Point, 3>> out;
    out.reserve(hits.size());
    for (const Face f : hits) out.push_back(corners_of(f));
    return out;
  }

 private:
  static BoundingBox used_box(const TriangleSoup& soup) {
    BoundingBox box;
    for (const auto& t : soup.triangles) {
      for (const std::uint32_t v : t) {
        box.lo = box.lo.cwiseMin(soup.vertices[v]);
        box.hi = box.hi.cwiseMax(soup.vertices[v]);
      }
    }
    return box;
  }

  std::array<Point, 3> corners_of(Face f) const {
    std::array<Point, 3> out;
    int k = 0;
    for (const auto v : vertices_around_face(surface_.halfedge(f), surface_)) out[k++] = surface_.point(v);
    return out;
  }

  BoundingBox box_;
  Surface surface_;
  std::vector<std::array<Point, 3>> triangles_;
  std::vector<Point> used_;
  std::unique_ptr<Tree> tree_;
  std::unique_ptr<Side> side_;
  mutable bool distances_ready_ = false;
};

/// The open boxes overlap (the boxes share more than a face, edge or corner).
bool boxes_overlap(const BoundingBox& a, const BoundingBox& b) {
  for (int k = 0; k < 3; ++k) {
    if (!(a.lo[k] < b.hi[k] && b.lo[k] < a.hi[k])) return false;
  }
  return true;
}

bool inside_box(const BoundingBox& box, const Point& p) {
  return box.lo.x() < p.x() && p.x() < box.hi.x() && box.lo.y() < p.y() && p.y() < box.hi.y() &&
         box.lo.z() < p.z() && p.z() < box.hi.z();
}

/// Whether p is farther than `contact` from the plane of triangle t (computed distance).
bool off_plane_by(const Point& p, const std::array<Point, 3>& t, double contact) {
  if (contact <= 0.0) return true;
  return CGAL::squared_distance(p, Kernel::Plane_3(t[0], t[1], t[2])) > contact * contact;
}

/// Whether segment pq, whose ends lie on either side of the plane of t,
/// meets that plane farther than `contact` from t's edges (computed distances).
bool inside_by(const Point& p, const Point& q, const std::array<Point, 3>& t, double contact) {
  if (contact <= 0.0) return true;
  const Kernel::Plane_3 plane(t[0], t[1], t[2]);
  const double dp = std::sqrt(CGAL::squared_distance(p, plane));
  const double dq = std::sqrt(CGAL::squared_distance(q, plane));
  const Point x = p + (q - p) * (dp / (dp + dq));
  for (int i = 0; i < 3; ++i) {
    if (CGAL::squared_distance(x, Kernel::Segment_3(t[i], t[(i + 1) % 3])) <= contact * contact) return false;
  }
  return true;
}

/// Segment pq crosses triangle t through its interior, p and q strictly on
/// either side of its plane (and farther than `contact` from it).
bool crosses(const Point& p, const Point& q, const std::array<Point, 3>& t, double contact) {
  const CGAL::Orientation op = CGAL::orientation(t[0], t[1], t[2], p);
  const CGAL::Orientation oq = CGAL::orientation(t[0], t[1], t[2], q);
  if (op == CGAL::COPLANAR || oq == CGAL::COPLANAR || op == oq) return false;
  if (!off_plane_by(p, t, contact) || !off_plane_by(q, t, contact) || !inside_by(p, q, t, contact))
    return false;
  const CGAL::Orientation a = CGAL::orientation(p, q, t[0], t[1]);
  const CGAL::Orientation b = CGAL::orientation(p, q, t[1], t[2]);
  const CGAL::Orientation c = CGAL::orientation(p, q, t[2], t[0]);
  return a != CGAL::COPLANAR && a == b && b == c;
}

/// A point off the plane of the non-degenerate triangle t: of four points
/// not in one plane, one is off it.
Point off_plane(const std::array<Point, 3>& t) {
  for (const Point& x : {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)}) {
    if (CGAL::orientation(t[0], t[1], t[2], x) != CGAL::COPLANAR) return x;
  }
  return {0, 0, 0};  // unreachable for a non-degenerate triangle
}

/// An edge of triangle t (of a plane holding u) has every corner of u on
/// its outer side or its line: it separates their interiors.
bool separates(const std::array<Point, 3>& t, const std::array<Point, 3>& u) {
  for (int i = 0; i < 3; ++i) {
    const Point& p = t[i];
    const Point& q = t[(i + 1) % 3];
    const Point& r = t[(i + 2) % 3];
    const bool outside = std::all_of(u.begin(), u.end(), [&](const Point& s) {
      return CGAL::coplanar_orientation(p, q, r, s) != CGAL::POSITIVE;
    });
    if (outside) return true;
  }
  return false;
}

/// Triangles a and b lie in one plane, face the same way and overlap with
/// positive area (exact: two convex polygons of one plane have disjoint
/// interiors exactly when the line of an edge of one separates them).
bool overlap_facing_alike(const std::array<Point, 3>& a, const std::array<Point, 3>& b) {
  for (const Point& p : b) {
    if (CGAL::orientation(a[0], a[1], a[2], p) != CGAL::COPLANAR) return false;
  }
  const Point x = off_plane(a);
  if (CGAL::orientation(a[0], a[1], a[2], x) != CGAL::orientation(b[0], b[1], b[2], x)) return false;
  return !separates(a, b) && !separates(b, a);
}

/// Some vertex, edge or face of `a` shows that it reaches into `b`'s inside
/// (criteria 1 to 3 of interpenetrating_pairs, from a's side).
bool reaches_into(const Solid& a, const Solid& b, double contact) {
  for (const Point& p : a.corners()) {
    if (inside_box(b.box(), p) && b.strictly_inside(p, contact)) return true;
  }
  const Surface& s = a.surface();
  for (const auto e : s.edges()) {
    const Point& p = s.point(s.vertex(e, 0));
    const Point& q = s.point(s.vertex(e, 1));
    const Kernel::Segment_3 segment(p, q);
    for (const auto& t : b.meeting(segment)) {
      if (crosses(p, q, t, contact)) return true;
    }
  }
  for (const auto& t : a.triangles()) {
    const Kernel::Triangle_3 triangle(t[0], t[1], t[2]);
    for (const auto& u : b.meeting(triangle)) {
      if (overlap_facing_alike(t, u)) return true;
    }
  }
  return false;
}

}  // namespace

std::size_t interpenetration_work_bound(std::size_t triangles) { return 16 * triangles + 100000; }

double float32_contact(const std::vector<const TriangleSoup*>& solids) {
  double largest = 0.0;
  for (const TriangleSoup* soup : solids) {
    if (soup == nullptr) continue;
    for (const Vec3& p : soup->vertices) {
      for (int k = 0; k < 3; ++k) {
        if (static_cast<double>(static_cast<float>(p[k])) != p[k]) return 0.0;
        largest = std::max(largest, std::abs(p[k]));
      }
    }
  }
  return 4.0 * std::ldexp(largest, -23);  // 4 units in the last place of a float at `largest`
}

Interpenetration interpenetrating_pairs(const std::vector<const TriangleSoup*>& solids, std::size_t max_work,
                                        double contact) {
  std::vector<std::size_t> judged;
  std::vector<BoundingBox> boxes(solids.size());
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < solids.size(); ++i) {
    if (solids[i] == nullptr) continue;
    judged.push_back(i);
    boxes[i] = bounding_box(solids[i]->vertices);
    triangles += solids[i]->triangles.size();
  }
  if (max_work == 0) max_work = interpenetration_work_bound(triangles);
  // A sweep along x: only pairs whose x ranges overlap are compared.
  std::sort(judged.begin(), judged.end(), [&](std::size_t a, std::size_t b) {
    return std::make_pair(boxes[a].lo.x(), a) < std::make_pair(boxes[b].lo.x(), b);
  });
  std::vector<std::unique_ptr<Solid>> ready(solids.size());
  const auto solid = [&](std::size_t i) -> const Solid& {
    if (!ready[i]) ready[i] = std::make_unique<Solid>(*solids[i]);
    return *ready[i];
  };
  Interpenetration found;
  std::size_t work = 0;
  for (std::size_t a = 0; a < judged.size() && found.complete; ++a) {
    for (std::size_t b = a + 1; b < judged.size() && boxes[judged[b]].lo.x() < boxes[judged[a]].hi.x(); ++b) {
      const std::size_t i = std::min(judged[a], judged[b]);
      const std::size_t j = std::max(judged[a], judged[b]);
      const std::size_t cost = boxes_overlap(boxes[i], boxes[j])
                                   ? 1 + solids[i]->triangles.size() + solids[j]->triangles.size()
                                   : 1;
      if (work + cost > max_work) {
        found.complete = false;
        break;
      }
      work += cost;
      if (cost == 1 || !boxes_overlap(solid(i).box(), solid(j).box())) continue;
      if (reaches_into(solid(i), solid(j), contact) || reaches_into(solid(j), solid(i), contact))
        found.pairs.emplace_back(i, j);
    }
  }
  std::sort(found.pairs.begin(), found.pairs.end());
  return found;
}

}  // namespace fabmesh
