// Meshes as numpy arrays: read and written in every format, and judged as
// `fabmesh check` judges files, the verdict a ValidationReport.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "python/bind.h"

namespace fabmesh_python {
namespace {

fabmesh::ValidationOptions validation_options(double weld_tolerance, double max_seconds) {
  fabmesh::ValidationOptions o;
  o.weld_tolerance = weld_tolerance;
  o.max_seconds = max_seconds;
  return o;
}

fabmesh::ValidationReport check(const py::handle& vertices, const py::handle& triangles,
                                double weld_tolerance, double max_seconds) {
  const auto v = rows_of_three<double>(vertices, "vertices");
  const auto t = rows_of_three<std::int64_t>(triangles, "triangles");
  fabmesh::MeshView view;
  view.vertices = v.data();
  view.vertex_count = static_cast<std::size_t>(v.shape(0));
  view.triangles = t.data();
  view.triangle_count = static_cast<std::size_t>(t.shape(0));
  py::gil_scoped_release free;
  return fabmesh::validate(view, validation_options(weld_tolerance, max_seconds));
}

fabmesh::ValidationReport check_file(const std::filesystem::path& path, double weld_tolerance,
                                     double max_seconds) {
  py::gil_scoped_release free;
  return fabmesh::check_file(path, validation_options(weld_tolerance, max_seconds));
}

fabmesh::Mesh read_mesh(const std::filesystem::path& path) {
  py::gil_scoped_release free;
  return fabmesh::read_mesh(path);
}

void write_mesh(const std::filesystem::path& path, const py::handle& vertices, const py::handle& triangles,
                const std::optional<std::string>& units) {
  fabmesh::Mesh mesh = mesh_of(vertices, triangles);
  fabmesh::WriteOptions options;
  if (units) options.units = fabmesh::unit_named(*units);
  py::gil_scoped_release free;
  fabmesh::write_mesh(path, mesh, options);
}

py::object units_of(const std::optional<fabmesh::Unit>& units) {
  return units ? enum_member("Unit", fabmesh::to_string(*units)) : py::none();
}

// 0.3's reports were dicts: a report still answers report["key"], with a warning.
py::object report_item(const fabmesh::ValidationReport& r, const std::string& key) {
  deprecated("ValidationReport[key]", "its attributes (report.valid, ...) or report.to_dict()[key]");
  return json_loads(r.to_json())[py::str(key)];
}

}  // namespace

void bind_meshes(py::module_& m) {
  py::class_<fabmesh::Defect>(m, "Defect", "One kind of defect found: its kind, how many, and a few places")
      .def_property_readonly(
          "kind",
          [](const fabmesh::Defect& d) { return enum_member("DefectKind", fabmesh::to_string(d.kind)); },
          "A DefectKind")
      .def_readonly("count", &fabmesh::Defect::count)
      .def_property_readonly(
          "examples", [](const fabmesh::Defect& d) { return matrix<3>(d.examples); },
          "A few places of it (edge midpoints, vertices or face centroids), shape (K, 3)")
      .def("__repr__", [](const fabmesh::Defect& d) {
        return "<fabmesh.Defect " + std::string(fabmesh::to_string(d.kind)) + " x" + std::to_string(d.count) +
               ">";
      });

  py::class_<fabmesh::ValidationReport>(
      m, "ValidationReport", "The verdict on one mesh, as `fabmesh check` gives it (docs/validity.md)")
      .def_readonly("valid", &fabmesh::ValidationReport::valid,
                    "Watertight, manifold, consistently oriented outward, no self-intersection")
      .def_readonly("watertight", &fabmesh::ValidationReport::watertight)
      .def_readonly("manifold", &fabmesh::ValidationReport::manifold)
      .def_readonly("oriented_outward", &fabmesh::ValidationReport::oriented_outward)
      .def_readonly("self_intersecting", &fabmesh::ValidationReport::self_intersecting)
      .def_readonly("vertices", &fabmesh::ValidationReport::vertices)
      .def_readonly("triangles", &fabmesh::ValidationReport::triangles)
      .def_readonly("components", &fabmesh::ValidationReport::components)
      .def_readonly("boundary_edges", &fabmesh::ValidationReport::boundary_edges)
      .def_readonly("non_manifold_edges", &fabmesh::ValidationReport::non_manifold_edges)
      .def_readonly("non_manifold_vertices", &fabmesh::ValidationReport::non_manifold_vertices)
      .def_readonly("degenerate_faces", &fabmesh::ValidationReport::degenerate_faces)
      .def_readonly("genus", &fabmesh::ValidationReport::genus, "When closed and manifold; else None")
      .def_readonly("volume", &fabmesh::ValidationReport::volume, "Signed enclosed volume")
      .def_readonly("area", &fabmesh::ValidationReport::area)
      .def_readonly("defects", &fabmesh::ValidationReport::defects, "A list of Defect")
      .def_property_readonly(
          "error", [](const fabmesh::ValidationReport& r) { return text_or_none(r.error); },
          "Why a file could not be read (check_file); None otherwise")
      .def("to_json", &fabmesh::ValidationReport::to_json,
           "The facts as one item of `fabmesh check --json` (docs/reports.md), as JSON text")
      .def(
          "to_dict", [](const fabmesh::ValidationReport& r) { return json_loads(r.to_json()); },
          "The facts as one item of `fabmesh check --json`, as a dict")
      .def("__getitem__", &report_item, py::arg("key"), "Deprecated since 0.4: report.to_dict()[key]")
      .def("__repr__", [](const fabmesh::ValidationReport& r) {
        return "<fabmesh.ValidationReport " + std::string(r.valid ? "valid" : "INVALID") + ", " +
               std::to_string(r.triangles) + " triangles>";
      });

  py::class_<fabmesh::Mesh>(
      m, "Mesh",
      "An indexed triangle mesh: vertices (N, 3) float64, triangles (M, 3) int64, units "
      "(a Unit, or None when the file states none); unpacks as (vertices, triangles, units)")
      .def_property_readonly("vertices", [](const fabmesh::Mesh& mesh) { return matrix<3>(mesh.vertices); })
      .def_property_readonly("triangles",
                             [](const fabmesh::Mesh& mesh) { return index_array(mesh.triangles); })
      .def_property_readonly("units", [](const fabmesh::Mesh& mesh) { return units_of(mesh.units); })
      .def("__len__", [](const fabmesh::Mesh&) { return 3; })
      .def("__iter__",
           [](const fabmesh::Mesh& mesh) {
             return py::iter(
                 py::make_tuple(matrix<3>(mesh.vertices), index_array(mesh.triangles), units_of(mesh.units)));
           })
      .def("__repr__", [](const fabmesh::Mesh& mesh) {
        return "<fabmesh.Mesh " + std::to_string(mesh.vertices.size()) + " vertices, " +
               std::to_string(mesh.triangles.size()) + " triangles>";
      });

  m.def("check", &check, py::arg("vertices"), py::arg("triangles"), py::kw_only(),
        py::arg("weld_tolerance") = 0.0, py::arg("max_seconds") = 600.0,
        R"(Validates a mesh given as arrays, as `fabmesh check` validates a file.

vertices: (N, 3) numbers; triangles: (M, 3) integer indices into vertices.
Returns a ValidationReport (an invalid mesh is a report with valid False,
never an exception; to_dict() gives the keys of one item of `fabmesh check
--json`). Raises InputError naming the argument for arrays of the wrong
shape or dtype, or an index out of range. The GIL is released meanwhile.)");
  m.def("check_file", &check_file, py::arg("path"), py::kw_only(), py::arg("weld_tolerance") = 0.0,
        py::arg("max_seconds") = 600.0,
        R"(Validates a mesh file exactly as `fabmesh check FILE --json`: returns a ValidationReport.

An unreadable file gives a report with valid False and its error.)");
  m.def("read_mesh", &read_mesh, py::arg("path"),
        "Reads a mesh file (STL, OBJ, PLY, OFF, 3MF, glTF/GLB, Draco) by its content, all its objects in one "
        "mesh: a Mesh (vertices (N, 3) float64, triangles (M, 3) int64, units or None), which unpacks as "
        "that tuple. Raises InputError. The GIL is released while reading and copying.");
  m.def(
      "write_mesh", &write_mesh, py::arg("path"), py::arg("vertices"), py::arg("triangles"), py::kw_only(),
      py::arg("units") = py::none(),
      "Writes a mesh in the format the path's extension names (.stl .obj .ply .off .3mf .glb .drc), all or "
      "nothing; units (default 'mm') is stated in 3MF and glTF. Nothing is validated, but a coordinate that "
      "is not finite is refused. Raises InputError, MachineError.");
}

}  // namespace fabmesh_python
