// `fabmesh.repair` and `fabmesh.repair_file` (docs/repair.md): the library's
// repair over numpy arrays, its report a RepairReport.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "python/bind.h"

namespace fabmesh_python {
namespace {

fabmesh::RepairOptions repair_options(double max_deviation, bool wrap, std::optional<double> weld_distance,
                                      bool fill_holes, double max_seconds) {
  fabmesh::RepairOptions o;
  o.max_deviation = max_deviation;
  o.wrap = wrap;
  o.weld_distance = weld_distance.value_or(-1.0);
  o.fill_holes = fill_holes;
  o.max_seconds = max_seconds;
  return o;
}

fabmesh::RepairReport repair(const py::handle& vertices, const py::handle& triangles, double max_deviation,
                             bool wrap, std::optional<double> weld_distance, bool fill_holes,
                             double max_seconds) {
  const auto v = rows_of_three<double>(vertices, "vertices");
  const auto t = rows_of_three<std::int64_t>(triangles, "triangles");
  fabmesh::MeshView view;
  view.vertices = v.data();
  view.vertex_count = static_cast<std::size_t>(v.shape(0));
  view.triangles = t.data();
  view.triangle_count = static_cast<std::size_t>(t.shape(0));
  const fabmesh::RepairOptions options =
      repair_options(max_deviation, wrap, weld_distance, fill_holes, max_seconds);
  py::gil_scoped_release free;
  return fabmesh::repair(view, options);
}

py::object repair_file(const std::filesystem::path& path, const std::filesystem::path& output,
                       double max_deviation, bool wrap, std::optional<double> weld_distance, bool fill_holes,
                       double max_seconds) {
  const fabmesh::RepairOptions options =
      repair_options(max_deviation, wrap, weld_distance, fill_holes, max_seconds);
  std::string json;
  {
    py::gil_scoped_release free;
    json = fabmesh::repair_file(path, output, options);
  }
  return json_loads(json);
}

}  // namespace

void bind_repair(py::module_& m) {
  py::class_<fabmesh::RepairReport>(m, "RepairReport",
                                    "What a repair did and got (docs/repair.md); to_dict() has every step "
                                    "with its places, the components dropped and why, before and after")
      .def_readonly("valid", &fabmesh::RepairReport::valid,
                    "The result is valid for fabrication and within max_deviation")
      .def_readonly("changed", &fabmesh::RepairReport::changed, "False: the input was valid already")
      .def_property_readonly(
          "vertices", [](const fabmesh::RepairReport& r) { return matrix<3>(r.mesh.vertices); },
          "The result's vertices, float64 (K, 3)")
      .def_property_readonly(
          "triangles", [](const fabmesh::RepairReport& r) { return index_array(r.mesh.triangles); },
          "The result's triangles, int64 (L, 3)")
      .def_readonly("distance", &fabmesh::RepairReport::distance,
                    "Proven bound of the two-sided distance between input and result")
      .def_readonly("weld_distance", &fabmesh::RepairReport::weld_distance,
                    "The border weld's distance (0: none)")
      .def_readonly("components_before", &fabmesh::RepairReport::components_before)
      .def_readonly("components_after", &fabmesh::RepairReport::components_after)
      .def_readonly("volume_before", &fabmesh::RepairReport::volume_before)
      .def_readonly("volume_after", &fabmesh::RepairReport::volume_after)
      .def_readonly("area_before", &fabmesh::RepairReport::area_before)
      .def_readonly("area_after", &fabmesh::RepairReport::area_after)
      .def_readonly("unresolved", &fabmesh::RepairReport::unresolved,
                    "What could not be mended, one line each with where")
      .def_readonly("after", &fabmesh::RepairReport::after, "The result's ValidationReport")
      .def("to_json", &fabmesh::RepairReport::to_json, "The `fabmesh repair --json` facts, as JSON text")
      .def(
          "to_dict", [](const fabmesh::RepairReport& r) { return json_loads(r.to_json()); },
          "The `fabmesh repair --json` facts, as a dict")
      .def("__repr__", [](const fabmesh::RepairReport& r) {
        return "<fabmesh.RepairReport " + std::string(r.valid ? "valid" : "NOT MENDED") + ", " +
               std::to_string(r.mesh.triangles.size()) + " triangles>";
      });
  m.def("repair", &repair, py::arg("vertices"), py::arg("triangles"), py::kw_only(),
        py::arg("max_deviation") = 0.0, py::arg("wrap") = false, py::arg("weld_distance") = py::none(),
        py::arg("fill_holes") = true, py::arg("max_seconds") = 600.0,
        R"(Repairs a mesh given as arrays, as `fabmesh repair` does (docs/repair.md).

vertices: (N, 3) numbers; triangles: (M, 3) integer indices. Returns a
RepairReport: .valid (the result is valid for fabrication and within
max_deviation), .changed, .vertices (K, 3) float64 and .triangles (L, 3)
int64 (the result), .distance (the proven two-sided distance), the
components, volumes and areas before and after, .unresolved (what could not
be mended, with where), .after (the result's ValidationReport), and
.to_dict() with every repair step and its places (face and vertex indices
into the arrays given, and points) and the components dropped. A mesh that
cannot be mended is valid=False, not an exception. max_deviation: refuse a
larger change (0: no limit); wrap: replace the mesh by an alpha wrap (lossy,
always closed); weld_distance: None to choose it from the data. Raises
InputError for arrays of the wrong shape, an index out of range, a
non-finite coordinate or an empty mesh. The GIL is released.)");
  m.def("repair_file", &repair_file, py::arg("path"), py::arg("output"), py::kw_only(),
        py::arg("max_deviation") = 0.0, py::arg("wrap") = false, py::arg("weld_distance") = py::none(),
        py::arg("fill_holes") = true, py::arg("max_seconds") = 600.0,
        R"(Repairs a mesh file into `output` (.3mf, .stl, .obj, .ply, .off) exactly as
`fabmesh repair PATH -o OUTPUT --json`; returns its item as a dict ("exit_code" 0: written,
1: refused, nothing written). Raises InputError for an unreadable file.)");
}

}  // namespace fabmesh_python
