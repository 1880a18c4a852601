// fabmesh's one error tree (<fabmesh/errors.h>) as Python exceptions of the
// same names: Error, InputError (a ValueError), MissingFileError (an
// InputError and a FileNotFoundError), ValidationFailed, MachineError (an
// OSError); EnvironmentError, MachineError's name before 0.4, stays as a
// deprecated alias (it shadowed the builtin).

#include "python/bind.h"

namespace fabmesh_python {
namespace {

PyObject* new_exception(py::module_& m, const char* name, const char* doc, PyObject* bases) {
  const std::string qualified = std::string("fabmesh.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases, nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

// Raises the module's exception class `name` for `e`, with the place of bad input as attributes.
void raise(const char* name, const fabmesh::Error& e, const fabmesh::ErrorLocation* at) {
  const py::object type = py::module_::import("fabmesh").attr(name);
  py::object exc = type(decoded(e.what()));
  exc.attr("exit_code") = e.exit_code();
  if (at != nullptr) {
    exc.attr("key") = text_or_none(at->key);
    exc.attr("file") = text_or_none(at->file);
    exc.attr("line") = at->line > 0 ? py::object(py::int_(at->line)) : py::none();
    exc.attr("column") = at->column > 0 ? py::object(py::int_(at->column)) : py::none();
    exc.attr("override") = text_or_none(at->override_text);
    exc.attr("is_default") = at->is_default;
    exc.attr("point") =
        at->point.empty() ? py::object(py::none()) : py::object(py::tuple(py::cast(at->point)));
  }
  PyErr_SetObject(type.ptr(), exc.ptr());
}

void translate(std::exception_ptr p) {
  if (!p) return;
  try {
    std::rethrow_exception(p);
  } catch (const fabmesh::MissingFileError& e) {
    raise("MissingFileError", e, &e.location());
  } catch (const fabmesh::InputError& e) {
    raise("InputError", e, &e.location());
  } catch (const fabmesh::ValidationFailed& e) {
    raise("ValidationFailed", e, nullptr);
  } catch (const fabmesh::MachineError& e) {
    raise("MachineError", e, nullptr);
  } catch (const fabmesh::Error& e) {
    raise("Error", e, nullptr);
  }
}

}  // namespace

void bind_errors(py::module_& m) {
  PyObject* error =
      new_exception(m, "Error",
                    "Any failure of a fabmesh call. `exit_code` is the command line's code for the same "
                    "failure (1 invalid mesh, 2 bad input, 3 internal error, 5 the machine).",
                    PyExc_Exception);
  const py::tuple input_bases = py::make_tuple(py::handle(error), py::handle(PyExc_ValueError));
  PyObject* input = new_exception(
      m, "InputError",
      "Bad input (exit code 2): a malformed design or mesh file, a value out of range, geometry that "
      "cannot be built as designed, arrays of the wrong shape. The message is the command line's. "
      "Attributes: key (the design key path or the argument), file, line, column (None when "
      "unknown), override (the override that gave the value), is_default, point (a model point "
      "near the problem, or None).",
      input_bases.ptr());
  const py::tuple missing_bases = py::make_tuple(py::handle(input), py::handle(PyExc_FileNotFoundError));
  new_exception(m, "MissingFileError",
                "A file that does not exist (a design, a template it reads, a mesh): an InputError and a "
                "FileNotFoundError.",
                missing_bases.ptr());
  new_exception(m, "ValidationFailed",
                "A mesh that is not valid for what it is asked for (exit code 1), e.g. Result.write of a "
                "design whose mesh is invalid.",
                error);
  const py::tuple machine_bases = py::make_tuple(py::handle(error), py::handle(PyExc_OSError));
  new_exception(m, "MachineError",
                "A fault of the machine, not of the input (exit code 5): disk full, I/O error, permission "
                "denied, a module of the installation missing.",
                machine_bases.ptr());
  py::register_exception_translator(&translate);
}

}  // namespace fabmesh_python
