#pragma once
// fabmesh's own optional modules: shared objects that hold what only some
// runs use (OpenCASCADE for STEP, lib3mf for 3MF, the HTTP server of the
// studio), loaded with dlopen the first time they are needed, so that every
// other run starts without loading those libraries. Each module exports one C
// function, `extern "C" const void* NAME()` (defined with exactly that type:
// it is called through it), returning a table of entry points whose first
// member is its interface version (`int abi`).

#include <string>

namespace fabmesh {

/// A module as this process found it: loaded once and never changed after
/// (its libraries stay mapped until the process ends).
struct ModuleLookup {
  const void* table = nullptr;  ///< what the entry function returned; null when not found
  std::string status;           ///< the path loaded, or every path tried and why each failed
};

/// The folder of the file that holds this code, its links resolved: the
/// program's own (/proc/self/exe) when the code is linked into the program,
/// the shared library's (libfabmesh, as the Python module loads it) when it
/// is in one. Never the working folder: a program started by a bare name
/// found on PATH, or through a symbolic link, finds its real folder. Empty
/// when neither can be told.
std::string folder_of_this_binary();

/// Looks for `file` (e.g. "fabmesh-step.so") where fabmesh installs its
/// modules, relative to the real location of the binary that holds this
/// code (folder_of_this_binary): LIBDIR/fabmesh from the program in bin/,
/// LIBDIR/fabmesh from the library in LIBDIR, and lib/fabmesh of the build
/// folder from any binary one folder below it. Calls `entry` there and keeps
/// the table when its first int is `abi`.
ModuleLookup find_module(const char* file, const char* entry, int abi);

/// The module's table, typed, looked up once per process (thread-safe).
/// Api's first member must be `int abi`.
template <class Api>
const ModuleLookup& module_of(const char* file, const char* entry, int abi) {
  static const ModuleLookup lookup = find_module(file, entry, abi);
  return lookup;
}

/// Throws MachineError (geometry/core/errors.h, exit code 5: the installation is
/// incomplete, not the input wrong) naming the module `file`, every place it
/// was looked for, and `what` needs it ("step: ...", "studio: ..."); `remedy`
/// ends the message. \throw MachineError
[[noreturn]] void throw_missing_module(const ModuleLookup& lookup, const std::string& file,
                                       const std::string& what, const std::string& remedy);

/// The module's table, typed; a module that is missing is an installation
/// fault. \throw MachineError (throw_missing_module)
template <class Api>
const Api& required_module(const char* file, const char* entry, int abi, const std::string& what,
                           const std::string& remedy) {
  const ModuleLookup& m = module_of<Api>(file, entry, abi);
  if (m.table == nullptr) throw_missing_module(m, file, what, remedy);
  return *static_cast<const Api*>(m.table);
}

}  // namespace fabmesh
