#pragma once
// What the library throws. Every error derives from fabmesh::Error, which
// carries the exit code the command line gives the same failure, and the
// same message it prints after "fabmesh: error: ".

#include <stdexcept>
#include <string>
#include <utility>

namespace fabmesh {
namespace api {

/// Any failure of a fabmesh call. `exit_code()` is the command line's for
/// the same failure: 1 invalid mesh, 2 bad input, 3 internal error, 5 the
/// machine (disk full, permission).
class Error : public std::runtime_error {
 public:
  Error(const std::string& message, int exit_code) : std::runtime_error(message), exit_code_(exit_code) {}
  int exit_code() const noexcept { return exit_code_; }

 private:
  int exit_code_;
};

/// Where bad input is: the design key path, and where the design gives it.
struct ErrorPlace {
  /// The design key path at fault ("body.wall", "holes[1].segments[2]"), or
  /// the argument of a library call ("vertices", "triangles"); empty when none.
  std::string key;
  std::string file;  ///< the design or mesh file; empty for text and arrays
  int line = 0;      ///< 1-based; 0 when unknown (an override, a default, arrays)
  int column = 0;    ///< 1-based; 0 when unknown
  /// The override that gave the value ("body.wall=2.5"), when one did.
  std::string override_text;
  /// The design does not write `key`: its default value is at fault.
  bool is_default = false;
};

/// Bad input (exit code 2): a malformed design or mesh file, a value out of
/// range, geometry that cannot be built as designed, arrays of the wrong
/// shape. The message is the command line's; `place()` says where as data.
class InputError : public Error {
 public:
  InputError(const std::string& message, ErrorPlace place) : Error(message, 2), place_(std::move(place)) {}
  const ErrorPlace& place() const noexcept { return place_; }
  const std::string& key() const noexcept { return place_.key; }
  const std::string& file() const noexcept { return place_.file; }
  int line() const noexcept { return place_.line; }
  int column() const noexcept { return place_.column; }

 private:
  ErrorPlace place_;
};

/// A mesh that is not valid for what it is asked for (exit code 1), e.g.
/// write_mesh of a mesh that rounding to the file's numbers would break.
class ValidationFailed : public Error {
 public:
  explicit ValidationFailed(const std::string& message) : Error(message, 1) {}
};

/// Writing failed for a reason of the machine, not of the input (exit
/// code 5): the disk is full, an I/O error, permission denied.
class EnvironmentError : public Error {
 public:
  explicit EnvironmentError(const std::string& message) : Error(message, 5) {}
};

}  // namespace api
#ifndef FABMESH_BUILDING_LIBRARY
using namespace api;  // fabmesh::Design, fabmesh::build, ...
#endif
}  // namespace fabmesh
