#pragma once
// Shared by the files of the Python module `fabmesh` (docs/python.md): the
// library's calls over numpy arrays, with the library's names and types
// (fabmesh::Result is fabmesh.Result, Unit is fabmesh.Unit). Each file binds
// one concept; module.cpp calls them in order.

#include <fabmesh/fabmesh.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace fabmesh_python {

namespace py = pybind11;

/// `text` as a Python str: a byte that is not UTF-8 (a file name from the
/// disk) kept as a surrogate escape, as os.fsdecode keeps it.
py::str decoded(const std::string& text);

/// decoded(text), or None for an empty text.
py::object text_or_none(const std::string& text);

/// Throws InputError at a call's argument (its key), "ARGUMENT: message".
[[noreturn]] void bad_argument(const std::string& argument, const std::string& message);

/// json.loads(text).
py::object json_loads(const std::string& text);

/// Warns (DeprecationWarning, at the caller) that `old_name` is deprecated
/// since 0.4 and removed in 0.5, naming what replaces it.
void deprecated(const std::string& old_name, const std::string& instead);

/// The member of the module's enum `enum_name` whose value is `value`
/// (fabmesh.Unit("mm")).
py::object enum_member(const char* enum_name, const char* value);

/// `value` as plain Python data JSON can write: numpy scalars and arrays as
/// numbers and (nested) lists, tuples as lists, dict keys as strings.
/// \throw InputError at `where` for anything else (an object())
py::object plain_value(const py::handle& value, const std::string& where);

/// Arrays of shape (rows, 3): the argument checked, as numpy holds it (C
/// order, no copy when it already is).
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

/// A (rows, N) array holding a copy of `rows`; the copy runs without the GIL.
template <std::size_t N, class T>
py::array_t<T> matrix(const std::vector<std::array<T, N>>& rows) {
  py::array_t<T> out({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)});
  T* data = out.mutable_data();
  py::gil_scoped_release free;
  if (!rows.empty()) std::memcpy(data, rows.front().data(), rows.size() * sizeof(rows.front()));
  return out;
}

/// Triangles as an int64 array of shape (M, 3); the copy runs without the GIL.
py::array_t<std::int64_t> index_array(const std::vector<fabmesh::Triangle>& triangles);

/// A Mesh holding copies of the checked arrays. \throw InputError ("vertices", "triangles")
fabmesh::Mesh mesh_of(const py::handle& vertices, const py::handle& triangles);

// The bindings, in the order module.cpp calls them.
void bind_errors(py::module_& m);   // errors.cpp: Error, InputError, MissingFileError, ...
void bind_enums(py::module_& m);    // enums.cpp: Unit, DefectKind, PartRole
void bind_designs(py::module_& m);  // designs.cpp: Design, Parameter, read_design, parse_design
void bind_meshes(py::module_& m);   // meshes.cpp: Mesh, ValidationReport, Defect, check, read/write
void bind_curves(py::module_& m);   // curves.cpp: Curve, tbezier, quasi_bspline, ..., fair
void bind_results(py::module_& m);  // results.cpp: Result, Part, OutputFile, build, optimize
void bind_repair(py::module_& m);   // repair.cpp: RepairReport, repair, repair_file

}  // namespace fabmesh_python
