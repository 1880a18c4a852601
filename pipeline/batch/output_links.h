#pragma once
// Links inside a batch's output folder are never followed: a folder or file
// of the batch that is a symbolic link could lead anywhere, and writing or
// tidying through it would change files outside the output folder.

#include <string>
#include <string_view>

namespace fabmesh {

/// True when `path` is itself a symbolic link (not followed).
bool is_link(const std::string& path);

/// \throw InputError naming `path` when it is a symbolic link; `what` names
/// its role ("variant folder", "batch folder").
void refuse_link(const std::string& path, std::string_view what);

}  // namespace fabmesh
