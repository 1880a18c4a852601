#include "io/design/points_csv.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "geometry/core/errors.h"
#include "io/file.h"

namespace fabmesh {
namespace {

bool is_separator(char c) { return c == ',' || c == ';' || c == ' ' || c == '\t' || c == '\r'; }

// The numbers of one row; false when a field is not a number.
bool parse_row(std::string_view row, std::vector<double>& values, std::string& bad) {
  values.clear();
  std::size_t i = 0;
  while (i < row.size()) {
    while (i < row.size() && is_separator(row[i])) ++i;
    if (i == row.size()) break;
    std::size_t j = i;
    while (j < row.size() && !is_separator(row[j])) ++j;
    const std::string field(row.substr(i, j - i));
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(field.c_str(), &end);
    if (end != field.c_str() + field.size() || errno == ERANGE) {
      bad = field;
      return false;
    }
    values.push_back(v);
    i = j;
  }
  return true;
}

}  // namespace

std::vector<Vec2> parse_points_csv(std::string_view text, const std::string& path) {
  std::vector<Vec2> points;
  std::vector<double> values;
  std::string bad;
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
    if (!parse_row(row, values, bad)) {
      if (header_allowed) {
        header_allowed = false;
        continue;
      }
      throw FileError(path, line, 0, fmt::format("{}:{}: '{}' is not a number", path, line, bad));
    }
    header_allowed = false;
    if (values.size() != 2) {
      throw FileError(path, line, 0,
                      fmt::format("{}:{}: expected two numbers x, y, got {}", path, line, values.size()));
    }
    if (!std::isfinite(values[0]) || !std::isfinite(values[1])) {
      throw FileError(path, line, 0, fmt::format("{}:{}: a coordinate is not a finite number", path, line));
    }
    points.emplace_back(values[0], values[1]);
    if (end == text.size()) break;
  }
  return points;
}

std::vector<Vec2> read_points_csv(const std::string& path) {
  constexpr std::size_t kMaxPointsFileBytes = 64u << 20;
  return parse_points_csv(read_file(path, kMaxPointsFileBytes, "points file"), path);
}

}  // namespace fabmesh
