#pragma once
// Designs as every command reads them: the file with its -D overrides,
// checked against the output table.

#include <string>
#include <vector>

#include "io/design/design.h"
#include "io/design/overrides.h"

namespace fabmesh {

/// Reads the design at `path` with `overrides` applied (io/design/read_design.h)
/// and checks its `outputs` against the output table, so a bad design fails
/// before any work. \throw FileError naming file, line, column and field (or the override)
Design load_design(const std::string& path, const std::vector<Override>& overrides = {});

/// The same for YAML text; `path` names it in messages, gives the default
/// name and the folder relative points files are read from. \throw FileError
Design load_design_text(const std::string& yaml_text, const std::string& path,
                        const std::vector<Override>& overrides = {});

/// Parses `-D` texts ("body.wall=2.5"). \throw InputError naming a malformed one
std::vector<Override> parse_overrides(const std::vector<std::string>& texts);

/// Runs `f` and returns what it returns. An InputError escaping it at a key
/// path of `design` (its ErrorLocation::key, see is_design_key) is rethrown
/// placed in the design (io's `placed`: file, line and column, the -D
/// override, or the default), where describe_failure reports it.
template <class F>
auto in_design(const Design& design, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (InputError& e) {
    if (e.location().place.empty() && is_design_key(design, e.location().key)) {
      e.set_location(placed(design.common, e.location()));
    }
    throw;
  }
}

}  // namespace fabmesh
