// The Python module `fabmesh` (docs/python.md): the library's calls over
// numpy arrays, with its names and types. The GIL is released while fabmesh
// works, so builds of distinct designs run in parallel threads. One file per
// concept (python/bind.h lists them); this one makes the module.

#include <malloc.h>

#include <string>

#include "python/bind.h"

namespace {

namespace py = pybind11;

// Names of 0.3 kept for one minor version (PEP 562's module __getattr__).
py::object deprecated_name(py::module_ m, const std::string& name) {
  if (name == "EnvironmentError") {
    fabmesh_python::deprecated("EnvironmentError", "fabmesh.MachineError (the name shadowed the builtin)");
    return m.attr("MachineError");
  }
  throw py::attribute_error("module 'fabmesh' has no attribute '" + name + "'");
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
  fabmesh_python::bind_errors(m);
  fabmesh_python::bind_enums(m);
  fabmesh_python::bind_designs(m);
  fabmesh_python::bind_meshes(m);
  fabmesh_python::bind_curves(m);
  fabmesh_python::bind_results(m);
  fabmesh_python::bind_repair(m);
  m.def(
      "__getattr__", [m](const std::string& name) { return deprecated_name(m, name); }, py::arg("name"));
}
