#include "io/design/yaml/fields.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "geometry/core/limits.h"
#include "io/design/number_limits.h"
#include "io/design/read_design.h"

namespace fabmesh::yaml {
namespace {

template <class Items>
std::string join(const Items& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + std::string(s);
  return out;
}

/// "parent.key", built in place.
std::string child_field(const std::string& parent, const std::string& key) {
  std::string out;
  out.reserve(parent.size() + 1 + key.size());
  out.append(parent).append(".").append(key);
  return out;
}

}  // namespace

namespace {

bool contains(const YAML::Node& tree, const YAML::Node& node) {
  if (!tree.IsDefined()) return false;
  if (tree.is(node)) return true;
  if (tree.IsSequence()) {
    for (const YAML::Node& child : tree) {
      if (contains(child, node)) return true;
    }
  } else if (tree.IsMap()) {
    for (const auto& kv : tree) {
      if (contains(kv.first, node) || contains(kv.second, node)) return true;
    }
  }
  return false;
}

}  // namespace

ErrorLocation at_key(const std::string& key, const KeySource& where) {
  ErrorLocation location{key};
  location.file = where.file;
  location.line = where.line;
  location.column = where.column;
  location.override_text = where.override_text;
  return location;
}

const OverrideOrigin* Fields::origin_of(const YAML::Node& node) const {
  if (!node.IsDefined()) return nullptr;
  for (const OverrideOrigin& o : overrides_) {
    if (contains(o.value, node)) return &o;
  }
  return nullptr;
}

std::string Fields::location(const YAML::Node& node) const {
  if (const OverrideOrigin* o = origin_of(node)) return "-D " + o->text;
  const YAML::Mark m = node.IsDefined() ? node.Mark() : YAML::Mark::null_mark();
  if (m.line < 0) return path_;
  return fmt::format("{}:{}:{}", path_, m.line + 1, m.column + 1);
}

std::string Fields::label(const YAML::Node& node, const std::string& field) const {
  return fmt::format("{}: {}", location(node), field);
}

YAML::Node Fields::required(const YAML::Node& parent, const char* key, const std::string& field) const {
  const YAML::Node child = parent[key];
  if (!child.IsDefined()) fail(parent, field, fmt::format("missing required key '{}'", key));
  return child;
}

KeySource Fields::source(const YAML::Node& node) const {
  KeySource where;
  where.place = location(node);
  where.file = path_;
  if (const OverrideOrigin* o = origin_of(node)) {
    where.override_text = o->text;
    return where;
  }
  const YAML::Mark m = node.IsDefined() ? node.Mark() : YAML::Mark::null_mark();
  if (m.line >= 0) {
    where.line = m.line + 1;
    where.column = m.column + 1;
  }
  return where;
}

void Fields::fail(const YAML::Node& node, const std::string& field, const std::string& message) const {
  const KeySource where = source(node);
  throw FileError(path_, where.line, where.column, fmt::format("{}: {}", where.place + ": " + field, message),
                  at_key(field, where));
}

void Fields::fail_key(const YAML::Node& key, const YAML::Node& value, const std::string& field,
                      const std::string& message) const {
  if (origin_of(value) != nullptr) {
    const KeySource where = source(value);
    throw FileError(path_, 0, 0, fmt::format("{}: {}: {}", where.place, field, message),
                    at_key(field, where));
  }
  fail(key, field, message);
}

void Fields::require_map(const YAML::Node& node, const std::string& field, const KeyGroup& allowed) const {
  if (!node.IsMap()) fail(node, field, "expected a map of keys");
  std::vector<std::pair<std::string, YAML::Mark>> seen;
  for (const auto& kv : node) {
    if (!kv.first.IsScalar())
      fail_key(kv.first, kv.second, field.empty() ? "(a top-level key)" : field,
               "a key must be a plain name, not a list or a map");
    const std::string key = kv.first.Scalar();
    for (const auto& [earlier, mark] : seen) {
      if (earlier == key) {
        fail_key(
            kv.first, kv.second, field.empty() ? key : child_field(field, key),
            fmt::format("key '{}' is given twice (first at line {}, column {}); YAML keys must be unique",
                        key, mark.line + 1, mark.column + 1));
      }
    }
    seen.emplace_back(key, kv.first.Mark());
    const bool known = std::find(allowed.keys.begin(), allowed.keys.end(), key) != allowed.keys.end();
    if (!known) {
      const std::string at = field.empty() ? key : child_field(field, key);
      const std::string message =
          fmt::format("unknown key '{}' (expected one of: {})", key, join(allowed.keys));
      // An override whose path runs through this key made it (`-D bodyy.wall=1` makes `bodyy`).
      const OverrideOrigin* o = origin_of(kv.second);
      for (std::size_t i = 0; o == nullptr && i < overrides_.size(); ++i) {
        const std::string& text = overrides_[i].text;
        const std::string path = text.substr(0, text.find('='));
        if (path == at || path.rfind(at + ".", 0) == 0 || path.rfind(at + "[", 0) == 0) o = &overrides_[i];
      }
      if (o != nullptr)
        throw UnknownKeyError(at, path_, 0, 0, fmt::format("-D {}: {}: {}", o->text, at, message));
      const YAML::Mark m = kv.first.Mark();
      throw UnknownKeyError(at, path_, m.line + 1, m.column + 1,
                            fmt::format("{}: {}", label(kv.first, at), message));
    }
  }
}

long Fields::integer(const YAML::Node& node, const std::string& field, long lo, long hi) const {
  const double v = number(node, field);
  if (v != std::floor(v) || v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
    fail(node, field,
         fmt::format("{} = {} must be a whole number in [{}, {}]", field, node.Scalar(), lo, hi));
  }
  return static_cast<long>(v);
}

std::size_t Fields::budget_or(const YAML::Node& parent, const char* key, std::size_t fallback) const {
  const YAML::Node n = parent[key];
  if (!n.IsDefined()) return fallback;
  const double budget = number(n, key);
  if (budget < 1.0 || budget > kMaxTrianglesLimit || budget != std::floor(budget)) {
    fail(n, key, fmt::format("{} = {} must be a whole number in [1, {}]", key, budget, kMaxTrianglesLimit));
  }
  return static_cast<std::size_t>(budget);
}

void Fields::require_list(const YAML::Node& node, const std::string& field, std::size_t min_size) const {
  if (!node.IsSequence()) fail(node, field, "expected a list");
  if (node.size() < min_size) {
    fail(node, field, fmt::format("expected at least {} entries, got {}", min_size, node.size()));
  }
}

double Fields::number(const YAML::Node& node, const std::string& field) const {
  if (!node.IsDefined() || node.IsNull()) fail(node, field, "missing value");
  if (!node.IsScalar()) fail(node, field, "expected a number");
  double value = 0.0;
  if (!YAML::convert<double>::decode(node, value)) {
    fail(node, field, fmt::format("'{}' is not a number", node.Scalar()));
  }
  if (!std::isfinite(value)) fail(node, field, fmt::format("{} is not a finite number", node.Scalar()));
  if (std::abs(value) > kMaxDesignNumber) {
    fail(node, field,
         fmt::format("{} is too large: numbers in a design are at most {:g} in magnitude", node.Scalar(),
                     kMaxDesignNumber));
  }
  return value;
}

double Fields::number_or(const YAML::Node& parent, const char* key, const std::string& field,
                         double fallback) const {
  const YAML::Node n = parent[key];
  return n.IsDefined() ? number(n, field) : fallback;
}

std::string Fields::text(const YAML::Node& node, const std::string& field) const {
  if (!node.IsDefined() || node.IsNull()) fail(node, field, "missing value");
  if (!node.IsScalar()) fail(node, field, "expected a string");
  return node.Scalar();
}

std::string Fields::text_or(const YAML::Node& parent, const char* key, const std::string& field,
                            const std::string& fallback) const {
  const YAML::Node n = parent[key];
  return n.IsDefined() ? text(n, field) : fallback;
}

std::string Fields::choice(const YAML::Node& node, const std::string& field,
                           const std::vector<std::string>& choices) const {
  std::string value = text(node, field);
  for (const std::string& c : choices) {
    if (value == c) return value;
  }
  fail(node, field, fmt::format("'{}' is not one of: {}", value, join(choices)));
}

bool Fields::boolean_or(const YAML::Node& parent, const char* key, const std::string& field,
                        bool fallback) const {
  const YAML::Node n = parent[key];
  if (!n.IsDefined()) return fallback;
  bool value = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, value)) {
    fail(n, field, fmt::format("expected true or false"));
  }
  return value;
}

Vec2 Fields::point2(const YAML::Node& node, const std::string& field) const {
  if (!node.IsSequence() || node.size() != 2) fail(node, field, "expected a point [x, y]");
  return {number(node[0], field + "[0]"), number(node[1], field + "[1]")};
}

std::vector<Vec2> Fields::points2(const YAML::Node& node, const std::string& field,
                                  std::size_t min_size) const {
  require_list(node, field, min_size);
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < node.size(); ++i)
    out.push_back(point2(node[i], fmt::format("{}[{}]", field, i)));
  return out;
}

Vec3 Fields::point3(const YAML::Node& node, const std::string& field) const {
  if (!node.IsSequence() || node.size() != 3) fail(node, field, "expected a point [x, y, z]");
  return {number(node[0], field + "[0]"), number(node[1], field + "[1]"), number(node[2], field + "[2]")};
}

}  // namespace fabmesh::yaml
