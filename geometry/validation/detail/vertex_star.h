#pragma once
// The faces around high-degree vertices ("stars"), tested together rather
// than pair by pair from the broad phase. A fan of d faces around a vertex v
// (a polygon triangulated from one corner, a cone apex) has d^2 / 2 pairs of
// faces sharing v whose boxes all overlap at v: the bounding-volume
// hierarchy would enumerate every one of them, which makes a 30,000-corner
// polygon take half a minute.
//
// Two faces containing v meet somewhere other than at v only at a point x
// != v, so the direction from v to x lies in both faces' "arcs": the sets of
// directions from v to their points (for a non-degenerate face, the great
// circle arc between the directions of its other two corners; every point
// v + s (a - v) + t (b - v) has a direction that is a positive combination of
// the two). So the pairs sharing v whose arcs do not overlap do not
// intersect; faces_intersect_exact says false for them (for faces sharing
// one vertex it asks whether a far edge, which avoids v, touches the other
// face; for faces sharing an edge vw, the direction of w is in both arcs).
// A box bounding each arc, inflated beyond every rounding error, and a sweep
// over the boxes give a superset of the candidates in O(d log d + k) for k
// overlapping boxes: about 2d for a valid fan (each face overlaps its
// neighbours), planar or not. Every candidate then goes through the same
// filter and exact test as the broad phase's, so the answer stays exact.
//
// Only certified faces (face_data: three distinct indices, filterable
// coordinates, certainly not degenerate) are members of stars; a pair with
// an uncertified face (a nearly degenerate sliver at a fan's apex, rare)
// stays in the broad phase.
//
// Internal to geometry/validation (validate.h is the public entry).

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh::detail {

/// The group of a face that contains no star centre.
constexpr std::uint32_t kNoStar = 0xffffffffu;

/// The stars of a soup: the vertices in >= a threshold of member faces
/// (certified faces taking part), and their member faces.
struct VertexStars {
  std::vector<char> centre;            ///< per vertex: nonzero when it is a star centre
  std::vector<std::uint32_t> group;    ///< per face: its smallest star centre if a member, else kNoStar
  std::vector<std::uint32_t> centres;  ///< the star centres, ascending
  std::vector<std::size_t> offsets;    ///< star s has faces[offsets[s] .. offsets[s + 1])
  std::vector<std::uint32_t> faces;    ///< the member faces of each star, ascending

  /// Whether member faces with vertex indices a and b share a star centre:
  /// then the pair is tested by a star (for_each_star_candidate), not the
  /// broad phase. (Only for members: certified faces.)
  bool shares_centre(const std::array<std::uint32_t, 3>& a, const std::array<std::uint32_t, 3>& b) const {
    for (const std::uint32_t v : a) {
      if (centre[v] && (v == b[0] || v == b[1] || v == b[2])) return true;
    }
    return false;
  }
};

/// Faces around fewer vertices than this are left to the broad phase (whose
/// d^2 / 2 pairs cost less than a sweep below it).
constexpr std::size_t kStarMinDegree = 32;

/// The stars of the certified faces f of `soup` with skip[f] == 0 (all when
/// `skip` is empty) around vertices in >= min_degree of them.
/// \pre indices in range, coordinates finite, skip empty or one flag per face.
VertexStars find_vertex_stars(const TriangleSoup& soup, const std::vector<char>& skip,
                              std::size_t min_degree = kStarMinDegree);

/// Calls visit(f, g), f < g, for each pair of faces of star s that may meet
/// beyond its centre and whose smallest shared star centre is this one (so
/// that over all stars every pair sharing a centre is visited at most once):
/// a superset of the pairs of the star for which faces_intersect_exact is
/// true. Stops when visit returns false. The order depends only on the soup.
void for_each_star_candidate(const TriangleSoup& soup, const VertexStars& stars, std::size_t s,
                             const std::function<bool(std::uint32_t, std::uint32_t)>& visit);

/// Calls visit(f, g) for each pair of a face f whose smallest star centre is
/// that of star s (group[f] == centres[s]) and a face g of `others` that may
/// meet: a superset of the pairs (f, g) for which faces_intersect_exact is
/// true, leaving out the pairs that share a star centre with g a member
/// (those are the stars' own, for_each_star_candidate). `others` are the
/// faces whose boxes may overlap those faces and whose group is greater than
/// the centre (kNoStar included), ascending, without duplicates. Stops when
/// visit returns false. The order depends only on the soup.
///
/// Seen from the centre v, a point x of g that lies in f is in f's arc and
/// in g's cone (the directions from v to g's points), so only pairs whose
/// boxes in direction space overlap are visited: a fan's long faces have
/// boxes overlapping most of the mesh around them in space, but arcs
/// overlapping few cones.
void for_each_star_neighbour_candidate(const TriangleSoup& soup, const VertexStars& stars, std::size_t s,
                                       const std::vector<std::uint32_t>& others,
                                       const std::function<bool(std::uint32_t, std::uint32_t)>& visit);

}  // namespace fabmesh::detail
