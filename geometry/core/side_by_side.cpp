#include "geometry/core/side_by_side.h"

#include <tbb/parallel_invoke.h>

#include <exception>

namespace fabmesh {

void side_by_side(const std::function<void()>& first, const std::function<void()>& second) {
  std::exception_ptr first_failed;
  std::exception_ptr second_failed;
  const auto guarded = [](const std::function<void()>& work, std::exception_ptr& failed) {
    return [&work, &failed] {
      try {
        work();
      } catch (...) {
        failed = std::current_exception();
      }
    };
  };
  tbb::parallel_invoke(guarded(first, first_failed), guarded(second, second_failed));
  if (first_failed) std::rethrow_exception(first_failed);
  if (second_failed) std::rethrow_exception(second_failed);
}

}  // namespace fabmesh
