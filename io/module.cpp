#include "io/module.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <vector>

namespace fabmesh {
namespace {

std::string folder_of_this_binary() {
  Dl_info info{};
  static const int anchor = 0;
  if (dladdr(&anchor, &info) == 0 || info.dli_fname == nullptr) return ".";
  const std::string path = info.dli_fname;
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

}  // namespace

ModuleLookup find_module(const char* file, const char* entry, int abi) {
  const std::string here = folder_of_this_binary();
  const std::vector<std::string> candidates = {
      fmt::format("{}/{}/{}", here, FABMESH_MODULES_FROM_PROGRAM, file),
      fmt::format("{}/fabmesh/{}", here, file),
      fmt::format("{}/../lib/fabmesh/{}", here, file),
  };
  ModuleLookup m;
  std::string tried;
  for (const std::string& path : candidates) {
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = dlerror();
      tried += fmt::format("; {}: {}", path, why != nullptr ? why : "not loadable");
      continue;
    }
    using Entry = const void* (*)();
    auto function = reinterpret_cast<Entry>(dlsym(handle, entry));
    const void* table = function != nullptr ? function() : nullptr;
    const int found = table != nullptr ? *static_cast<const int*>(table) : 0;
    if (found != abi) {
      tried += fmt::format("; {}: built for another fabmesh (interface {}, this one {})", path, found, abi);
      dlclose(handle);
      continue;
    }
    m.table = table;
    m.status = path;
    return m;
  }
  m.status = fmt::format("fabmesh's module {} was not found (tried {})", file, tried.substr(2));
  return m;
}

}  // namespace fabmesh
