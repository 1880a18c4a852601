// The Python module `fabmesh` (docs/python.md): the library's calls over
// numpy arrays and dicts. The GIL is released while fabmesh works, so builds
// of distinct designs run in parallel threads.

#include <fabmesh/fabmesh.h>
#include <malloc.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace py = pybind11;

void register_repair(py::module_& m);  // repair_bindings.cpp

namespace {

PyObject* new_exception(py::module_& m, const char* name, const char* doc, PyObject* bases) {
  const std::string qualified = std::string("fabmesh.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases, nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

// `text` as a Python str: a byte that is not UTF-8 (a file name from the disk) kept as a surrogate
// escape, as Python's own os.fsdecode keeps it, never a UnicodeDecodeError in place of ours.
py::str decoded(const std::string& text) {
  PyObject* s = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "surrogateescape");
  if (s == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(s);
}

py::object text_or_none(const std::string& text) {
  return text.empty() ? py::object(py::none()) : py::object(decoded(text));
}

// Raises the module's exception class `name` for `e`, with the place of bad input as attributes.
void raise(const char* name, const fabmesh::Error& e, const fabmesh::ErrorPlace* place) {
  const py::object type = py::module_::import("fabmesh").attr(name);
  py::object exc = type(decoded(e.what()));
  exc.attr("exit_code") = e.exit_code();
  if (place != nullptr) {
    exc.attr("key") = text_or_none(place->key);
    exc.attr("file") = text_or_none(place->file);
    exc.attr("line") = place->line > 0 ? py::object(py::int_(place->line)) : py::none();
    exc.attr("column") = place->column > 0 ? py::object(py::int_(place->column)) : py::none();
    exc.attr("override") = text_or_none(place->override_text);
    exc.attr("is_default") = place->is_default;
  }
  PyErr_SetObject(type.ptr(), exc.ptr());
}

void register_errors(py::module_& m) {
  PyObject* error =
      new_exception(m, "Error",
                    "Any failure of a fabmesh call. `exit_code` is the command line's code for the same "
                    "failure (1 invalid mesh, 2 bad input, 3 internal error, 5 the machine).",
                    PyExc_Exception);
  py::tuple input_bases = py::make_tuple(py::handle(error), py::handle(PyExc_ValueError));
  new_exception(m, "InputError",
                "Bad input (exit code 2): a malformed design or mesh file, a value out of range, "
                "geometry that cannot be built as designed, arrays of the wrong shape. The message is "
                "the command line's. Attributes: key (the design key path or the argument), file, "
                "line, column (None when unknown), override (the override that gave the value), "
                "is_default.",
                input_bases.ptr());
  new_exception(m, "ValidationFailed",
                "A mesh that is not valid for what it is asked for (exit code 1), e.g. "
                "Result.write of a design whose mesh is invalid.",
                error);
  py::tuple env_bases = py::make_tuple(py::handle(error), py::handle(PyExc_OSError));
  new_exception(m, "EnvironmentError",
                "Writing failed for a reason of the machine (exit code 5): disk full, I/O "
                "error, permission denied.",
                env_bases.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    try {
      std::rethrow_exception(p);
    } catch (const fabmesh::InputError& e) {
      raise("InputError", e, &e.place());
    } catch (const fabmesh::ValidationFailed& e) {
      raise("ValidationFailed", e, nullptr);
    } catch (const fabmesh::EnvironmentError& e) {
      raise("EnvironmentError", e, nullptr);
    } catch (const fabmesh::Error& e) {
      raise("Error", e, nullptr);
    }
  });
}

[[noreturn]] void bad_argument(const std::string& argument, const std::string& message) {
  fabmesh::ErrorPlace place;
  place.key = argument;
  throw fabmesh::InputError(argument + ": " + message, place);
}

py::object json_loads(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

// An override value as YAML text: JSON is YAML, so numbers, lists, strings and dicts keep their meaning.
std::string yaml_text(const py::handle& value) {
  return py::module_::import("json").attr("dumps")(value).cast<std::string>();
}

fabmesh::Overrides overrides_of(const std::optional<py::dict>& overrides) {
  fabmesh::Overrides out;
  if (!overrides) return out;
  for (const auto& [key, value] : *overrides) {
    if (!py::isinstance<py::str>(key)) bad_argument("overrides", "keys must be strings such as 'body.wall'");
    out.push_back({key.cast<std::string>(), yaml_text(value)});
  }
  return out;
}

fabmesh::Design load_design(const std::optional<std::filesystem::path>& path,
                            const std::optional<std::string>& text,
                            const std::optional<py::dict>& overrides) {
  if (path.has_value() == text.has_value()) bad_argument("path", "give exactly one of path and text");
  fabmesh::Overrides o = overrides_of(overrides);
  py::gil_scoped_release free;
  return path ? fabmesh::read_design(*path, o) : fabmesh::parse_design(*text, o);
}

// Arrays of shape (rows, 3): the argument checked, as numpy holds it (C order, no copy when it already is).
template <class T>
py::array_t<T, py::array::c_style> rows_of_three(const py::handle& value, const char* argument) {
  py::array array = py::array::ensure(value);
  if (!array) bad_argument(argument, "is not an array");
  if (array.ndim() != 2 || array.shape(1) != 3) {
    std::string shape;
    for (py::ssize_t i = 0; i < array.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(array.shape(i));
    bad_argument(argument, "must have shape (N, 3), not (" + shape + ")");
  }
  const char kind = array.dtype().kind();
  if (std::is_integral_v<T> && kind != 'i' && kind != 'u' && !(kind == 'f' && array.shape(0) == 0))
    bad_argument(argument,
                 std::string("must hold integers, not dtype ") + py::str(array.dtype()).cast<std::string>());
  if (!std::is_integral_v<T> && kind != 'f' && kind != 'i' && kind != 'u')
    bad_argument(argument,
                 std::string("must hold numbers, not dtype ") + py::str(array.dtype()).cast<std::string>());
  return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
}

fabmesh::ValidationOptions validation_options(double weld_tolerance, double max_seconds) {
  fabmesh::ValidationOptions o;
  o.weld_tolerance = weld_tolerance;
  o.max_seconds = max_seconds;
  return o;
}

py::object check(const py::handle& vertices, const py::handle& triangles, double weld_tolerance,
                 double max_seconds) {
  const auto v = rows_of_three<double>(vertices, "vertices");
  const auto t = rows_of_three<std::int64_t>(triangles, "triangles");
  fabmesh::MeshView view;
  view.vertices = v.data();
  view.vertex_count = static_cast<std::size_t>(v.shape(0));
  view.triangles = t.data();
  view.triangle_count = static_cast<std::size_t>(t.shape(0));
  fabmesh::ValidationReport report;
  {
    py::gil_scoped_release free;
    report = fabmesh::validate(view, validation_options(weld_tolerance, max_seconds));
  }
  return json_loads(report.json);
}

py::object check_file(const std::filesystem::path& path, double weld_tolerance, double max_seconds) {
  fabmesh::ValidationReport report;
  {
    py::gil_scoped_release free;
    report = fabmesh::check_file(path, validation_options(weld_tolerance, max_seconds));
  }
  return json_loads(report.json);
}

// A (rows, columns) float64 array holding a copy of `rows`.
template <std::size_t N, class T>
py::array_t<T> matrix(const std::vector<std::array<T, N>>& rows) {
  py::array_t<T> out({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)});
  if (!rows.empty()) std::memcpy(out.mutable_data(), rows.front().data(), rows.size() * sizeof(rows.front()));
  return out;
}

// A Mesh holding copies of the checked arrays.
fabmesh::Mesh mesh_of(const py::handle& vertices, const py::handle& triangles) {
  const auto v = rows_of_three<double>(vertices, "vertices");
  const auto t = rows_of_three<std::int64_t>(triangles, "triangles");
  fabmesh::Mesh mesh;
  mesh.vertices.resize(static_cast<std::size_t>(v.shape(0)));
  if (!mesh.vertices.empty())
    std::memcpy(mesh.vertices.data(), v.data(), mesh.vertices.size() * sizeof(fabmesh::Point));
  mesh.triangles.resize(static_cast<std::size_t>(t.shape(0)));
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::int64_t i = t.data()[3 * f + k];
      if (i < 0 || static_cast<std::size_t>(i) >= mesh.vertices.size())
        bad_argument("triangles", "triangle " + std::to_string(f) + " names vertex " + std::to_string(i) +
                                      ", not one of the " + std::to_string(mesh.vertices.size()) +
                                      " vertices");
      mesh.triangles[f][k] = static_cast<std::uint32_t>(i);
    }
  }
  return mesh;
}

// A build's result with the design it came from (for write and outputs).
struct Result {
  fabmesh::Design design;
  fabmesh::BuildResult built;
};

Result build(const fabmesh::Design& design) {
  py::gil_scoped_release free;
  return Result{design, fabmesh::build(design)};
}

py::array_t<std::int64_t> triangles_of(const Result& r) {
  const auto& t = r.built.triangles;
  py::array_t<std::int64_t> out({static_cast<py::ssize_t>(t.size()), py::ssize_t{3}});
  std::int64_t* p = out.mutable_data();
  for (std::size_t f = 0; f < t.size(); ++f) {
    for (std::size_t k = 0; k < 3; ++k) p[3 * f + k] = t[f][k];
  }
  return out;
}

// Curves: parameters as a float or an array of them.
template <class F>
py::object per_parameter(const py::handle& t, F&& f) {
  if (py::isinstance<py::float_>(t) || py::isinstance<py::int_>(t)) {
    const auto p = f(t.cast<double>());
    return py::array_t<double>(2, p.data());
  }
  const auto ts = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(t);
  if (!ts || ts.ndim() != 1) bad_argument("t", "must be a number or a 1-D array of numbers");
  py::array_t<double> out({ts.shape(0), py::ssize_t{2}});
  double* o = out.mutable_data();
  for (py::ssize_t i = 0; i < ts.shape(0); ++i) {
    const auto p = f(ts.data()[i]);
    o[2 * i] = p[0];
    o[2 * i + 1] = p[1];
  }
  return out;
}

std::vector<fabmesh::Point2> plane_points(const py::handle& points, const std::string& argument = "points") {
  py::array_t<double, py::array::c_style | py::array::forcecast> a =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if (!a || a.ndim() != 2 || a.shape(1) != 2) bad_argument(argument, "must have shape (N, 2)");
  std::vector<fabmesh::Point2> out(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {a.data()[2 * i], a.data()[2 * i + 1]};
  return out;
}

const char* continuity_name(fabmesh::Continuity c) {
  switch (c) {
    case fabmesh::Continuity::G0:
      return "G0";
    case fabmesh::Continuity::G1:
      return "G1";
    case fabmesh::Continuity::G2:
      return "G2";
    case fabmesh::Continuity::None:
      break;
  }
  return "none";
}

fabmesh::Continuity continuity_of(const py::handle& value, const std::string& argument) {
  if (py::isinstance<py::str>(value)) {
    const std::string name = value.cast<std::string>();
    if (name == "G0") return fabmesh::Continuity::G0;
    if (name == "G1") return fabmesh::Continuity::G1;
    if (name == "G2") return fabmesh::Continuity::G2;
  }
  bad_argument(argument, "must be 'G0', 'G1' or 'G2', got " + py::repr(value).cast<std::string>());
}

double number_of(const py::handle& value, const std::string& argument) {
  PyObject* number = nullptr;
  if (!py::isinstance<py::bool_>(value) && !py::isinstance<py::str>(value))
    number = PyNumber_Float(value.ptr());
  if (number == nullptr) {
    PyErr_Clear();
    bad_argument(argument, "must be a number, got " + py::repr(value).cast<std::string>());
  }
  const double v = PyFloat_AsDouble(number);
  Py_DECREF(number);
  return v;
}

// Each key of `dict` is one of `known`, or an InputError naming it.
void require_known_keys(const py::dict& dict, const std::vector<std::string>& known,
                        const std::string& where) {
  for (const auto& item : dict) {
    const std::string key = py::str(item.first).cast<std::string>();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      bad_argument(where + "." + key, "unknown key (known: " + list + ")");
    }
  }
}

py::dict dict_of(const py::handle& value, const std::string& argument) {
  if (!py::isinstance<py::dict>(value)) bad_argument(argument, "must be a dict");
  return py::reinterpret_borrow<py::dict>(value);
}

// One segment of fabmesh.composite, given with a design file's keys.
fabmesh::Segment segment_of(const py::handle& value, std::size_t i) {
  const std::string at = "segments[" + std::to_string(i) + "]";
  const py::dict d = dict_of(value, at);
  require_known_keys(d, {"family", "points", "lambda", "mu", "alpha", "join", "continuity"}, at);
  fabmesh::Segment s;
  if (d.contains("family")) {
    const std::string family = py::str(d["family"]).cast<std::string>();
    if (family == "tbezier") {
      s.family = fabmesh::SegmentFamily::TBezier;
    } else if (family == "hbezier") {
      s.family = fabmesh::SegmentFamily::HBezier;
    } else if (family == "line") {
      s.family = fabmesh::SegmentFamily::Line;
    } else {
      bad_argument(at + ".family", "must be 'tbezier', 'hbezier' or 'line', got '" + family + "'");
    }
  }
  if (!d.contains("points")) bad_argument(at + ".points", "is required");
  s.points = plane_points(d["points"], at + ".points");
  if (d.contains("lambda")) s.lambda = number_of(d["lambda"], at + ".lambda");
  if (d.contains("mu")) s.mu = number_of(d["mu"], at + ".mu");
  if (d.contains("alpha")) s.alpha = number_of(d["alpha"], at + ".alpha");
  if (d.contains("continuity")) s.continuity = continuity_of(d["continuity"], at + ".continuity");
  if (d.contains("join")) {
    const std::string where = at + ".join";
    const py::dict j = dict_of(d["join"], where);
    require_known_keys(j, {"continuity", "alpha", "beta", "k", "m"}, where);
    if (!j.contains("continuity")) bad_argument(where + ".continuity", "is required");
    fabmesh::Join join;
    join.continuity = continuity_of(j["continuity"], where + ".continuity");
    if (j.contains("alpha")) join.alpha = number_of(j["alpha"], where + ".alpha");
    if (j.contains("beta")) join.beta = number_of(j["beta"], where + ".beta");
    if (j.contains("k")) join.k = number_of(j["k"], where + ".k");
    if (j.contains("m")) join.m = number_of(j["m"], where + ".m");
    s.join = join;
  }
  return s;
}

fabmesh::Energy energy_of(const std::string& name) {
  if (name == "strain") return fabmesh::Energy::Strain;
  if (name == "curvature_variation") return fabmesh::Energy::CurvatureVariation;
  bad_argument("energy", "must be 'strain' or 'curvature_variation', got '" + name + "'");
}

py::list joints_of(const fabmesh::Curve& c) {
  py::list out;
  for (const fabmesh::Joint& j : c.joints()) {
    py::dict d;
    d["before"] = j.before;
    d["after"] = j.after;
    d["closing"] = j.closing;
    d["gap"] = j.gap;
    d["tangent_angle"] = j.tangent_angle;
    d["curvature_before"] = j.curvature_before;
    d["curvature_after"] = j.curvature_after;
    d["curvature_jump"] = j.curvature_jump;
    d["declared"] = continuity_name(j.declared);
    d["achieved"] = continuity_name(j.achieved);
    out.append(d);
  }
  return out;
}

py::object fairing_of(const fabmesh::Curve& c) {
  const std::optional<fabmesh::Fairing> f = c.fairing();
  if (!f) return py::none();
  py::dict d;
  d["energy"] = f->energy == fabmesh::Energy::Strain ? "strain" : "curvature_variation";
  d["before"] = f->energy_before;
  d["after"] = f->energy_after;
  return std::move(d);
}

}  // namespace

PYBIND11_MODULE(fabmesh, m) {
  // The program's allocation policy (pipeline/cli/main.cpp): glibc returns every freed block of
  // 32 MiB or more to the kernel and maps it afresh, so builds in two threads page-fault and
  // flush each other's TLBs; keeping blocks below 64 MiB in the heap made a 1e6-triangle check
  // about twice as fast in-process (bench/README.md, "Python module").
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  m.doc() =
      "fabmesh: exact curves (T-Bezier, quasi-cubic B-splines, H-Bezier) to proven-valid meshes and "
      "fabrication files, and validity checks of any mesh (docs/python.md).";
  m.attr("__version__") = fabmesh::version();
  register_errors(m);
  register_repair(m);

  py::class_<fabmesh::Parameter>(m, "Parameter",
                                 "One of a design's named parameters (`parameters:`), with the value used")
      .def_readonly("name", &fabmesh::Parameter::name)
      .def_readonly("value", &fabmesh::Parameter::value, "The value the design was read with")
      .def_readonly("min", &fabmesh::Parameter::min, "The declared minimum, or None")
      .def_readonly("max", &fabmesh::Parameter::max, "The declared maximum, or None")
      .def_readonly("step", &fabmesh::Parameter::step, "The declared step, or None")
      .def_readonly("description", &fabmesh::Parameter::description, "'' when none")
      .def("__repr__", [](const fabmesh::Parameter& p) {
        return "<fabmesh.Parameter " + p.name + " = " + py::repr(py::float_(p.value)).cast<std::string>() +
               ">";
      });

  py::class_<fabmesh::Design>(m, "Design",
                              "A design, read and checked; immutable, safe to share between threads.")
      .def_property_readonly("kind", &fabmesh::Design::kind, "'vessel', 'countertop', 'surface' or 'curve'")
      .def_property_readonly("name", &fabmesh::Design::name, "The design's name (default: its file's stem)")
      .def_property_readonly("units", &fabmesh::Design::units, "The model unit: 'mm', 'cm', 'm' or 'in'")
      .def_property_readonly("tolerance", &fabmesh::Design::tolerance,
                             "The proven deviation the mesh may have, model units")
      .def_property_readonly(
          "path", [](const fabmesh::Design& d) { return d.path().string(); },
          "The file it was read from (for text: 'design.yaml')")
      .def_property_readonly("outputs", &fabmesh::Design::outputs, "The formats `fabmesh run` writes for it")
      .def_property_readonly("parameters", &fabmesh::Design::parameters,
                             "The design's named parameters (a list of Parameter), in the order declared")
      .def("__repr__", [](const fabmesh::Design& d) {
        return "<fabmesh.Design " + d.kind() + " '" + d.name() + "' from " + d.path().string() + ">";
      });

  m.def("load_design", &load_design, py::arg("path") = py::none(), py::kw_only(),
        py::arg("text") = py::none(), py::arg("overrides") = py::none(),
        R"(Reads a design, from a file (path) or from YAML text (text=...), with overrides applied.

overrides: a dict {"body.wall": 0.25, "profile.points[1]": [1, 5]} with the
meaning of `fabmesh run -D key=value` (values as YAML/JSON); a key that names
a parameter the design declares ({"height": 12}) sets that parameter.
Returns a Design. Raises InputError (with key, file, line, column) for a
malformed or out-of-range value, an unknown key or an unreadable file.)");

  py::class_<fabmesh::BuiltCurve>(m, "BuiltCurve", "One of a design's curves as built")
      .def_readonly("key", &fabmesh::BuiltCurve::key,
                    "The design key: 'curve', 'profile', 'outline', 'holes[0]'")
      .def_property_readonly(
          "points", [](const fabmesh::BuiltCurve& c) { return matrix<2>(c.points); },
          "The sampled polyline, shape (K, 2), model units")
      .def_readonly("closed", &fabmesh::BuiltCurve::closed)
      .def_readonly("max_deviation", &fabmesh::BuiltCurve::max_deviation,
                    "Proven bound of the polyline against the exact curve, model units")
      .def_readonly("curve", &fabmesh::BuiltCurve::curve, "The exact curve, to evaluate");

  py::class_<Result>(m, "Result", "A design built and validated as `fabmesh run` builds it")
      .def_property_readonly(
          "valid", [](const Result& r) { return r.built.valid; },
          "True when the mesh is valid for what the design is for")
      .def_property_readonly(
          "vertices", [](const Result& r) { return matrix<3>(r.built.vertices); },
          "float64 array of shape (N, 3), model units (Design.units)")
      .def_property_readonly("triangles", &triangles_of,
                             "int64 array of shape (M, 3): outward, counter-clockwise")
      .def_property_readonly("units", [](const Result& r) { return r.built.units; })
      .def_property_readonly("tolerance", [](const Result& r) { return r.built.tolerance; })
      .def_property_readonly(
          "max_deviation", [](const Result& r) { return r.built.max_deviation; },
          "Proven bound of the mesh against the exact shape, model units")
      .def_property_readonly(
          "error", [](const Result& r) { return r.built.error; }, "Why the mesh is not valid; '' when it is")
      .def_property_readonly(
          "curves", [](const Result& r) { return r.built.curves; }, "The design's curves")
      .def_property_readonly(
          "report", [](const Result& r) { return json_loads(r.built.report_json); },
          "The design's item of `fabmesh run --json`, as a dict")
      .def_property_readonly(
          "validation", [](const Result& r) { return json_loads(r.built.validation.json); },
          "The validation facts, as in the report")
      .def(
          "write",
          [](const Result& r, const std::filesystem::path& path) {
            py::gil_scoped_release free;
            fabmesh::write_output(r.design, path);
          },
          py::arg("path"),
          "Writes the output the path's extension names, the same bytes as `fabmesh run DESIGN -o path`. "
          "Raises InputError, ValidationFailed or EnvironmentError.")
      .def(
          "outputs",
          [](const Result& r, const std::filesystem::path& folder) {
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
      .def("__repr__", [](const Result& r) {
        return "<fabmesh.Result " + std::string(r.built.valid ? "valid" : "INVALID") + ", " +
               std::to_string(r.built.vertices.size()) + " vertices, " +
               std::to_string(r.built.triangles.size()) + " triangles>";
      });

  m.def("build", &build, py::arg("design"),
        R"(Builds and validates a design as `fabmesh run` does (same tolerance budget, same proofs).

Returns a Result: .vertices (N, 3) float64, .triangles (M, 3) int64, .valid,
.report (dict), .write(path), .outputs(folder). An invalid mesh gives
valid=False and .error; a design that cannot be built raises InputError.
The GIL is released while building.)");

  m.def("check", &check, py::arg("vertices"), py::arg("triangles"), py::kw_only(),
        py::arg("weld_tolerance") = 0.0, py::arg("max_seconds") = 600.0,
        R"(Validates a mesh given as arrays, as `fabmesh check` validates a file.

vertices: (N, 3) numbers; triangles: (M, 3) integer indices into vertices.
Returns a dict with the keys of one item of `fabmesh check --json` (file,
format and units None); an invalid mesh is {"valid": False, ...}, never an
exception. Raises InputError naming the argument for arrays of the wrong
shape or dtype, or an index out of range.)");

  m.def("check_file", &check_file, py::arg("path"), py::kw_only(), py::arg("weld_tolerance") = 0.0,
        py::arg("max_seconds") = 600.0,
        R"(Validates a mesh file exactly as `fabmesh check FILE --json`; returns its item as a dict.

An unreadable file gives {"file": ..., "error": ..., "exit_code": 2, "valid": False}.)");

  m.def(
      "read_mesh",
      [](const std::filesystem::path& path) {
        fabmesh::Mesh mesh;
        {
          py::gil_scoped_release free;
          mesh = fabmesh::read_mesh(path);
        }
        py::array_t<std::int64_t> triangles(
            {static_cast<py::ssize_t>(mesh.triangles.size()), py::ssize_t{3}});
        for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
          for (std::size_t k = 0; k < 3; ++k) triangles.mutable_data()[3 * f + k] = mesh.triangles[f][k];
        }
        return py::make_tuple(matrix<3>(mesh.vertices), triangles, text_or_none(mesh.units));
      },
      py::arg("path"),
      "Reads a mesh file (STL, OBJ, PLY, OFF, 3MF, glTF/GLB, Draco) by its content, all its objects in one "
      "mesh: returns (vertices (N, 3) float64, triangles (M, 3) int64, units or None). Raises InputError.");
  m.def(
      "write_mesh",
      [](const std::filesystem::path& path, const py::handle& vertices, const py::handle& triangles,
         const std::optional<std::string>& units) {
        fabmesh::Mesh mesh = mesh_of(vertices, triangles);
        fabmesh::WriteOptions options;
        options.units = units.value_or("");
        py::gil_scoped_release free;
        fabmesh::write_mesh(path, mesh, options);
      },
      py::arg("path"), py::arg("vertices"), py::arg("triangles"), py::kw_only(),
      py::arg("units") = py::none(),
      "Writes a mesh in the format the path's extension names (.stl .obj .ply .off .3mf .glb .drc), all or "
      "nothing; units (default 'mm') is stated in 3MF and glTF. Nothing is validated. Raises InputError, "
      "EnvironmentError.");

  py::class_<fabmesh::Curve>(
      m, "Curve",
      "A composite plane curve of n segments, parameter t in [0, n]: segment floor(t) at "
      "t - floor(t)")
      .def_property_readonly("segments", &fabmesh::Curve::segments)
      .def_property_readonly("closed", &fabmesh::Curve::closed)
      .def(
          "evaluate",
          [](const fabmesh::Curve& c, const py::handle& t) {
            return per_parameter(t, [&](double s) { return c.point(s); });
          },
          py::arg("t"), "The point at t (a float: shape (2,); an array of K parameters: shape (K, 2))")
      .def(
          "derivative",
          [](const fabmesh::Curve& c, const py::handle& t, int order) {
            return per_parameter(t, [&](double s) { return c.derivative(s, order); });
          },
          py::arg("t"), py::arg("order") = 1, "The derivative of order 1, 2 or 3 with respect to t")
      .def(
          "curvature",
          [](const fabmesh::Curve& c, const py::handle& t) -> py::object {
            if (py::isinstance<py::float_>(t) || py::isinstance<py::int_>(t))
              return py::float_(c.curvature(t.cast<double>()));
            const auto ts = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(t);
            if (!ts || ts.ndim() != 1) bad_argument("t", "must be a number or a 1-D array of numbers");
            py::array_t<double> out(ts.shape(0));
            for (py::ssize_t i = 0; i < ts.shape(0); ++i) out.mutable_data()[i] = c.curvature(ts.data()[i]);
            return std::move(out);
          },
          py::arg("t"), "Signed curvature at t (positive turning left), 1 / model units")
      .def(
          "sample",
          [](const fabmesh::Curve& c, double tolerance) {
            fabmesh::SampledCurve s;
            {
              py::gil_scoped_release free;
              s = c.sample(tolerance);
            }
            return py::make_tuple(matrix<2>(s.points), s.max_deviation);
          },
          py::arg("tolerance"),
          "Samples the curve within tolerance: returns (points of shape (K, 2), the proven bound achieved)")
      .def_property_readonly("joints", &joints_of,
                             "Every joint, measured on the exact curve: a list of dicts with before, after "
                             "(segment indices), closing, gap (model units), tangent_angle (radians), "
                             "curvature_before, curvature_after, curvature_jump (relative), declared and "
                             "achieved ('G0', 'G1', 'G2' or 'none')")
      .def_property_readonly("fairing", &fairing_of,
                             "For a curve made by fabmesh.fair (or faired by its design): {'energy': "
                             "'strain' or 'curvature_variation', 'before': ..., 'after': ...}; else None")
      .def("__repr__", [](const fabmesh::Curve& c) {
        return "<fabmesh.Curve of " + std::to_string(c.segments()) + " segment" +
               (c.segments() == 1 ? "" : "s") + ">";
      });

  m.def(
      "tbezier",
      [](const py::handle& points, double lam, double mu) {
        return fabmesh::tbezier(plane_points(points), lam, mu);
      },
      py::arg("points"), py::arg("lam") = 0.0, py::arg("mu") = 0.0,
      "Cubic T-Bezier segments through 3n + 1 control points (shape (3n + 1, 2)), shape parameters lam, mu "
      "in "
      "[-2, 1]. Raises InputError.");
  m.def(
      "quasi_bspline",
      [](const py::handle& points, const std::optional<std::vector<double>>& lambdas) {
        return fabmesh::quasi_bspline(plane_points(points), lambdas.value_or(std::vector<double>{}));
      },
      py::arg("points"), py::arg("lambdas") = py::none(),
      "A quasi-cubic B-spline with control points p0..pn (shape (n + 1, 2), n >= 2) and shape parameters "
      "lambda_1..lambda_{n-1} in [-8, 1] (None: all 0). Raises InputError.");
  m.def(
      "hbezier",
      [](const py::handle& points, double alpha, double lam, double mu) {
        return fabmesh::hbezier(plane_points(points), alpha, lam, mu);
      },
      py::arg("points"), py::arg("alpha") = 1.0, py::arg("lam") = 0.0, py::arg("mu") = 0.0,
      "Generalized cubic H-Bezier segments through 3n + 1 control points, alpha in (0, 10]. Raises "
      "InputError.");
  m.def(
      "composite",
      [](const py::sequence& segments, bool closed, const std::string& closing) {
        std::vector<fabmesh::Segment> list;
        for (std::size_t i = 0; i < segments.size(); ++i) list.push_back(segment_of(segments[i], i));
        const fabmesh::Continuity close = continuity_of(py::str(closing), "closing");
        py::gil_scoped_release free;
        return fabmesh::composite(list, closed, close);
      },
      py::arg("segments"), py::arg("closed") = false, py::arg("closing") = "G0",
      R"(A composite curve of T-Bezier, H-Bezier and line segments, each starting where the
previous one ends: the segments of a design file's composite curve, as dicts with
the same keys (docs/design-files.md):

  family      'tbezier' (default), 'hbezier' or 'line'
  points      (K, 2): a cubic's 4 control points, or after a join only the free ones
              (G0: 3, G1: 2, G2: 1); a line's [from, to] when first, else [to]
  lambda, mu  shape parameters (T-Bezier in [-2, 1])
  alpha       H-Bezier's hyperbolic parameter in (0, 10]
  join        {'continuity': 'G0'/'G1'/'G2', 'alpha', 'beta' (T-Bezier), 'k', 'm' (H-Bezier)}:
              the leading control points computed from the previous segment
  continuity  without a join: the continuity declared with the previous segment, verified

closed: the curve must end where it starts (a join on the first segment joins it to
the last); closing: the continuity declared for the closing joint. Raises InputError
naming the segment ('segments[1].join.k').)");
  m.def(
      "fair",
      [](const fabmesh::Curve& curve, const std::string& energy, const std::optional<std::string>& keeps) {
        const fabmesh::Energy e = energy_of(energy);
        std::optional<fabmesh::Continuity> k;
        if (keeps) k = continuity_of(py::str(*keeps), "keeps");
        py::gil_scoped_release free;
        return fabmesh::fair(curve, e, k);
      },
      py::arg("curve"), py::arg("energy") = "curvature_variation", py::arg("keeps") = py::none(),
      "The curve with the shape parameters that minimise the energy ('strain' or 'curvature_variation'), "
      "its control points kept: a quasi-cubic B-spline's lambdas, or each T-Bezier segment's lambda and mu "
      "(curvature_variation only). A joint may not fall below its declared continuity, or below keeps "
      "('G0', 'G1', 'G2') when given. The result's .fairing gives the energy before and after. Raises "
      "InputError (key 'energy' or 'keeps').");
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
      "per "
      "curve. Raises InputError.");
}
