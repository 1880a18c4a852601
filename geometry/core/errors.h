#pragma once
// Typed exceptions. Everything a user can get wrong derives from InputError
// (exit code 2 at the command line); anything else escaping a stage is an
// internal error (exit code 3).

#include <stdexcept>
#include <string>

namespace fabmesh {

/// Bad input: a value out of range, a malformed file, geometry that cannot be
/// built as asked. The message names the offending value.
class InputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A numeric parameter outside its allowed range (or NaN/Inf).
/// Carries the parameter's name and the offending value.
class RangeError : public InputError {
 public:
  RangeError(std::string field, double value, const std::string& message)
      : InputError(message), field_(std::move(field)), value_(value) {}
  const std::string& field() const { return field_; }
  double value() const { return value_; }

 private:
  std::string field_;
  double value_;
};

/// Geometry that cannot be built as designed: a curve that does not close or
/// crosses itself, a declared continuity the joint contradicts, a wall too
/// thick for the profile. `where` names the segment, joint or hole.
class GeometryError : public InputError {
 public:
  GeometryError(std::string where, const std::string& message)
      : InputError(message), where_(std::move(where)) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

/// A work budget (triangles, samples) that the requested tolerance would exceed.
class BudgetError : public InputError {
 public:
  BudgetError(double requested, double budget, const std::string& message)
      : InputError(message), requested_(requested), budget_(budget) {}
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
  OutputError(std::string format, const std::string& message)
      : InputError(message), format_(std::move(format)) {}
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
