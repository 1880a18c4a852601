#include "io/design/yaml/canonical_tree.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <utility>
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/yaml/double_quoted.h"
#include "io/design/yaml/file_keys.h"
#include "io/file.h"

namespace fabmesh::yaml {
namespace {

constexpr std::size_t kMaxCanonicalBytes = 256u << 20;
constexpr std::size_t kMaxReadFileBytes = 64u << 20;  // as io/design/points_csv.cpp reads

class Writer {
 public:
  Writer(std::string path, std::string folder, const std::vector<std::string>* blank = nullptr)
      : path_(std::move(path)), folder_(std::move(folder)), blank_(blank) {}

  void node(const YAML::Node& n, const char* parent_key) {
    check_size();
    switch (n.Type()) {
      case YAML::NodeType::Undefined:
      case YAML::NodeType::Null:
        out_ += '~';
        break;
      case YAML::NodeType::Scalar:
        scalar(n);
        break;
      case YAML::NodeType::Sequence:
        out_ += '[';
        for (std::size_t i = 0; i < n.size(); ++i) {
          if (i > 0) out_ += ',';
          node(n[i], parent_key);  // a list's entries are under its key (holes: [{dxf: ...}])
        }
        out_ += ']';
        break;
      case YAML::NodeType::Map:
        map(n, parent_key);
        break;
    }
  }

  std::string take() { return std::move(out_); }

  // The text with the values of the root entries named in `blank` as "*" (the
  // spans were noted while writing, in order).
  std::string blanked() const {
    std::string text;
    std::size_t from = 0;
    for (const auto& [begin, end] : blanked_) {
      text.append(out_, from, begin - from);
      text += '*';
      from = end;
    }
    text.append(out_, from, std::string::npos);
    return text;
  }

 private:
  void scalar(const YAML::Node& n) {
    // "?" is a plain scalar, "!" a quoted one; anything else is an explicit tag.
    const std::string& tag = n.Tag();
    if (tag == "!") {
      out_ += '\'';
    } else if (tag != "?") {
      out_ += '!';
      quoted(tag);
    }
    quoted(n.Scalar());
  }

  void quoted(const std::string& text) { out_ += double_quoted(text); }

  void map(const YAML::Node& n, const char* parent_key) {
    // Sorted through indices: assigning a YAML::Node (as sorting nodes would)
    // overwrites the node it refers to.
    std::vector<std::string> keys;
    std::vector<YAML::Node> values;
    for (const auto& kv : n) {
      Writer key(path_, folder_);
      key.node(kv.first, nullptr);
      keys.push_back(key.take());
      values.push_back(kv.second);
    }
    std::vector<std::size_t> order(keys.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
    const bool root = depth_ == 0;
    ++depth_;
    out_ += '{';
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::string& key = keys[order[k]];
      const YAML::Node& value = values[order[k]];
      if (k > 0) out_ += ',';
      out_ += key;
      out_ += ':';
      const std::size_t begin = out_.size();
      const std::string plain_key = key_text(key);
      if (is_file_reference(parent_key, key, value)) {
        file(value.Scalar());
      } else {
        node(value, plain_key.empty() ? nullptr : plain_key.c_str());
      }
      if (root && blank_ != nullptr && !plain_key.empty() &&
          std::find(blank_->begin(), blank_->end(), plain_key) != blank_->end()) {
        blanked_.emplace_back(begin, out_.size());
      }
    }
    out_ += '}';
    --depth_;
  }

  // The text of a plain scalar key as written ("polyline"), or "" for any other key.
  static std::string key_text(const std::string& canonical_key) {
    if (canonical_key.size() < 2 || canonical_key.front() != '"' || canonical_key.back() != '"') return "";
    const std::string inner = canonical_key.substr(1, canonical_key.size() - 2);
    return inner.find_first_of("\"\\") == std::string::npos ? inner : "";
  }

  static bool is_file_reference(const char* parent_key, const std::string& canonical_key,
                                const YAML::Node& value) {
    if (parent_key == nullptr || !value.IsScalar()) return false;
    // A file key (file_keys.h) must be here, or its file's content would not enter the key.
    return is_file_key(parent_key, key_text(canonical_key));
  }

  // The bytes of the file, not its name: a moved or renamed file keeps its key.
  void file(const std::string& name) {
    const std::filesystem::path p(name);
    const std::filesystem::path full = p.is_absolute() ? p : std::filesystem::path(folder_) / p;
    try {
      const std::string bytes = read_file(full.string(), kMaxReadFileBytes, "file");
      out_ += fmt::format("file({}:", bytes.size());
      out_ += bytes;
      out_ += ')';
    } catch (const FileError&) {
      out_ += "unreadable-file(";
      quoted(name);
      out_ += ')';
    }
  }

  void check_size() const {
    if (out_.size() > kMaxCanonicalBytes) {
      throw FileError(path_, 0, 0,
                      fmt::format("{}: the design expands to more than {} MiB (through YAML aliases?)", path_,
                                  kMaxCanonicalBytes >> 20));
    }
  }

  std::string path_, folder_;
  const std::vector<std::string>* blank_ = nullptr;           // root keys whose values blanked() leaves out
  std::vector<std::pair<std::size_t, std::size_t>> blanked_;  // their spans in out_
  int depth_ = 0;                                             // maps being written
  std::string out_;
};

}  // namespace

std::string canonical_tree(const YAML::Node& root, const std::string& path,
                           const std::string& design_folder) {
  Writer w(path, design_folder);
  w.node(root, nullptr);
  return w.take();
}

std::string canonical_tree(const YAML::Node& root, const std::string& path, const std::string& design_folder,
                           const std::vector<std::string>& blank, std::string& blanked) {
  Writer w(path, design_folder, &blank);
  w.node(root, nullptr);
  blanked = w.blanked();
  return w.take();
}

}  // namespace fabmesh::yaml
