#pragma once
// Reads YAML design files into Design structs.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/design.h"
#include "io/design/overrides.h"

namespace fabmesh {

/// A key the design's map does not have (`body.wal`, `bodyy`): a FileError
/// that also carries the key's full path, so that a batch can tell a typo in
/// an override path (every variant would fail alike) from a bad value.
class UnknownKeyError : public FileError {
 public:
  UnknownKeyError(std::string field, const std::string& path, int line, int column,
                  const std::string& message)
      : FileError(path, line, column, message, ErrorLocation{field, {}, {}, {}, path, line, column}),
        field_(std::move(field)) {}
  /// The key's path in the design: "body.wal", "bodyy", "holes[0].elipse".
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

/// The largest design file fabmesh reads (read_design_text): every command
/// and the studio alike (docs/design-files.md, "Limits").
inline constexpr std::size_t kMaxDesignFileBytes = std::size_t{16} << 20;

/// The text of the design file at `path`: a regular file of at most
/// kMaxDesignFileBytes (io/file.h's bounded read_file).
/// \throw FileError naming the path: missing, unreadable, not a regular file, too large
std::string read_design_text(const std::string& path);

/// Reads and validates a design file (read_design_text: a regular file of at
/// most 16 MiB; one YAML document). Every error is a FileError whose message starts with
/// "path:line:column: field:" and names the value. The `outputs` are kept as
/// given: the pipeline's output table checks them.
/// Ranges checked here: tolerance > 0, shape parameters of each family,
/// counts of control points; geometry (joins, closure) is checked when built.
/// `overrides` (-D path=value) replace or add fields before anything is read,
/// in order; an error at an overridden value names the override
/// ("-D body.wall=-1: body.wall: wall = -1 must be > 0"), a path through a
/// missing list entry or a value that is not a map is bad input too.
/// \throw FileError
Design read_design(const std::string& path, const std::vector<Override>& overrides = {});

/// The same from YAML text; `path` is used for messages and the default name.
Design parse_design(const std::string& yaml_text, const std::string& path,
                    const std::vector<Override>& overrides = {});

/// Why `name` is not a plain file name, the rule for design names (empty when
/// it is): at most 120 bytes of letters (UTF-8), digits, spaces and _ - . + ( ),
/// not starting with '.', '-' or a space, not ending with a space or '.'.
std::string plain_name_problem(const std::string& name);

/// Why `name` is not a parameter set's name (empty when it is): 1 to 64
/// letters, digits, _ and -, not starting with - (names go into file names
/// and onto command lines: `run -P NAME`, `{set}` in a batch's names).
std::string parameter_set_name_problem(const std::string& name);

}  // namespace fabmesh
