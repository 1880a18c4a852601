// `fabmesh.repair` and `fabmesh.repair_file` (docs/python.md): the library's
// repair over numpy arrays. Registered by module.cpp (register_repair).

#include <fabmesh/fabmesh.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <optional>
#include <string>

namespace py = pybind11;

namespace {

[[noreturn]] void bad_array(const char* argument, const std::string& message) {
  fabmesh::ErrorPlace place;
  place.key = argument;
  throw fabmesh::InputError(std::string(argument) + ": " + message, place);
}

/// `value` as a C-ordered (N, 3) array of T, or InputError naming the argument.
template <class T>
py::array_t<T, py::array::c_style> three_columns(const py::handle& value, const char* argument) {
  const py::array array = py::array::ensure(value);
  if (!array || array.ndim() != 2 || array.shape(1) != 3)
    bad_array(argument, "must be an array of shape (N, 3)");
  return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
}

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

py::dict repair(const py::handle& vertices, const py::handle& triangles, double max_deviation, bool wrap,
                std::optional<double> weld_distance, bool fill_holes, double max_seconds) {
  const auto v = three_columns<double>(vertices, "vertices");
  const auto t = three_columns<std::int64_t>(triangles, "triangles");
  fabmesh::MeshView view;
  view.vertices = v.data();
  view.vertex_count = static_cast<std::size_t>(v.shape(0));
  view.triangles = t.data();
  view.triangle_count = static_cast<std::size_t>(t.shape(0));
  const fabmesh::RepairOptions options =
      repair_options(max_deviation, wrap, weld_distance, fill_holes, max_seconds);
  fabmesh::RepairReport report;
  {
    py::gil_scoped_release free;
    report = fabmesh::repair(view, options);
  }
  py::dict result = py::module_::import("json").attr("loads")(report.json);
  py::array_t<double> out_vertices({static_cast<py::ssize_t>(report.mesh.vertices.size()), py::ssize_t{3}});
  if (!report.mesh.vertices.empty())
    std::memcpy(out_vertices.mutable_data(), report.mesh.vertices.data(),
                report.mesh.vertices.size() * sizeof(fabmesh::Point));
  py::array_t<std::int64_t> out_triangles(
      {static_cast<py::ssize_t>(report.mesh.triangles.size()), py::ssize_t{3}});
  for (std::size_t f = 0; f < report.mesh.triangles.size(); ++f) {
    for (std::size_t k = 0; k < 3; ++k) out_triangles.mutable_data()[3 * f + k] = report.mesh.triangles[f][k];
  }
  result["vertices"] = out_vertices;
  result["triangles"] = out_triangles;
  return result;
}

py::dict repair_file(const std::filesystem::path& path, const std::filesystem::path& output,
                     double max_deviation, bool wrap, std::optional<double> weld_distance, bool fill_holes,
                     double max_seconds) {
  const fabmesh::RepairOptions options =
      repair_options(max_deviation, wrap, weld_distance, fill_holes, max_seconds);
  std::string json;
  {
    py::gil_scoped_release free;
    json = fabmesh::repair_file(path, output, options);
  }
  return py::module_::import("json").attr("loads")(json);
}

}  // namespace

/// Adds fabmesh.repair and fabmesh.repair_file to `m`.
void register_repair(py::module_& m) {
  m.def("repair", &repair, py::arg("vertices"), py::arg("triangles"), py::kw_only(),
        py::arg("max_deviation") = 0.0, py::arg("wrap") = false, py::arg("weld_distance") = py::none(),
        py::arg("fill_holes") = true, py::arg("max_seconds") = 600.0,
        R"(Repairs a mesh given as arrays, as `fabmesh repair` does (docs/repair.md).

vertices: (N, 3) numbers; triangles: (M, 3) integer indices. Returns a dict:
"valid" (the result is valid for fabrication and within max_deviation),
"changed", "vertices" (K, 3) float64 and "triangles" (L, 3) int64 (the
result), "repairs" (each step with its places: face and vertex indices into
the arrays given, and points), "dropped_components", "components", "volume",
"area", "distance" ("bound": the proven two-sided distance), "unresolved"
(what could not be mended, with where), "before" and "after" (check's
facts). A mesh that cannot be mended is valid=False, not an exception.
max_deviation: refuse a larger change (0: no limit); wrap: replace the mesh
by an alpha wrap (lossy, always closed); weld_distance: None to choose it
from the data. Raises InputError for arrays of the wrong shape, an index out
of range, a non-finite coordinate or an empty mesh. The GIL is released.)");
  m.def("repair_file", &repair_file, py::arg("path"), py::arg("output"), py::kw_only(),
        py::arg("max_deviation") = 0.0, py::arg("wrap") = false, py::arg("weld_distance") = py::none(),
        py::arg("fill_holes") = true, py::arg("max_seconds") = 600.0,
        R"(Repairs a mesh file into `output` (.3mf, .stl, .obj, .ply, .off) exactly as
`fabmesh repair PATH -o OUTPUT --json`; returns its item as a dict ("exit_code" 0: written,
1: refused, nothing written). Raises InputError for an unreadable file.)");
}
