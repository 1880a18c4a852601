#include "pipeline/batch/shard.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {

Shard parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  auto whole = [](const std::string& s) {
    return !s.empty() && s.size() <= 7 && s.find_first_not_of("0123456789") == std::string::npos;
  };
  const std::string i = slash == std::string::npos ? "" : text.substr(0, slash);
  const std::string n = slash == std::string::npos ? "" : text.substr(slash + 1);
  if (!whole(i) || !whole(n)) {
    throw InputError(fmt::format("--shard {}: expected I/N, e.g. 0/8 (shard I of N, counted from 0)", text));
  }
  const Shard s{std::stoul(i), std::stoul(n)};
  if (s.count == 0 || s.count > kMaxShards || s.index >= s.count) {
    throw InputError(fmt::format("--shard {}: I must be in [0, N) and N in [1, {}]", text, kMaxShards));
  }
  return s;
}

}  // namespace fabmesh
