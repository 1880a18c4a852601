// What every binding of the module shares: text, errors at arguments,
// deprecations, enum members and plain values.

#include <string>

#include "python/bind.h"

namespace fabmesh_python {

py::str decoded(const std::string& text) {
  PyObject* s = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "surrogateescape");
  if (s == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(s);
}

py::object text_or_none(const std::string& text) {
  return text.empty() ? py::object(py::none()) : py::object(decoded(text));
}

void bad_argument(const std::string& argument, const std::string& message) {
  fabmesh::ErrorLocation at;
  at.key = argument;
  throw fabmesh::InputError(argument + ": " + message, at);
}

py::object json_loads(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

void deprecated(const std::string& old_name, const std::string& instead) {
  const std::string message =
      "fabmesh." + old_name + " is deprecated since fabmesh 0.4 and is removed in 0.5: use " + instead;
  if (PyErr_WarnEx(PyExc_DeprecationWarning, message.c_str(), 2) != 0) throw py::error_already_set();
}

py::object enum_member(const char* enum_name, const char* value) {
  return py::module_::import("fabmesh").attr(enum_name)(value);
}

py::object plain_value(const py::handle& value, const std::string& where) {
  if (value.is_none() || py::isinstance<py::bool_>(value) || py::isinstance<py::int_>(value) ||
      py::isinstance<py::float_>(value) || py::isinstance<py::str>(value)) {
    return py::reinterpret_borrow<py::object>(value);
  }
  if (py::hasattr(value, "tolist") && py::hasattr(value, "dtype")) {  // numpy scalars and arrays
    return plain_value(value.attr("tolist")(), where);
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    py::list out;
    std::size_t i = 0;
    for (const py::handle& item : value)
      out.append(plain_value(item, where + "[" + std::to_string(i++) + "]"));
    return std::move(out);
  }
  if (py::isinstance<py::dict>(value)) {
    py::dict out;
    for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(key))
        bad_argument(where, "keys must be texts, not " + py::repr(key).cast<std::string>());
      out[key] = plain_value(item, where + "." + key.cast<std::string>());
    }
    return std::move(out);
  }
  bad_argument(where, "must be a number, a text, a list or a dict (numpy values too), not " +
                          py::repr(value).cast<std::string>());
}

py::array_t<std::int64_t> index_array(const std::vector<fabmesh::Triangle>& triangles) {
  py::array_t<std::int64_t> out({static_cast<py::ssize_t>(triangles.size()), py::ssize_t{3}});
  std::int64_t* p = out.mutable_data();
  py::gil_scoped_release free;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (std::size_t k = 0; k < 3; ++k) p[3 * f + k] = triangles[f][k];
  }
  return out;
}

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

}  // namespace fabmesh_python
