#pragma once
// Line and token scanning for the text mesh formats (ASCII STL, OBJ, OFF,
// ASCII PLY), with errors that name the file and line.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace fabmesh {

/// Reads `data` line by line ('\n', '\r\n' or '\r' endings), counting lines
/// from 1. Every parse error is a FileError naming `name` and the line.
class TextScanner {
 public:
  /// \param data  the whole file (must outlive the scanner)
  /// \param name  the file's path, for messages
  /// \param first_line  the line number `data` starts at
  TextScanner(std::string_view data, std::string name, int first_line = 1);

  /// The next line without its ending; false at the end of the data.
  bool next_line(std::string_view& line);
  /// The next line that is not blank after removing a `comment` suffix
  /// (e.g. '#'; '\0' for none); false at the end of the data.
  bool next_content_line(std::string_view& line, char comment);
  /// The 1-based number of the line last returned (0 before the first).
  int line() const { return line_; }
  /// Offset in `data` of the first byte not yet returned as a line.
  std::size_t position() const { return pos_; }
  /// Bytes not yet returned as lines.
  std::size_t remaining() const { return data_.size() - pos_; }
  const std::string& name() const { return name_; }

  /// Throws FileError "NAME:LINE: message".
  [[noreturn]] void fail(const std::string& message) const;
  /// `token` as a finite double; fails naming `what` otherwise.
  double to_double(std::string_view token, const char* what) const;
  /// `token` as an integer; fails naming `what` otherwise.
  std::int64_t to_int(std::string_view token, const char* what) const;

 private:
  std::string_view data_;
  std::string name_;
  std::size_t pos_ = 0;
  int line_;
};

/// Removes and returns the first whitespace-separated token of `rest`
/// (empty when none is left).
std::string_view next_token(std::string_view& rest);

}  // namespace fabmesh
