#include "io/design/file_references.h"

#include <fmt/format.h>

#include <filesystem>

#include "io/design/yaml/design_tree.h"
#include "io/design/yaml/file_keys.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

// Collects the file keys' values under `node`, whose path is `key` and whose
// map key (or list's key) is `parent_key`.
void collect(const YAML::Node& node, const std::string& key, const std::string& parent_key,
             const fs::path& folder, std::vector<FileReference>& out) {
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      collect(node[i], fmt::format("{}[{}]", key, i), parent_key, folder, out);
    return;
  }
  if (!node.IsMap()) return;
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) continue;
    const std::string& name = entry.first.Scalar();
    const std::string path = key.empty() ? name : fmt::format("{}.{}", key, name);
    if (yaml::is_file_key(parent_key, name) && entry.second.IsScalar()) {
      const fs::path file(entry.second.Scalar());
      out.push_back(
          {path, fs::absolute(file.is_absolute() ? file : folder / file).lexically_normal().string()});
    } else {
      collect(entry.second, path, name, folder, out);
    }
  }
}

}  // namespace

std::vector<FileReference> file_references(const std::string& text, const std::string& path,
                                           const std::vector<Override>& overrides) {
  const YAML::Node root = yaml::load_design_tree(text, path);
  (void)yaml::apply_overrides(root, path, overrides);
  std::vector<FileReference> out;
  collect(root, "", "", fs::path(path).parent_path(), out);
  return out;
}

}  // namespace fabmesh
