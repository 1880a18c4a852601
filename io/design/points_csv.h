#pragma once
// 2D points from a CSV file: digitised outlines too long to write as YAML.

#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// Parses "x,y" rows (spaces, tabs or ';' also separate; blank lines and
/// lines starting with '#' are skipped; a UTF-8 byte order mark at the start
/// is skipped; a first row that does not parse as numbers is a header). Every
/// other row must hold exactly two finite numbers of magnitude at most 1e12
/// (kMaxDesignNumber).
/// \param path for messages
/// \param header_line set to the 1-based line of a skipped header row, else 0
/// \throw FileError naming the line and the value
std::vector<Vec2> parse_points_csv(std::string_view text, const std::string& path,
                                   int* header_line = nullptr);

/// Reads and parses the file at `path`. \throw FileError
std::vector<Vec2> read_points_csv(const std::string& path, int* header_line = nullptr);

}  // namespace fabmesh
