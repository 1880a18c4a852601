#include "io/design/yaml_fields.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace fabmesh::yaml {
namespace {

std::string join(std::initializer_list<const char*> items) {
  std::string out;
  for (const char* s : items) out += (out.empty() ? "" : ", ") + std::string(s);
  return out;
}

}  // namespace

std::string Fields::label(const YAML::Node& node, const std::string& field) const {
  const YAML::Mark m = node.IsDefined() ? node.Mark() : YAML::Mark::null_mark();
  if (m.line < 0) return fmt::format("{}: {}", path_, field);
  return fmt::format("{}:{}:{}: {}", path_, m.line + 1, m.column + 1, field);
}

YAML::Node Fields::required(const YAML::Node& parent, const char* key, const std::string& field) const {
  const YAML::Node child = parent[key];
  if (!child.IsDefined()) fail(parent, field, fmt::format("missing required key '{}'", key));
  return child;
}

void Fields::fail(const YAML::Node& node, const std::string& field, const std::string& message) const {
  const YAML::Mark m = node.IsDefined() ? node.Mark() : YAML::Mark::null_mark();
  throw FileError(path_, m.line + 1, m.column + 1, fmt::format("{}: {}", label(node, field), message));
}

void Fields::require_map(const YAML::Node& node, const std::string& field,
                         std::initializer_list<const char*> allowed) const {
  if (!node.IsMap()) fail(node, field, "expected a map of keys");
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    const bool known = std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; });
    if (!known) {
      fail(kv.first, field.empty() ? key : field + "." + key,
           fmt::format("unknown key '{}' (expected one of: {})", key, join(allowed)));
    }
  }
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
                           std::initializer_list<const char*> choices) const {
  const std::string value = text(node, field);
  for (const char* c : choices) {
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
