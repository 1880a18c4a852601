// The one tree of fabmesh's errors: the program, the library (this file is
// also its public <fabmesh/errors.h>) and Python (the same names) throw and
// catch these. Everything a user can get wrong derives from InputError
// (exit code 2); a mesh that is not valid is ValidationFailed (1); a fault of
// the machine is MachineError (5); anything else escaping a stage is an
// internal error (3).
//
// Geometry throws with the key path of the argument or option at fault and a
// point near the problem; reading a design attaches where the design gives
// that key (file, line, column, or the -D override) once, and the command
// line formats the message from it (pipeline/failure.h).
//
// Self-contained (the standard library only, everything inline) and guarded
// by a macro rather than `#pragma once`: the library's sources see it under
// both of its names.
#ifndef FABMESH_ERRORS_H
#define FABMESH_ERRORS_H

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fabmesh {

/// Exit codes of the command line, the same for every command; every
/// error's exit_code() is one of them.
inline constexpr int kExitOk = 0;        ///< done, every mesh valid
inline constexpr int kExitInvalid = 1;   ///< a mesh is not valid (ValidationFailed)
inline constexpr int kExitBadInput = 2;  ///< bad input (InputError)
inline constexpr int kExitInternal = 3;  ///< an internal error
/// Writing failed for a reason of the machine, not of the input (MachineError:
/// disk full, I/O error, permission, an installed module missing): the same
/// command may succeed once that is fixed.
inline constexpr int kExitEnvironment = 5;

/// Any failure of fabmesh: its message, and the exit code the command line
/// gives the same failure.
class Error : public std::runtime_error {
 public:
  Error(const std::string& message, int exit_code) : std::runtime_error(message), exit_code_(exit_code) {}
  int exit_code() const noexcept { return exit_code_; }

 private:
  int exit_code_;
};

/// Where bad input is, as data: the key path geometry names, and where the
/// design (or file) gives it, once io has looked it up.
struct ErrorLocation {
  /// The design key path whose value is at fault, as the design writes it:
  /// "profile", "holes[1]", "profile.segments[2]", "mould.key_clearance";
  /// or a library call's argument ("vertices", "triangles"). Empty: none.
  std::string key = {};
  /// How the message names the place when that says more than the key:
  /// "patches[1] ('lid')", "profile.segments[2] (point 3)". Empty: the key.
  std::string name = {};
  /// A model point near the problem, (x, y) or (x, y, z); empty when there is none.
  std::vector<double> point = {};
  /// Where the design gives `key`, once io has looked it up: "path:line:column",
  /// "-D path=value" for an override, or the design's path when `is_default`.
  /// Empty: not looked up.
  std::string place = {};
  /// The same place as data: the file, and the 1-based line and column in it
  /// (0 when the value came from an override, is a default, or has no position).
  std::string file = {};
  int line = 0;
  int column = 0;
  /// The override that gave the value, as the user wrote it ("body.wall=2.5");
  /// empty when the file did.
  std::string override_text = {};
  /// The design does not write `key`: its default value is at fault.
  bool is_default = false;
};

/// Bad input (exit code 2): a value out of range, a malformed file, geometry
/// that cannot be built as asked. The message names the offending value; its
/// location, when it has one, says where (the message does not repeat it
/// inside fabmesh; the library's and Python's messages are the command
/// line's whole line).
class InputError : public Error {
 public:
  explicit InputError(const std::string& message) : Error(message, kExitBadInput) {}
  InputError(const std::string& message, ErrorLocation location)
      : Error(message, kExitBadInput), location_(std::move(location)) {}
  const ErrorLocation& location() const noexcept { return location_; }
  /// Replaces the location, for rethrowing the same error: a builder maps
  /// its geometry's key to the design's ("wall" -> "body.wall"), io places it.
  void set_location(ErrorLocation location) { location_ = std::move(location); }
  /// The key path at fault (location().key).
  const std::string& key() const noexcept { return location_.key; }
  /// The file at fault, and the 1-based line and column (0 when unknown).
  const std::string& file() const noexcept { return location_.file; }
  int line() const noexcept { return location_.line; }
  int column() const noexcept { return location_.column; }
  /// The same as location(), under its name before 0.4.
  const ErrorLocation& place() const noexcept { return location_; }

 private:
  ErrorLocation location_;
};

/// A numeric parameter outside its allowed range (or NaN/Inf).
/// Carries the parameter's name and the offending value (and, where the
/// parameter is a design key's, the location of that key).
class RangeError : public InputError {
 public:
  RangeError(std::string field, double value, const std::string& message, ErrorLocation location = {})
      : InputError(message, std::move(location)), field_(std::move(field)), value_(value) {}
  const std::string& field() const noexcept { return field_; }
  double value() const noexcept { return value_; }

 private:
  std::string field_;
  double value_;
};

/// Geometry that cannot be built as designed: a curve that does not close or
/// crosses itself, a declared continuity the joint contradicts, a wall too
/// thick for the profile. Its location names the key at fault (the curve,
/// hole, segment or option), with a point near the problem where there is one.
class GeometryError : public InputError {
 public:
  GeometryError(ErrorLocation location, const std::string& message)
      : InputError(message, std::move(location)) {}
  /// At the key path `key` (ErrorLocation::key).
  GeometryError(std::string key, const std::string& message)
      : GeometryError(ErrorLocation{std::move(key)}, message) {}
  /// The key path it is at (location().key).
  const std::string& where() const noexcept { return location().key; }
};

/// A work budget (triangles, samples) that the requested tolerance would exceed.
class BudgetError : public InputError {
 public:
  BudgetError(double requested, double budget, const std::string& message, ErrorLocation location = {})
      : InputError(message, std::move(location)), requested_(requested), budget_(budget) {}
  double requested() const noexcept { return requested_; }
  double budget() const noexcept { return budget_; }

 private:
  double requested_;
  double budget_;
};

/// A file that cannot be read or parsed. Its message names the file (and
/// the line, column and key where known); location() has them as data.
class FileError : public InputError {
 public:
  FileError(std::string path, int line, int column, const std::string& message)
      : FileError(std::move(path), line, column, message, ErrorLocation{}) {}
  /// The same at a design key (`location` has its key path and place).
  FileError(std::string path, int line, int column, const std::string& message, ErrorLocation location)
      : InputError(message, with_file(std::move(location), std::move(path), line, column)) {}
  /// The file (location().file).
  const std::string& path() const noexcept { return file(); }

 private:
  static ErrorLocation with_file(ErrorLocation at, std::string path, int line, int column) {
    if (at.file.empty()) at.file = std::move(path);
    if (at.line == 0) {
      at.line = line;
      at.column = column;
    }
    return at;
  }
};

/// A file that does not exist (a design, a DXF template, a mesh to check).
class MissingFileError : public FileError {
 public:
  using FileError::FileError;
};

/// An output file that cannot be made as asked, e.g. a quantization that
/// cannot hold the tolerance at these coordinates. The message says what to
/// change. The job skips that output (or fails, when the design asks).
class OutputError : public InputError {
 public:
  OutputError(std::string format, const std::string& message, ErrorLocation location = {})
      : InputError(message, std::move(location)), format_(std::move(format)) {}
  const std::string& format() const noexcept { return format_; }

 private:
  std::string format_;
};

/// A mesh that fails validation where a valid one is required (exit code 1).
class ValidationFailed : public Error {
 public:
  explicit ValidationFailed(const std::string& message) : Error(message, kExitInvalid) {}
};

/// A fault of the machine, not of the input (exit code 5): the disk is full,
/// an I/O error, permission denied, a file size limit, a module of the
/// installation missing. The same command may succeed once it is fixed.
class MachineError : public Error {
 public:
  explicit MachineError(const std::string& message) : MachineError("", 0, message) {}
  MachineError(std::string path, int error_number, const std::string& message)
      : Error(message, kExitEnvironment), path_(std::move(path)), error_(error_number) {}
  /// The file or folder at fault; empty when none.
  const std::string& path() const noexcept { return path_; }
  int error_number() const noexcept { return error_; }  ///< the errno; 0 when none

 private:
  std::string path_;
  int error_;
};

/// MachineError under its name before 0.4.
using EnvironmentError = MachineError;

}  // namespace fabmesh

#endif  // FABMESH_ERRORS_H
