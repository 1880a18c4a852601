#pragma once
// Where one instance of a defect is, as indices: the faces and vertices
// involved, so that a report can list them and a picture can mark them.

#include <cstdint>
#include <vector>

namespace fabmesh {

/// One instance of a defect (a boundary edge, a pair of intersecting faces,
/// a component facing inward ...) as indices into the validated soup.
/// Per kind (validate.h's Defect):
/// - NonFiniteVertex: the vertex; no face.
/// - BoundaryEdge, NonManifoldEdge, InconsistentOrientation: the edge's two
///   vertices (ascending) and its faces (ascending).
/// - NonManifoldVertex: the vertex and every face around it.
/// - DegenerateFace: the face and its corners (as the face lists them).
/// - DuplicateFace: the faces with the same three vertices (ascending) and those vertices.
/// - SelfIntersection: the two faces and their corners.
/// - InvertedComponent, NestedSameOrientation: the component's lowest vertex and all its faces.
/// - Empty, InsideOut: the whole mesh; no location is listed.
struct DefectLocation {
  std::vector<std::uint32_t> faces;
  std::vector<std::uint32_t> vertices;
};

}  // namespace fabmesh
