#pragma once
// Values written into shell scripts (the Slurm script of a batch).

#include <string>
#include <string_view>

namespace fabmesh {

/// `text` as one bash word that stands for exactly `text`, on one line:
/// 'text' ('\'' for each single quote) when it holds no control character,
/// else $'...' with \n, \t, \r, \\, \' and \xHH escapes, so that neither a
/// newline nor anything else ends the line (or the comment) it is written in.
/// Nothing inside is expanded: $(...), backticks, spaces and globs stay text.
/// \throw InputError for a NUL byte, which no shell word can hold
std::string shell_quote(std::string_view text);

}  // namespace fabmesh
