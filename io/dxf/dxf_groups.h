#pragma once
// The text of an ASCII DXF file as its group code / value pairs, read
// strictly: lines of any length, a code line that is an integer, a value line
// after every code, numbers that parse whole and are finite. Every refusal
// names the file, the line and the group code.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace fabmesh {

/// One group of a DXF text.
struct DxfGroup {
  int code = 0;
  std::string_view value;  ///< the value line without surrounding spaces, tabs and carriage return
  std::size_t line = 0;    ///< the 1-based line of the group code (its value is on the next)
};

/// `value` as a finite number, when the whole of it is one (a sign, digits,
/// a point, an exponent: "1000abc", "1000,0", "inf", "nan" and "1e999" are not).
std::optional<double> dxf_number(std::string_view value);

/// `value` as a whole number, when the whole of it is one.
std::optional<long long> dxf_integer(std::string_view value);

/// Reads a DXF text group by group, in order. Holds views into `bytes`,
/// which must outlive it.
class DxfGroupReader {
 public:
  /// `path` names the file in messages.
  DxfGroupReader(std::string_view bytes, std::string path);

  /// Reads the next group into `group`; false at the end of the text (a
  /// last empty line is no group). The first group must be a comment (999)
  /// or `0 SECTION`. \throw FileError naming the line: a code line that is
  /// not an integer (for the first line: "not a DXF drawing"), a file that
  /// starts otherwise, a code without its value line (the file is cut)
  bool next(DxfGroup& group);

  /// Throws FileError "path:line: what: group CODE: 'VALUE' is not KIND"
  /// ("a finite number", "a whole number") at the group's value line. \throw FileError
  [[noreturn]] void bad_value(const DxfGroup& group, std::string_view what, std::string_view kind) const;

  /// Throws FileError "path:line: why". \throw FileError
  [[noreturn]] void fail(std::size_t line, const std::string& why) const;

  /// The file's name in messages.
  const std::string& path() const { return path_; }
  /// How many lines the text has (a bound on any count it announces).
  std::size_t lines() const { return lines_; }
  /// The line last read (the value line of the last group).
  std::size_t line() const { return line_; }

 private:
  std::string_view next_line();

  std::string_view bytes_;
  std::string path_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
  std::size_t lines_ = 0;
  bool first_ = true;
};

}  // namespace fabmesh
