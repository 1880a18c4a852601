#include "pipeline/build_design.h"

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <limits>
#include <new>
#include <string>

#include "geometry/core/errors.h"
#include "pipeline/load_design.h"

namespace fabmesh {

std::size_t process_memory_limit() {
  std::size_t limit = std::numeric_limits<std::size_t>::max();
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGESIZE);
  if (pages > 0 && page_size > 0)
    limit = static_cast<std::size_t>(pages) * static_cast<std::size_t>(page_size);
  rlimit address_space{};
  if (::getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY) {
    limit = std::min(limit, static_cast<std::size_t>(address_space.rlim_cur));
  }
  return limit;
}

Result build_design(const Design& design, const BuildContext& context) {
  const DesignCommon& common = design.common;
  return in_design(design, [&] {
    try {
      return std::visit([&](const auto& body) { return build(body, context); }, design.body);
    } catch (const BudgetError& e) {
      // Every budget is the tolerance's (and max_triangles'): at the tolerance, in the design's words.
      throw BudgetError(e.requested(), e.budget(),
                        fmt::format("{} {}: {}", common.tolerance, common.units, e.what()),
                        ErrorLocation{"tolerance"});
    } catch (const std::bad_alloc&) {
      // A budget the design allows (max_triangles) that this machine's memory does not.
      throw BudgetError(0.0, 0.0,
                        fmt::format("{} {}: the mesh does not fit in this machine's memory; raise the "
                                    "tolerance or lower max_triangles",
                                    common.tolerance, common.units),
                        ErrorLocation{"tolerance"});
    }
  });
}

}  // namespace fabmesh
