#pragma once
// The connected components of a triangle soup as closed shells: which faces
// belong to which component, each component's signed volume, and how the
// components nest (which contain which), decided by ray parity with exact
// predicates. validate uses it to check the orientation of each component
// against its nesting.
//
// Internal to geometry/validation (validate.h is the public entry); the
// tests include it to check this part alone.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// The connected components of a soup (faces sharing a vertex), numbered in
/// order of each component's lowest vertex: the order of
/// Topology::euler_characteristics and TopologyProof. Index-degenerate faces
/// (a repeated index) belong to none, as in analyse_topology.
struct ComponentLabels {
  static constexpr std::uint32_t kNone = UINT32_MAX;
  std::size_t count = 0;
  std::vector<std::uint32_t> face_component;  ///< per face: its component, or kNone
  std::vector<std::uint32_t> lowest_vertex;   ///< per component: its lowest vertex index
  std::vector<std::size_t> faces;             ///< per component: its number of faces
};

/// Labels the faces of `soup` by connected component, in O(n alpha(n)).
/// \pre every index in range
ComponentLabels label_components(const TriangleSoup& soup);

/// The signed volume each component encloses (positive when it faces
/// outward), taken about the component's lowest vertex.
/// \pre every index in range, every coordinate finite
std::vector<double> component_volumes(const TriangleSoup& soup, const ComponentLabels& labels);

/// The exact sign (+1, 0, -1) of the signed volume each component encloses,
/// about its lowest vertex: the double sum when its error bound decides it,
/// else the exact sum (CGAL::Mpzf). So a closed component of tiny volume is
/// judged outward or inward as it is, not as rounding makes it.
/// \pre every index in range, every coordinate finite
std::vector<int> component_volume_signs(const TriangleSoup& soup, const ComponentLabels& labels);

/// The exact sign of the signed volume of all of `soup`'s faces but those
/// with a repeated index, about the first such face's first vertex, as
/// component_volume_signs decides it for one component of all those faces:
/// the total signed volume's sign when the mesh is closed (then it does not
/// depend on the point). 0 for a soup of no such face.
/// \pre every index in range, every coordinate finite
int total_volume_sign(const TriangleSoup& soup);

/// How the components nest.
struct Nesting {
  std::vector<std::size_t> depth;  ///< per component: how many other components contain it
  /// Per component: nonzero when its nesting was settled; zero when every
  /// ray cast from it met another component other than transversally (then
  /// depth is 0 and inside unset: unknown).
  std::vector<char> determined;
  /// Per component: the innermost component containing it (the container of
  /// greatest depth), none at depth 0.
  std::vector<std::optional<std::size_t>> inside;
  std::size_t rays = 0;     ///< rays cast, retries included
  std::size_t retries = 0;  ///< rays abandoned because they touched an edge, a vertex or a face's plane
};

/// What a segment does to a triangle.
enum class SegmentMeeting {
  Miss,   ///< no common point
  Cross,  ///< through the triangle's interior, from one side of its plane to the other
  Touch,  ///< any other common point: at an edge or a vertex, or within the triangle's plane
};

/// Classifies the segment pq against the (non-degenerate) triangle abc with
/// exact predicates: what nest_components counts (Cross) or casts again for
/// (Touch).
SegmentMeeting segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                                      const Vec3& c);

/// The direction (not normalized, every coordinate a dyadic rational of
/// magnitude in [0.5, 1]) of the k-th ray nest_components tries from a point:
/// a fixed pseudo-random sequence, the same on every platform.
std::array<double, 3> ray_direction(std::size_t k);

/// Which components contain which. The candidates to contain a component C
/// are the other components whose boxes hold a vertex of C (a hierarchy over
/// the component boxes finds them; most often there are none and no ray is
/// cast). From that vertex a segment is cast to a point outside the
/// candidates' boxes; a candidate contains C when the segment crosses it an
/// odd number of times.
/// Every crossing is classified with exact predicates (CGAL Epick): a segment
/// that touches an edge, a vertex or lies in a face's plane where it meets
/// the face is abandoned for the next direction of ray_direction (then the
/// next vertex of C's first face), so every crossing counted is transversal
/// through the interior of one face and the parity is exact. Candidate faces
/// come from a bounding-volume hierarchy over the face boxes: O(n log n) to
/// build, about O(log n + faces met) per ray.
/// \pre the components are closed, manifold, consistently oriented and
///      pairwise disjoint (no self-intersection), with finite coordinates
///      and no degenerate faces; otherwise nesting has no meaning.
/// \throw std::logic_error when every ray tried from a component is
///        degenerate (impossible for disjoint components short of a
///        contrived input of hundreds of aligned features).
Nesting nest_components(const TriangleSoup& soup, const ComponentLabels& labels);

}  // namespace fabmesh
