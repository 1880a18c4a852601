// Designs: read from a file, from YAML text or from a dict, with overrides
// as a dict of values (numbers, texts, lists; numpy scalars and arrays too).

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "python/bind.h"

namespace fabmesh_python {
namespace {

// An override value as YAML text: JSON is YAML, so numbers, lists, texts and dicts keep their meaning.
std::string yaml_text(const py::handle& value, const std::string& where) {
  return py::module_::import("json").attr("dumps")(plain_value(value, where)).cast<std::string>();
}

fabmesh::Overrides overrides_of(const std::optional<py::dict>& overrides) {
  fabmesh::Overrides out;
  if (!overrides) return out;
  for (const auto& [key, value] : *overrides) {
    if (!py::isinstance<py::str>(key)) bad_argument("overrides", "keys must be texts such as 'body.wall'");
    const std::string name = key.cast<std::string>();
    out.push_back({name, yaml_text(value, "overrides." + name)});
  }
  return out;
}

fabmesh::Design read_design(const std::filesystem::path& path, const std::optional<py::dict>& overrides) {
  const fabmesh::Overrides o = overrides_of(overrides);
  py::gil_scoped_release free;
  return fabmesh::read_design(path, o);
}

// A design given as YAML text, or as a dict (written as the JSON text it is,
// which is YAML: errors name its lines as json.dumps(indent=2) lays them out).
fabmesh::Design parse_design(const py::handle& design, const std::optional<py::dict>& overrides,
                             const std::filesystem::path& source) {
  std::string text;
  if (py::isinstance<py::str>(design)) {
    text = design.cast<std::string>();
  } else if (py::isinstance<py::dict>(design)) {
    text = py::module_::import("json")
               .attr("dumps")(plain_value(design, "design"), py::arg("indent") = 2)
               .cast<std::string>();
  } else {
    bad_argument("design", "must be YAML text or a dict, not " + py::repr(design).cast<std::string>());
  }
  const fabmesh::Overrides o = overrides_of(overrides);
  py::gil_scoped_release free;
  return fabmesh::parse_design(text, o, source);
}

// 0.3's reader: one of path and text.
fabmesh::Design load_design(const std::optional<std::filesystem::path>& path,
                            const std::optional<std::string>& text,
                            const std::optional<py::dict>& overrides) {
  deprecated("load_design", "fabmesh.read_design(path) or fabmesh.parse_design(text or dict)");
  if (path.has_value() == text.has_value()) bad_argument("path", "give exactly one of path and text");
  return path ? read_design(*path, overrides) : parse_design(py::str(*text), overrides, "design.yaml");
}

}  // namespace

void bind_designs(py::module_& m) {
  py::class_<fabmesh::Parameter>(m, "Parameter",
                                 "One of a design's named parameters (`parameters:`), with the value used")
      .def_readonly("name", &fabmesh::Parameter::name)
      .def_readonly("value", &fabmesh::Parameter::value, "The value the design was read with")
      .def_readonly("min", &fabmesh::Parameter::min, "The declared minimum, or None")
      .def_readonly("max", &fabmesh::Parameter::max, "The declared maximum, or None")
      .def_readonly("step", &fabmesh::Parameter::step, "The declared step, or None")
      .def_readonly("description", &fabmesh::Parameter::description, "'' when none")
      .def_readonly("kind", &fabmesh::Parameter::kind, "'number', 'choice' or 'switch'")
      .def_readonly("text", &fabmesh::Parameter::text,
                    "A choice's value, or 'true' / 'false' for a switch; '' for a number")
      .def_readonly("choices", &fabmesh::Parameter::choices, "A choice's values (a list), [] otherwise")
      .def("__repr__", [](const fabmesh::Parameter& p) {
        const std::string shown =
            p.kind == "number" ? py::repr(py::float_(p.value)).cast<std::string>() : p.text;
        return "<fabmesh.Parameter " + p.name + " = " + shown + ">";
      });

  py::class_<fabmesh::Design>(m, "Design",
                              "A design, read and checked; immutable, safe to share between threads.")
      .def_property_readonly("kind", &fabmesh::Design::kind, "'vessel', 'countertop', 'surface' or 'curve'")
      .def_property_readonly("name", &fabmesh::Design::name, "The design's name (default: its file's stem)")
      .def_property_readonly(
          "units",
          [](const fabmesh::Design& d) { return enum_member("Unit", fabmesh::to_string(d.units())); },
          "The model unit, a Unit")
      .def_property_readonly("tolerance", &fabmesh::Design::tolerance,
                             "The proven deviation the mesh may have, model units")
      .def_property_readonly(
          "path", [](const fabmesh::Design& d) { return d.path().string(); },
          "The file it was read from (for text: the source given, 'design.yaml' by default)")
      .def_property_readonly("outputs", &fabmesh::Design::outputs, "The formats `fabmesh run` writes for it")
      .def_property_readonly("parameters", &fabmesh::Design::parameters,
                             "The design's named parameters (a list of Parameter), in the order declared")
      .def_property_readonly("parameter_set", &fabmesh::Design::parameter_set,
                             "The parameter set whose values were used ('' for none): the design's "
                             "`parameter_set`, or the override {'parameter_set': NAME}")
      .def_property_readonly("parameter_sets", &fabmesh::Design::parameter_sets,
                             "The names of the design's parameter sets (`parameter_sets:`), in file order")
      .def("__repr__", [](const fabmesh::Design& d) {
        return "<fabmesh.Design " + d.kind() + " '" + d.name() + "' from " + d.path().string() + ">";
      });

  const char* overrides_doc =
      "overrides: a dict {\"body.wall\": 0.25, \"profile.points[1]\": [1, 5]} with the meaning of "
      "`fabmesh run -D key=value`; values are numbers, texts, lists or dicts (numpy scalars and arrays "
      "too); a key that names a parameter the design declares ({\"height\": 12}) sets that parameter.";
  m.def("read_design", &read_design, py::arg("path"), py::arg("overrides") = py::none(),
        (std::string(
             "Reads the design file at path with overrides applied, as `fabmesh run PATH -D ...`.\n\n") +
         overrides_doc +
         "\nReturns a Design. Raises MissingFileError for a file that does not exist, InputError (with "
         "key, file, line, column) for a malformed or out-of-range value or an unknown key.")
            .c_str());
  m.def("parse_design", &parse_design, py::arg("design"), py::arg("overrides") = py::none(),
        py::arg("source") = std::filesystem::path("design.yaml"),
        (std::string("Reads a design from YAML text or from a dict of its keys, with overrides applied; "
                     "source names it in messages and is the folder its relative files are read from.\n\n") +
         overrides_doc + "\nReturns a Design. Raises InputError.")
            .c_str());
  m.def("load_design", &load_design, py::arg("path") = py::none(), py::kw_only(),
        py::arg("text") = py::none(), py::arg("overrides") = py::none(),
        "Deprecated since 0.4 (removed in 0.5): read_design(path) or parse_design(text).");
}

}  // namespace fabmesh_python
