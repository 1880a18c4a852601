#pragma once
// Designs as every command reads them: the file, checked against the output table.

#include <string>

#include "io/design/design.h"

namespace fabmesh {

/// Reads the design at `path` (io/design/read_design.h) and checks its
/// `outputs` against the output table, so a bad design fails before any work.
/// \throw FileError naming file, line, column and field
Design load_design(const std::string& path);

}  // namespace fabmesh
