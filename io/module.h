#pragma once
// fabmesh's own optional modules: shared objects that hold what only some
// runs use (OpenCASCADE for STEP, lib3mf for 3MF, the HTTP server of the
// studio), loaded with dlopen the first time they are needed, so that every
// other run starts without loading those libraries. Each module exports one C
// function returning a table of entry points whose first member is its
// interface version (`int abi`).

#include <string>

namespace fabmesh {

/// A module as this process found it: loaded once and never changed after
/// (its libraries stay mapped until the process ends).
struct ModuleLookup {
  const void* table = nullptr;  ///< what the entry function returned; null when not found
  std::string status;           ///< the path loaded, or every path tried and why each failed
};

/// Looks for `file` (e.g. "fabmesh-step.so") where fabmesh installs its
/// modules, relative to the binary that holds this code: LIBDIR/fabmesh from
/// the program in bin/, LIBDIR/fabmesh from the library in LIBDIR, and
/// lib/fabmesh of the build folder from any binary one folder below it.
/// Calls `entry` there and keeps the table when its first int is `abi`.
ModuleLookup find_module(const char* file, const char* entry, int abi);

/// The module's table, typed, looked up once per process (thread-safe).
/// Api's first member must be `int abi`.
template <class Api>
const ModuleLookup& module_of(const char* file, const char* entry, int abi) {
  static const ModuleLookup lookup = find_module(file, entry, abi);
  return lookup;
}

}  // namespace fabmesh
