#include "io/design/points_csv.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <system_error>

#include "geometry/core/errors.h"
#include "io/design/number_limits.h"
#include "io/file.h"

namespace fabmesh {
namespace {

bool is_separator(char c) { return c == ',' || c == ';' || c == ' ' || c == '\t' || c == '\r'; }

// One number of a row: its value, its text and its 1-based column.
struct Field {
  double value = 0.0;
  std::string text;
  int column = 0;
};

// The fields of one row, at most three (a third is already an error); false
// when a field is not a number (`bad` says which). Values too large for a
// double come back infinite, to be reported as not finite.
bool parse_row(std::string_view row, std::vector<Field>& fields, Field& bad) {
  fields.clear();
  std::size_t i = 0;
  while (i < row.size() && fields.size() < 3) {
    while (i < row.size() && is_separator(row[i])) ++i;
    if (i == row.size()) break;
    std::size_t j = i;
    while (j < row.size() && !is_separator(row[j])) ++j;
    Field f{0.0, std::string(row.substr(i, j - i)), static_cast<int>(i) + 1};
    const char* first = f.text.data();
    const char* last = first + f.text.size();
    // from_chars reads a decimal number to the same double as strtod (both
    // round correctly), several times faster; what it does not read whole
    // ("+1", "0x1p3", a value out of range) is read by strtod, as before.
    auto [end, error] = std::from_chars(first, last, f.value);
    if (error != std::errc() || end != last) {
      char* stop = nullptr;
      f.value = std::strtod(first, &stop);
      end = stop;
    }
    if (f.text.empty() || end != last) {
      bad = std::move(f);
      return false;
    }
    fields.push_back(std::move(f));
    i = j;
  }
  return true;
}

// A field as messages show it: at most 40 bytes, control characters escaped
// ("\x00"): a NUL would end the message there.
std::string shown(const std::string& field) {
  std::string text;
  for (std::size_t i = 0; i < field.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(field[i]);
    if (c < 0x20 || c == 0x7f) {
      text += fmt::format("\\x{:02x}", c);
    } else {
      text += field[i];
    }
  }
  return field.size() <= 40 ? text : text + "...";
}

}  // namespace

std::vector<Vec2> parse_points_csv(std::string_view text, const std::string& path, int* header_line) {
  // Excel's "CSV UTF-8" starts with a byte order mark: not part of the first row.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  if (header_line != nullptr) *header_line = 0;
  std::vector<Vec2> points;
  std::vector<Field> fields;
  Field bad;
  int line = 0;
  bool header_allowed = true;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view row = text.substr(pos, end - pos);
    pos = end + 1;
    ++line;
    const std::size_t first = row.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || row[first] == '#') continue;
    if (!parse_row(row, fields, bad)) {
      if (header_allowed) {
        header_allowed = false;
        if (header_line != nullptr) *header_line = line;
        continue;
      }
      throw FileError(path, line, bad.column,
                      fmt::format("{}:{}:{}: '{}' is not a number", path, line, bad.column, shown(bad.text)));
    }
    header_allowed = false;
    if (fields.size() != 2) {
      const int column = fields.size() > 2 ? fields[2].column : static_cast<int>(first) + 1;
      throw FileError(path, line, column,
                      fmt::format("{}:{}:{}: expected two numbers x, y, got {}", path, line, column,
                                  fields.size() > 2    ? "more"
                                  : fields.size() == 1 ? "one"
                                                       : "none"));
    }
    for (std::size_t k = 0; k < 2; ++k) {
      if (!std::isfinite(fields[k].value)) {
        throw FileError(path, line, fields[k].column,
                        fmt::format("{}:{}:{}: {} = {} is not a finite number", path, line, fields[k].column,
                                    k == 0 ? "x" : "y", shown(fields[k].text)));
      }
      if (std::abs(fields[k].value) > kMaxDesignNumber) {
        throw FileError(
            path, line, fields[k].column,
            fmt::format("{}:{}:{}: {} = {} is too large: coordinates are at most {:g} in magnitude", path,
                        line, fields[k].column, k == 0 ? "x" : "y", shown(fields[k].text), kMaxDesignNumber));
      }
    }
    points.emplace_back(fields[0].value, fields[1].value);
    if (end == text.size()) break;
  }
  return points;
}

std::vector<Vec2> read_points_csv(const std::string& path, int* header_line) {
  constexpr std::size_t kMaxPointsFileBytes = 64u << 20;
  return parse_points_csv(read_file(path, kMaxPointsFileBytes, "points file"), path, header_line);
}

}  // namespace fabmesh
