// A design built as `fabmesh run` builds it: its Result (parts, curves, the
// files `run` writes, the report every command prints) and its outputs.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>
#include <vector>

#include "python/bind.h"

namespace fabmesh_python {
namespace {

// A build's result with the design it came from (for write and outputs).
struct BuiltDesign {
  fabmesh::Design design;
  fabmesh::Result result;
};

BuiltDesign build(const fabmesh::Design& design) {
  py::gil_scoped_release free;
  return BuiltDesign{design, fabmesh::build(design)};
}

py::object unit_of(fabmesh::Unit unit) { return enum_member("Unit", fabmesh::to_string(unit)); }

void bind_parts(py::module_& m) {
  py::class_<fabmesh::Part>(m, "Part", "One mesh of a Result: the design's own (its product) or a mould part")
      .def_readonly("name", &fabmesh::Part::name, "The design's name for its product; 'side-1', 'base' ...")
      .def_property_readonly(
          "role", [](const fabmesh::Part& p) { return enum_member("PartRole", fabmesh::to_string(p.role)); },
          "A PartRole")
      .def_property_readonly(
          "vertices", [](const fabmesh::Part& p) { return matrix<3>(p.mesh.vertices); },
          "float64 array of shape (N, 3), model units")
      .def_property_readonly(
          "triangles", [](const fabmesh::Part& p) { return index_array(p.mesh.triangles); },
          "int64 array of shape (M, 3): outward, counter-clockwise")
      .def_readonly("validation", &fabmesh::Part::validation,
                    "Its ValidationReport, with the builder's proofs")
      .def_property_readonly(
          "valid", [](const fabmesh::Part& p) { return p.validation.valid; }, "Valid for fabrication")
      .def("__repr__", [](const fabmesh::Part& p) {
        return "<fabmesh.Part " + std::string(fabmesh::to_string(p.role)) + " '" + p.name + "', " +
               std::to_string(p.mesh.triangles.size()) + " triangles>";
      });

  py::class_<fabmesh::OutputFile>(m, "OutputFile", "One file `fabmesh run` writes for the design")
      .def_property_readonly(
          "path", [](const fabmesh::OutputFile& f) { return f.path.string(); },
          "As run names it (under out/)")
      .def_readonly("format", &fabmesh::OutputFile::format, "'stl', '3mf', 'step', ...")
      .def_property_readonly(
          "units", [](const fabmesh::OutputFile& f) { return unit_of(f.units); },
          "The unit of its coordinates")
      .def_readonly("max_added_error", &fabmesh::OutputFile::max_added_error,
                    "How far writing moves any vertex at most, model units")
      .def_readonly("valid_as_written", &fabmesh::OutputFile::valid_as_written,
                    "Mesh outputs: the mesh as stored is proven valid; None for drawings and programs")
      .def_readonly("parts", &fabmesh::OutputFile::parts, "The parts it holds ([]: the design as a whole)")
      .def("__repr__",
           [](const fabmesh::OutputFile& f) { return "<fabmesh.OutputFile " + f.path.string() + ">"; });
}

void bind_result(py::module_& m) {
  py::class_<BuiltDesign>(m, "Result", "A design built and validated as `fabmesh run` builds it")
      .def_property_readonly(
          "valid", [](const BuiltDesign& r) { return r.result.valid; },
          "True when every part is valid for what the design is for")
      .def_property_readonly(
          "error", [](const BuiltDesign& r) { return r.result.error; }, "Why it is not valid; '' when it is")
      .def_property_readonly("name", [](const BuiltDesign& r) { return r.result.name; })
      .def_property_readonly("kind", [](const BuiltDesign& r) { return r.result.kind; })
      .def_property_readonly(
          "units", [](const BuiltDesign& r) { return unit_of(r.result.units); }, "The model unit, a Unit")
      .def_property_readonly("tolerance", [](const BuiltDesign& r) { return r.result.tolerance; })
      .def_property_readonly(
          "max_deviation", [](const BuiltDesign& r) { return r.result.max_deviation; },
          "Proven bound of the meshes against the exact shape, model units")
      .def_property_readonly(
          "parts", [](const BuiltDesign& r) { return r.result.parts; },
          "Its meshes, a list of Part: the product first, then a mould's parts")
      .def_property_readonly(
          "curves", [](const BuiltDesign& r) { return r.result.curves; }, "The design's curves (BuiltCurve)")
      .def_property_readonly(
          "files", [](const BuiltDesign& r) { return r.result.files; },
          "The files `fabmesh run` writes, a list of OutputFile (a valid result's)")
      .def_property_readonly(
          "skipped", [](const BuiltDesign& r) { return r.result.skipped; },
          "Outputs that cannot be made, each 'format: why'")
      .def_property_readonly(
          "warnings", [](const BuiltDesign& r) { return r.result.warnings; }, "What deserves a look")
      .def_property_readonly(
          "vertices", [](const BuiltDesign& r) { return matrix<3>(r.result.vertices); },
          "The product's vertices: float64 array of shape (N, 3), model units")
      .def_property_readonly(
          "triangles", [](const BuiltDesign& r) { return index_array(r.result.triangles); },
          "The product's triangles: int64 array of shape (M, 3), outward, counter-clockwise")
      .def_property_readonly(
          "validation", [](const BuiltDesign& r) { return r.result.validation; },
          "The product's ValidationReport")
      .def(
          "to_json", [](const BuiltDesign& r) { return r.result.to_json(); },
          "The design's item of `fabmesh run --json`, as JSON text")
      .def(
          "to_dict", [](const BuiltDesign& r) { return json_loads(r.result.to_json()); },
          "The design's item of `fabmesh run --json`, as a dict")
      .def_property_readonly(
          "report",
          [](const BuiltDesign& r) {
            deprecated("Result.report", "Result.to_dict()");
            return json_loads(r.result.to_json());
          },
          "Deprecated since 0.4: Result.to_dict()")
      .def(
          "write",
          [](const BuiltDesign& r, const std::filesystem::path& path) {
            py::gil_scoped_release free;
            fabmesh::write_output(r.design, path);
          },
          py::arg("path"),
          "Writes the output the path's extension names, the same bytes as `fabmesh run DESIGN -o path`. "
          "Raises InputError, ValidationFailed or MachineError.")
      .def(
          "outputs",
          [](const BuiltDesign& r, const std::filesystem::path& folder) {
            std::vector<std::filesystem::path> files;
            {
              py::gil_scoped_release free;
              files = fabmesh::write_outputs(r.design, folder);
            }
            std::vector<std::string> out;
            for (const auto& f : files) out.push_back(f.string());
            return out;
          },
          py::arg("folder"),
          "Writes every output of the design into folder, as `fabmesh run DESIGN -o folder/`; returns the "
          "paths.")
      .def("__repr__", [](const BuiltDesign& r) {
        return "<fabmesh.Result " + std::string(r.result.valid ? "valid" : "INVALID") + ", " +
               std::to_string(r.result.parts.size()) + " part" + (r.result.parts.size() == 1 ? "" : "s") +
               ", " + std::to_string(r.result.triangles.size()) + " triangles>";
      });
}

}  // namespace

void bind_results(py::module_& m) {
  bind_parts(m);
  bind_result(m);
  m.def("build", &build, py::arg("design"),
        R"(Builds and validates a design as `fabmesh run` does (same tolerance budget, same proofs).

Returns a Result: .parts (each a Part with its mesh and ValidationReport),
.vertices (N, 3) float64 and .triangles (M, 3) int64 of the product,
.valid, .files, .to_dict() (the `run --json` item), .write(path),
.outputs(folder). An invalid mesh gives valid=False and .error; a design
that cannot be built raises InputError. The GIL is released while building.)");
  m.def(
      "optimize",
      [](const fabmesh::Design& design) {
        std::string text;
        {
          py::gil_scoped_release free;
          text = fabmesh::optimize(design);
        }
        return json_loads(text);
      },
      py::arg("design"),
      "The fairest shape parameters of the design's curves, as `fabmesh optimize --json`: a list, one dict "
      "per curve. Raises InputError.");
}

}  // namespace fabmesh_python
