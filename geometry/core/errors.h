#pragma once
// Typed exceptions. Everything a user can get wrong derives from InputError
// (exit code 2 at the command line); anything else escaping a stage is an
// internal error (exit code 3).

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fabmesh {

/// Where in a design an error is, as data: geometry names the key path, io
/// adds where the design gives it (io/design/design.h, placed), the pipeline
/// formats the message from it (pipeline/failure.cpp).
struct ErrorLocation {
  /// The design key path whose value is at fault, as the design writes it:
  /// "profile", "holes[1]", "profile.segments[2]", "mould.key_clearance".
  /// Empty: none (the message says where it is, or nothing does).
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
  /// The same place as data, for callers that are not printing a message (the
  /// library): the file, and the 1-based line and column of the key in it (0
  /// when the value came from an override, is a default, or has no position).
  std::string file = {};
  int line = 0;
  int column = 0;
  /// The override that gave the value, as the user wrote it ("body.wall=2.5");
  /// empty when the file did.
  std::string override_text = {};
  /// The design does not write `key`: its default value is at fault.
  bool is_default = false;
};

/// How messages name `location`: "place: name", "path: key (default)" for a
/// key the design does not write, or just the name before io placed it.
std::string location_text(const ErrorLocation& location);

/// Bad input: a value out of range, a malformed file, geometry that cannot be
/// built as asked. The message names the offending value; its location, when
/// it has one, says where in the design (the message does not repeat it).
class InputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
  InputError(const std::string& message, ErrorLocation location)
      : std::invalid_argument(message), location_(std::move(location)) {}
  const ErrorLocation& location() const { return location_; }
  /// Replaces the location, for rethrowing the same error: a builder maps
  /// its geometry's key to the design's ("wall" -> "body.wall"), io places it.
  void set_location(ErrorLocation location) { location_ = std::move(location); }

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
  const std::string& field() const { return field_; }
  double value() const { return value_; }

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
  const std::string& where() const { return location().key; }
};

/// A work budget (triangles, samples) that the requested tolerance would exceed.
class BudgetError : public InputError {
 public:
  BudgetError(double requested, double budget, const std::string& message, ErrorLocation location = {})
      : InputError(message, std::move(location)), requested_(requested), budget_(budget) {}
  double requested() const { return requested_; }
  double budget() const { return budget_; }

 private:
  double requested_;
  double budget_;
};

/// A file that cannot be read or parsed. Carries the path and, where known,
/// the 1-based line and column (0 when unknown).
class FileError : public InputError {
 public:
  FileError(std::string path, int line, int column, const std::string& message)
      : InputError(message), path_(std::move(path)), line_(line), column_(column) {}
  /// The same at a design key (`location` has its key path and place as
  /// data; the message already names them).
  FileError(std::string path, int line, int column, const std::string& message, ErrorLocation location)
      : InputError(message, std::move(location)), path_(std::move(path)), line_(line), column_(column) {}
  const std::string& path() const { return path_; }
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  std::string path_;
  int line_;
  int column_;
};

/// An output file that cannot be made as asked, e.g. a quantization that
/// cannot hold the tolerance at these coordinates. The message says what to
/// change. The job skips that output (or fails, when the design asks).
class OutputError : public InputError {
 public:
  OutputError(std::string format, const std::string& message, ErrorLocation location = {})
      : InputError(message, std::move(location)), format_(std::move(format)) {}
  const std::string& format() const { return format_; }

 private:
  std::string format_;
};

/// A mesh that fails validation where a valid one is required (exit code 1).
class ValidationFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws RangeError unless `value` is finite and within [lo, hi].
void require_in_range(const std::string& field, double value, double lo, double hi);

/// Throws RangeError unless `value` is finite and > 0.
void require_positive(const std::string& field, double value);

}  // namespace fabmesh
