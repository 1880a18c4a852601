#include "api/src/validation_report.h"

namespace fabmesh::api::detail {

DefectKind public_kind(fabmesh::Defect kind) {
  switch (kind) {
    case fabmesh::Defect::Empty:
      return DefectKind::Empty;
    case fabmesh::Defect::NonFiniteVertex:
      return DefectKind::NonFiniteVertex;
    case fabmesh::Defect::BoundaryEdge:
      return DefectKind::BoundaryEdge;
    case fabmesh::Defect::NonManifoldEdge:
      return DefectKind::NonManifoldEdge;
    case fabmesh::Defect::NonManifoldVertex:
      return DefectKind::NonManifoldVertex;
    case fabmesh::Defect::InconsistentOrientation:
      return DefectKind::InconsistentOrientation;
    case fabmesh::Defect::InsideOut:
      return DefectKind::InsideOut;
    case fabmesh::Defect::InvertedComponent:
      return DefectKind::InvertedComponent;
    case fabmesh::Defect::NestedSameOrientation:
      return DefectKind::NestedSameOrientation;
    case fabmesh::Defect::DegenerateFace:
      return DefectKind::DegenerateFace;
    case fabmesh::Defect::DuplicateFace:
      return DefectKind::DuplicateFace;
    case fabmesh::Defect::SelfIntersection:
      return DefectKind::SelfIntersection;
  }
  return DefectKind::Empty;
}

fabmesh::Defect internal_kind(DefectKind kind) {
  switch (kind) {
    case DefectKind::Empty:
      return fabmesh::Defect::Empty;
    case DefectKind::NonFiniteVertex:
      return fabmesh::Defect::NonFiniteVertex;
    case DefectKind::BoundaryEdge:
      return fabmesh::Defect::BoundaryEdge;
    case DefectKind::NonManifoldEdge:
      return fabmesh::Defect::NonManifoldEdge;
    case DefectKind::NonManifoldVertex:
      return fabmesh::Defect::NonManifoldVertex;
    case DefectKind::InconsistentOrientation:
      return fabmesh::Defect::InconsistentOrientation;
    case DefectKind::InsideOut:
      return fabmesh::Defect::InsideOut;
    case DefectKind::InvertedComponent:
      return fabmesh::Defect::InvertedComponent;
    case DefectKind::NestedSameOrientation:
      return fabmesh::Defect::NestedSameOrientation;
    case DefectKind::DegenerateFace:
      return fabmesh::Defect::DegenerateFace;
    case DefectKind::DuplicateFace:
      return fabmesh::Defect::DuplicateFace;
    case DefectKind::SelfIntersection:
      return fabmesh::Defect::SelfIntersection;
  }
  return fabmesh::Defect::Empty;
}

ValidationReport public_report(const fabmesh::ValidationReport& report, const nlohmann::ordered_json& json) {
  ValidationReport out;
  out.valid = report.valid();
  out.watertight = report.boundary_edges == 0 && report.non_manifold_edges == 0;
  out.manifold = report.non_manifold_edges == 0 && report.non_manifold_vertices == 0;
  out.oriented_outward = report.oriented_outward;
  out.self_intersecting = report.self_intersecting;
  out.vertices = report.vertices;
  out.triangles = report.triangles;
  out.components = report.components;
  out.boundary_edges = report.boundary_edges;
  out.non_manifold_edges = report.non_manifold_edges;
  out.non_manifold_vertices = report.non_manifold_vertices;
  out.degenerate_faces = report.degenerate_faces;
  out.genus = report.genus;
  out.volume = report.volume;
  out.area = report.area;
  for (const fabmesh::DefectReport& d : report.defects) {
    Defect defect{public_kind(d.kind), d.count, {}};
    for (const Vec3& p : d.examples) defect.examples.push_back({p.x(), p.y(), p.z()});
    out.defects.push_back(std::move(defect));
  }
  out.set_json(json.dump());
  return out;
}

ValidationReport file_report(const fabmesh::FileCheck& check, const nlohmann::ordered_json& json) {
  if (!check.readable) {
    ValidationReport out;
    out.error = check.failure.message;
    out.set_json(json.dump());
    return out;
  }
  if (!check.several()) return public_report(check.objects.front().report, json);
  ValidationReport out = public_report(check.objects.front().report, json);
  for (std::size_t i = 1; i < check.objects.size(); ++i) {
    const ValidationReport o = public_report(check.objects[i].report, {});
    out.watertight = out.watertight && o.watertight;
    out.manifold = out.manifold && o.manifold;
    out.oriented_outward = out.oriented_outward && o.oriented_outward;
    out.self_intersecting = out.self_intersecting || o.self_intersecting;
    out.vertices += o.vertices;
    out.triangles += o.triangles;
    out.components += o.components;
    out.boundary_edges += o.boundary_edges;
    out.non_manifold_edges += o.non_manifold_edges;
    out.non_manifold_vertices += o.non_manifold_vertices;
    out.degenerate_faces += o.degenerate_faces;
    out.genus.reset();  // of no one object
    out.volume += o.volume;
    out.area += o.area;
    out.defects.insert(out.defects.end(), o.defects.begin(), o.defects.end());
  }
  out.valid = check.valid();  // interpenetration is a note of the assembly, as the command line says
  return out;
}

}  // namespace fabmesh::api::detail
