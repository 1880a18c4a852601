#pragma once
// Mesh validity for fabrication: closed, manifold, consistently and outward
// oriented, free of self-intersections, degenerate and duplicate faces.
// The one public entry of geometry/validation: validate(soup, options), the
// options carrying what a builder already proved. Every mesh fabmesh writes
// passes through it and require_valid (pipeline/validate_parts.h). Its
// private parts (connectivity analysis, bounding-volume hierarchy, face-pair
// filters, self-intersection test) are in geometry/validation/detail/.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/proofs.h"
#include "geometry/core/soup.h"
#include "geometry/core/stage_timer.h"
#include "geometry/core/types.h"
#include "geometry/validation/defect_location.h"

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
  InvertedComponent,        ///< of several components, one inside no other faces inward
  NestedSameOrientation,    ///< a component faces the way of the innermost one containing it
  DegenerateFace,           ///< zero area: a repeated index or collinear corners (exact test)
  DuplicateFace,            ///< another face has the same three vertices
  SelfIntersection,         ///< two faces meet away from their shared vertices and edges
};

/// A short lower-case name of a defect kind, e.g. "boundary edges".
const char* to_string(Defect kind);

/// The defect kind as a JSON key, e.g. "boundary_edge", "inverted_component".
const char* to_key(Defect kind);

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
  /// The first ValidationOptions::max_locations occurrences as faces and
  /// vertices (defect_location.h says what each kind lists; none for Empty
  /// and InsideOut), in a fixed order; count says how many there are in all.
  std::vector<DefectLocation> locations;
};

/// One connected component as a shell: its orientation, and where it lies
/// among the others. A closed component facing outward encloses solid; one
/// facing inward bounds a cavity, and must then lie inside an odd number of
/// other components.
struct ComponentShell {
  std::size_t faces = 0;         ///< faces of the component (index-degenerate faces belong to none)
  double volume = 0.0;           ///< signed enclosed volume, model units^3 (meaningful when closed)
  bool outward = false;          ///< volume > 0
  Vec3 location = Vec3::Zero();  ///< its lowest-indexed vertex, to point at it
  /// How many other components contain it; unset when the nesting was not
  /// determined (a mesh with one component has depth 0; with several, the
  /// nesting is determined only when the mesh has no other defect than
  /// InsideOut and its self-intersection was tested or proven absent).
  std::optional<std::size_t> depth;
  /// The innermost component containing it (index into component_shells);
  /// unset at depth 0 or when the nesting was not determined.
  std::optional<std::size_t> inside;
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
  /// With ProvenByConstruction: the builder's exact re-proof for a moved
  /// copy (EmbeddingProof::recheck), and what it proves; null when none.
  std::function<bool(const TriangleSoup& moved)> embedding_recheck;
  std::string embedding_recheck_statement;
  /// The builder's statement when its construction proved the connectivity
  /// (closed, manifold, oriented, components, Euler characteristics; see
  /// TopologyProof); empty when the connectivity was analysed.
  std::string topology_proof;
  bool self_intersecting = false;
  std::size_t intersecting_pairs = 0;  ///< face pairs that intersect (found so far when timed out)
  /// The self-intersection test ran out of its time budget (it stays NotRun);
  /// with the number of candidate face pairs it had tested by then.
  bool self_intersection_timed_out = false;
  std::size_t self_intersection_pairs_tested = 0;
  /// Components whose nesting (so whether they must face outward or inward)
  /// no ray settled: every ray cast from 16 of their vertices in 32
  /// directions met another component at an edge, a vertex or within a
  /// face's plane. Their orientation is then unknown, and the mesh is not
  /// called valid (a verdict not reached is not a pass).
  std::size_t undetermined_components = 0;
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
  /// Each component as a shell, in the order of euler_characteristics (each
  /// component's lowest vertex): with several, InvertedComponent and
  /// NestedSameOrientation judge their orientations against their nesting.
  /// One entry, from the totals, when the mesh has one component; none when
  /// it has no faces or a non-finite vertex.
  std::vector<ComponentShell> component_shells;

  /// True when no defect was found and self-intersection was tested or proven absent.
  bool valid() const {
    return defects.empty() && self_intersection != IntersectionCheck::NotRun && undetermined_components == 0;
  }
  /// The entry for `kind`, or nullptr when that defect was not found.
  const DefectReport* find(Defect kind) const;
};

/// A mesh already validated of which the soup being validated is a moved
/// copy: the same triangles (same indices, same order), its vertices moved
/// (quantized for Draco, rounded to float32, scaled).
struct MovedFrom {
  const TriangleSoup* soup = nullptr;        ///< the mesh as it was validated
  const ValidationReport* report = nullptr;  ///< its report (validate(*soup, ...))
};

/// What validate checks and what the caller (a builder) already proved.
struct ValidationOptions {
  bool check_self_intersections = true;  ///< the slowest stage; off only for diagnostics
  bool parallel = true;                  ///< use all cores for the self-intersection test
  std::size_t max_examples = 5;          ///< example locations kept per defect kind
  /// Occurrences kept per defect kind as faces and vertices
  /// (DefectReport::locations); 0 (default): none.
  std::size_t max_locations = 0;
  /// Which boundary edges are kept as examples: the first in face order
  /// (true: the order a builder made its faces, as the reports of built
  /// meshes list them) or the first by vertex index (false: as `check`
  /// lists a file's). Counts and the verdict do not depend on it.
  bool examples_in_face_order = false;
  /// Time budget of the self-intersection test, seconds (0: none). Past it
  /// the test stops: the report says NotRun and self_intersection_timed_out.
  double max_self_intersection_seconds = 0.0;
  /// The builder's proof of the connectivity: replaces the connectivity
  /// analysis (the report's counts, components, Euler characteristics and
  /// genus come from it; the report carries its statement as topology_proof).
  std::optional<TopologyProof> topology;
  /// The builder's proof of embedding: replaces the 3D self-intersection
  /// test (IntersectionCheck::ProvenByConstruction, with its statement and
  /// margin). A mesh with a non-finite vertex keeps IntersectionCheck::NotRun
  /// (a proof about the exact construction says nothing about NaNs), so it
  /// is never called valid.
  std::optional<EmbeddingProof> embedding;
  /// Set when the soup is a moved copy of a validated mesh: everything
  /// combinatorial (edges, fans, orientation, components, Euler
  /// characteristics, genus, duplicate faces, topology_proof) is a function
  /// of the triangles alone and is taken from that mesh's report (its
  /// example locations are the original positions, within the displacement
  /// of the moved ones). Everything geometric is recomputed on the soup:
  /// finiteness, area, signed volume and orientation (of every component,
  /// with their nesting), exact degeneracy, and the exact self-intersection
  /// test. So valid() and every defect kind and count equal those of a
  /// validation without it. Except that when the
  /// original report carries an embedding margin and no vertex moved as far,
  /// the 3D test is replaced by that proof (the report says
  /// ProvenByConstruction and how far the vertices moved). Not to be
  /// combined with `topology` or `embedding`.
  std::optional<MovedFrom> moved_from;
};

/// Validates an indexed triangle soup (no topology assumed: non-manifold
/// input is fully analysed, unless options.topology proves it). Vertices are
/// taken as they are; weld a soup from a file first.
/// \throw InputError when an index is out of range; with options.moved_from,
///        when the soup's triangles or vertex count differ from the
///        original's, or when topology or embedding is also given.
ValidationReport validate(const TriangleSoup& soup, const ValidationOptions& options = {});

/// What a mesh is fit for.
enum class MeshPurpose {
  Fabrication,  ///< closed, manifold, outward, embedded: every check passed
  Viewing,      ///< an open surface (no thickness): its only defect is its own border
  Drawing,      ///< no mesh at all: a curve design, drawn at true size
};

/// True when `report` is fit for `purpose`: valid; or, for viewing, its
/// only defects are boundary edges (an open surface's own border) and the
/// self-intersection test ran or was proven; always for drawing.
bool fit_for(const ValidationReport& report, MeshPurpose purpose);

/// True when a mesh validated as `report`, whose vertices then moved by at
/// most `moved_by` (model units), is proven still valid without validating
/// it again: it was valid and did not move, or moved by less than its
/// embedding margin (which keeps it embedded and its faces non-degenerate).
bool valid_when_moved(const ValidationReport& report, double moved_by);

/// One line per defect kind: "3 boundary edges (e.g. at (0, 0.5, 1))". Empty when valid.
std::vector<std::string> describe_defects(const ValidationReport& report);

/// Throws ValidationFailed unless report.valid(); the message starts with
/// `what` (e.g. "vessel 'cup'") and lists every defect with counts and examples.
void require_valid(const ValidationReport& report, const std::string& what);

}  // namespace fabmesh
