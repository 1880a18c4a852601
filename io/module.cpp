#include "io/module.h"

#include <dlfcn.h>
#include <fmt/format.h>
#include <link.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <vector>

#include "io/file.h"

namespace fabmesh {
namespace {

// `path` with every link and ".." resolved; empty when it cannot be.
std::string real_path(const char* path) {
  const std::unique_ptr<char, decltype(&std::free)> real(::realpath(path, nullptr), &std::free);
  return real ? std::string(real.get()) : std::string();
}

std::string folder_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : slash == 0 ? "/" : path.substr(0, slash);
}

}  // namespace

std::string folder_of_this_binary() {
  static const int anchor = 0;
  Dl_info info{};
  link_map* map = nullptr;
  if (dladdr1(&anchor, &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) == 0) return "";
  // The loader names the program by its argv[0] (a bare name found on PATH,
  // a symbolic link, a path relative to the folder it was started from):
  // the kernel's link to the executable is its real file.
  const bool in_program = map == nullptr || map->l_name == nullptr || map->l_name[0] == '\0';
  std::string real = real_path(in_program ? "/proc/self/exe" : info.dli_fname);
  if (real.empty() && info.dli_fname != nullptr && info.dli_fname[0] == '/') real = info.dli_fname;
  return folder_of(real);
}

ModuleLookup find_module(const char* file, const char* entry, int abi) {
  const std::string here = folder_of_this_binary();
  ModuleLookup m;
  if (here.empty()) {
    m.status = fmt::format(
        "fabmesh's module {} was not looked for: the location of fabmesh itself is unknown "
        "(/proc is not mounted?)",
        file);
    return m;
  }
  const std::filesystem::path folder(here);
  const std::vector<std::filesystem::path> candidates = {
      folder / FABMESH_MODULES_FROM_PROGRAM / file,
      folder / "fabmesh" / file,
      folder / ".." / "lib" / "fabmesh" / file,
  };
  std::string tried;
  for (const std::filesystem::path& candidate : candidates) {
    const std::string path = candidate.lexically_normal().string();
    if (tried.find("; " + path + ":") != std::string::npos) continue;  // the same place twice
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* error = dlerror();
      std::string why = error != nullptr ? error : "not loadable";
      if (why.rfind(path + ": ", 0) == 0) why.erase(0, path.size() + 2);  // the loader names it too
      tried += fmt::format("; {}: {}", path, why);
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

void throw_missing_module(const ModuleLookup& lookup, const std::string& file, const std::string& what,
                          const std::string& remedy) {
  throw MachineError(
      file, ENOENT,
      fmt::format("{}: {}: fabmesh is not installed completely; {}", what, lookup.status, remedy));
}

}  // namespace fabmesh
