#include "io/design/design_source.h"

#include <filesystem>
#include <mutex>
#include <utility>

#include "io/design/read_design.h"
#include "io/design/yaml/canonical_tree.h"
#include "io/design/yaml/design_tree.h"
#include "io/file.h"

namespace fabmesh {

struct DesignSource::Impl {
  std::string path;
  std::string folder;
  /// The text, parsed again for each resolution: a copy of a parsed tree
  /// (YAML::Clone) loses every node's line and column, which messages about
  /// a variant's values must name.
  std::string text;
  YAML::Node root;
  // yaml-cpp nodes are not safe to read from several threads at once (iterating
  // a map updates internal state): `root` is read one thread at a time.
  std::mutex copying;
};

DesignSource::DesignSource(const std::string& text, std::string path) : impl_(std::make_unique<Impl>()) {
  impl_->root = yaml::load_design_tree(text, path);
  impl_->text = text;
  impl_->folder = std::filesystem::path(path).parent_path().string();
  impl_->path = std::move(path);
}

DesignSource DesignSource::read(const std::string& path) {
  return DesignSource(read_design_text(path), path);
}

DesignSource::DesignSource(DesignSource&&) noexcept = default;
DesignSource& DesignSource::operator=(DesignSource&&) noexcept = default;
DesignSource::~DesignSource() = default;

const std::string& DesignSource::path() const { return impl_->path; }

std::string DesignSource::name() const {
  std::lock_guard<std::mutex> lock(impl_->copying);
  const YAML::Node& root = impl_->root;
  const YAML::Node name = root["name"];
  if (name.IsDefined() && name.IsScalar()) return name.Scalar();
  return std::filesystem::path(impl_->path).stem().string();
}

std::vector<std::string> DesignSource::parameter_set_names() const {
  std::lock_guard<std::mutex> lock(impl_->copying);
  std::vector<std::string> names;
  const YAML::Node sets = impl_->root["parameter_sets"];
  if (!sets.IsDefined() || !sets.IsMap()) return names;
  for (const auto& kv : sets) {
    if (kv.first.IsScalar()) names.push_back(kv.first.Scalar());
  }
  return names;
}

std::string DesignSource::canonical(const std::vector<Override>& overrides) const {
  YAML::Node root = yaml::load_design_tree(impl_->text, impl_->path);
  yaml::apply_overrides(root, impl_->path, overrides);
  return yaml::canonical_tree(root, impl_->path, impl_->folder);
}

Design DesignSource::resolve(const std::vector<Override>& overrides, std::string* canonical,
                             BlankedText* blanked) const {
  if (canonical != nullptr) canonical->clear();
  if (blanked != nullptr) blanked->text.clear();
  YAML::Node root = yaml::load_design_tree(impl_->text, impl_->path);
  std::vector<yaml::OverrideOrigin> origins = yaml::apply_overrides(root, impl_->path, overrides);
  if (blanked != nullptr) {
    std::string text = yaml::canonical_tree(root, impl_->path, impl_->folder, blanked->keys, blanked->text);
    if (canonical != nullptr) *canonical = std::move(text);
  } else if (canonical != nullptr) {
    *canonical = yaml::canonical_tree(root, impl_->path, impl_->folder);
  }
  return yaml::read_design_tree(root, impl_->path, std::move(origins));
}

}  // namespace fabmesh
