#include "pipeline/batch/output_links.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include "geometry/core/errors.h"

namespace fabmesh {

bool is_link(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
}

void refuse_link(const std::string& path, std::string_view what) {
  if (!is_link(path)) return;
  throw InputError(
      fmt::format("{}: the {} is a symbolic link; fabmesh never follows a link inside the output folder "
                  "(writing or tidying through it would change files elsewhere): remove the link",
                  path, what));
}

}  // namespace fabmesh
