#pragma once
// Mesh validity for fabrication: closed, manifold, consistently and outward
// oriented, free of self-intersections, degenerate and duplicate faces.
// Every mesh fabmesh writes passes through validate + require_valid.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/stage_timer.h"
#include "geometry/core/types.h"
#include "geometry/mesh/soup.h"
#include "geometry/mesh/topology.h"

namespace fabmesh {

/// The kinds of defect that make a mesh invalid for fabrication.
enum class Defect {
  Empty,                    ///< no faces at all
  NonFiniteVertex,          ///< a coordinate is NaN or infinite
  BoundaryEdge,             ///< an edge with one face (a hole; the mesh is not closed)
  NonManifoldEdge,          ///< an edge with three or more faces
  NonManifoldVertex,        ///< a vertex whose faces form more than one fan
  InconsistentOrientation,  ///< two faces traverse their shared edge the same way
  InsideOut,                ///< closed, but the signed volume is not positive
  DegenerateFace,           ///< zero area: a repeated index or collinear corners (exact test)
  DuplicateFace,            ///< another face has the same three vertices
  SelfIntersection,         ///< two faces meet away from their shared vertices and edges
};

/// A short lower-case name of a defect kind, e.g. "boundary edges".
const char* to_string(Defect kind);

/// How the self-intersection question was settled for a report.
enum class IntersectionCheck {
  NotRun,                ///< skipped (by option, or non-finite input): the mesh cannot be called valid
  Tested,                ///< the 3D test ran over every candidate pair of faces (exact predicates)
  ProvenByConstruction,  ///< the builder proved the mesh embedded (EmbeddingProof); no 3D test ran
};

/// "not run", "tested" or "proven by construction".
const char* to_string(IntersectionCheck check);

/// One kind of defect found: how often, and a few locations (model units).
struct DefectReport {
  Defect kind;
  std::size_t count = 0;
  std::vector<Vec3> examples;  ///< edge midpoints, vertices or face centroids
};

/// Options of validate.
struct ValidateOptions {
  bool check_self_intersections = true;  ///< the slowest stage; off only for diagnostics
  bool parallel = true;                  ///< use all cores for the self-intersection test
  std::size_t max_examples = 5;          ///< example locations kept per defect kind
};

/// Everything validate found out about a mesh.
struct ValidationReport {
  std::size_t vertices = 0;    ///< vertices of the mesh (after any welding the caller did)
  std::size_t triangles = 0;   ///< faces, degenerate ones included
  std::size_t components = 0;  ///< connected components (faces sharing a vertex)
  std::size_t boundary_edges = 0;
  std::size_t non_manifold_edges = 0;
  std::size_t non_manifold_vertices = 0;
  std::size_t inconsistent_edges = 0;  ///< two-face edges whose faces disagree on orientation
  std::size_t degenerate_faces = 0;
  std::size_t duplicate_faces = 0;
  std::size_t non_finite_vertices = 0;
  IntersectionCheck self_intersection = IntersectionCheck::NotRun;
  std::string embedding_proof;  ///< the builder's statement when ProvenByConstruction
  /// With ProvenByConstruction: moving every vertex by less than this keeps
  /// the mesh embedded (EmbeddingProof::margin; 0: not proven).
  double embedding_margin = 0.0;
  /// The builder's statement when its construction proved the connectivity
  /// (closed, manifold, oriented, components, Euler characteristics; see
  /// TopologyProof); empty when the connectivity was analysed.
  std::string topology_proof;
  bool self_intersecting = false;
  std::size_t intersecting_pairs = 0;  ///< face pairs that intersect
  bool consistently_oriented = false;  ///< no inconsistent edge
  bool oriented_outward = false;       ///< signed volume > 0
  double volume = 0.0;                 ///< signed enclosed volume, model units^3 (meaningful when closed)
  double area = 0.0;                   ///< total surface area, model units^2
  /// Sum of the component genera, from each component's Euler characteristic
  /// (g = (2 - chi) / 2); set only for a closed, manifold, consistently
  /// oriented mesh.
  std::optional<long> genus;
  std::vector<long> euler_characteristics;  ///< V - E + F of each component
  std::vector<DefectReport> defects;        ///< one entry per kind found, in enum order
  StageTimings timings_ms;                  ///< stage name -> wall time, ms

  /// True when no defect was found and self-intersection was tested or proven absent.
  bool valid() const { return defects.empty() && self_intersection != IntersectionCheck::NotRun; }
  /// The entry for `kind`, or nullptr when that defect was not found.
  const DefectReport* find(Defect kind) const;
};

/// Validates an indexed triangle soup (no topology assumed: non-manifold
/// input is fully analysed). Vertices are taken as they are; weld a soup
/// from a file first. \throw InputError when an index is out of range.
ValidationReport validate(const TriangleSoup& soup, const ValidateOptions& options = {});

/// Validates an OpenMesh mesh: its connectivity in linear time from the
/// halfedges (analyse_topology(Mesh)), its geometry through its soup.
ValidationReport validate(const Mesh& mesh, const ValidateOptions& options = {});

/// The same when the caller already has `soup` == to_soup(mesh).
ValidationReport validate(const Mesh& mesh, const TriangleSoup& soup, const ValidateOptions& options = {});

/// Validates `soup` given its connectivity facts `topology` (from
/// analyse_topology on the same triangles, or from a construction proof):
/// every geometric check of validate (finiteness, exact degeneracy, area,
/// signed volume and orientation, the exact self-intersection test) runs on
/// `soup`, the combinatorial counts and the genus come from `topology`.
ValidationReport validate_geometry(const TriangleSoup& soup, const Topology& topology,
                                   const ValidateOptions& options = {});

/// The report validate(moved) would give, without redoing what cannot have
/// changed. `moved` has the same triangles as `original` (same indices, same
/// order) and `original_report` is validate(original) (or
/// validate_constructed). Everything combinatorial is a function of the
/// triangles alone (edges, fans, orientation, components, Euler
/// characteristics, genus, duplicate faces), so it is taken from
/// `original_report` (its example locations are the original positions,
/// within the displacement of the moved ones). Everything geometric is
/// recomputed on `moved` exactly as validate does: finiteness, area, signed
/// volume and orientation, exact degeneracy, and the exact self-intersection
/// test. So valid() and every defect kind and count equal validate(moved)'s.
/// Except that when `original_report` carries an embedding margin and no
/// vertex moved as far, the 3D test is replaced by that proof (the report
/// says ProvenByConstruction and how far the vertices moved).
/// \throw InputError when the triangles differ or an index is out of range.
ValidationReport validate_moved(const TriangleSoup& original, const ValidationReport& original_report,
                                const TriangleSoup& moved, const ValidateOptions& options = {});

/// One line per defect kind: "3 boundary edges (e.g. at (0, 0.5, 1))". Empty when valid.
std::vector<std::string> describe_defects(const ValidationReport& report);

/// Throws ValidationFailed unless report.valid(); the message starts with
/// `what` (e.g. "vessel 'cup'") and lists every defect with counts and examples.
void require_valid(const ValidationReport& report, const std::string& what);

}  // namespace fabmesh
