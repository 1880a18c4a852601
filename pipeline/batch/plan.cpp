#include "pipeline/batch/plan.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "pipeline/batch/sha256.h"

namespace fabmesh {
namespace {

// Changing what a key covers (or how) changes this tag: every key changes with it.
constexpr const char* kKeyFormat = "fabmesh batch variant key 1";

// A key for a variant whose overrides do not apply: its base and its override texts.
std::string unresolvable_key(const std::string& base_canonical, const std::vector<Override>& overrides) {
  std::string material = "unresolvable\n" + base_canonical;
  for (const Override& o : overrides) material += "\n" + o.path + "=" + o.value;
  return variant_key(material);
}

}  // namespace

std::string variant_key(const std::string& canonical) {
  return Sha256().update(kKeyFormat).update("\nfabmesh " FABMESH_VERSION "\n").update(canonical).hex_digest();
}

namespace {

std::array<std::uint8_t, 32> key_bytes(const std::string& hex) {
  std::array<std::uint8_t, 32> out{};
  if (hex.size() != 64) throw std::invalid_argument("a variant key has 64 hex digits");
  for (std::size_t i = 0; i < 32; ++i)
    out[i] = static_cast<std::uint8_t>(std::stoi(hex.substr(2 * i, 2), nullptr, 16));
  return out;
}

std::uint64_t name_hash(const std::string& name) { return std::hash<std::string>{}(name); }

PlannedVariant planned(const BatchManifest& manifest, const Variant& v) {
  PlannedVariant p;
  p.name = v.name;
  p.design = manifest.base_labels[v.base];
  for (const Override& o : v.overrides) p.overrides.emplace_back(o.path, o.value);
  return p;
}

}  // namespace

PlannedVariant BatchPlan::variant(std::size_t i) const {
  if (source_ == nullptr) return read_.at(i);
  PlannedVariant p = planned(*source_, source_->variant(i));
  p.key = key(i);
  return p;
}

std::string BatchPlan::name(std::size_t i) const {
  return source_ == nullptr ? read_.at(i).name : source_->variant(i).name;
}

std::string BatchPlan::key(std::size_t i) const {
  std::string hex;
  hex.reserve(64);
  for (const std::uint8_t b : keys_.at(i)) hex += fmt::format("{:02x}", b);
  return hex;
}

std::optional<std::size_t> BatchPlan::find(const std::string& name) const {
  const std::uint64_t h = name_hash(name);
  auto it = std::lower_bound(names_.begin(), names_.end(), std::make_pair(h, std::uint64_t{0}));
  for (; it != names_.end() && it->first == h; ++it) {
    if (this->name(it->second) == name) return static_cast<std::size_t>(it->second);
  }
  return std::nullopt;
}

void BatchPlan::index_names() {
  names_.clear();
  names_.reserve(size());
  for (std::size_t i = 0; i < size(); ++i) names_.emplace_back(name_hash(name(i)), i);
  std::sort(names_.begin(), names_.end());
}

BatchPlan plan_batch(const BatchManifest& manifest) {
  BatchPlan plan;
  plan.manifest = manifest.path;
  plan.parameters = manifest.parameters;
  plan.source_ = &manifest;
  const std::size_t n = manifest.variant_count();
  plan.keys_.resize(n);
  std::vector<std::string> base_canonical(manifest.bases.size());
  for (std::size_t b = 0; b < manifest.bases.size(); ++b) {
    try {
      base_canonical[b] = manifest.bases[b].canonical({});
    } catch (const FileError& e) {
      base_canonical[b] = std::string("unreadable base\n") + e.what();
    }
  }
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    const Variant v = manifest.variant(i);
    const std::vector<Override> all = variant_overrides(manifest, v);
    std::string key;
    try {
      key = variant_key(manifest.bases[v.base].canonical(all));
    } catch (const FileError&) {
      key = unresolvable_key(base_canonical[v.base], all);
    }
    plan.keys_[i] = key_bytes(key);
  });
  Sha256 digest;
  digest.update("fabmesh batch plan 1\n");
  for (std::size_t i = 0; i < n; ++i)
    digest.update(plan.name(i)).update(std::string_view("\0", 1)).update(plan.key(i)).update("\n");
  plan.digest = digest.hex_digest();
  plan.index_names();
  return plan;
}

namespace {

// One variant of the plan file (a line of its "variants" list).
std::string variant_json(const PlannedVariant& p) {
  nlohmann::ordered_json v;
  v["name"] = p.name;
  v["design"] = p.design;
  v["overrides"] = nlohmann::ordered_json::object();
  for (const auto& [path, value] : p.overrides) v["overrides"][path] = value;
  v["key"] = p.key;
  return v.dump();
}

}  // namespace

BatchPlan read_plan(const std::string& path) {
  const std::string text = read_file(path);
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    BatchPlan plan;
    plan.digest = j.at("digest").get<std::string>();
    plan.manifest = j.at("manifest").get<std::string>();
    plan.parameters = j.at("parameters").get<std::vector<std::string>>();
    for (const auto& v : j.at("variants")) {
      PlannedVariant p;
      p.name = v.at("name").get<std::string>();
      p.design = v.at("design").get<std::string>();
      for (const auto& [k, value] : v.at("overrides").items())
        p.overrides.emplace_back(k, value.get<std::string>());
      p.key = v.at("key").get<std::string>();
      plan.keys_.push_back(key_bytes(p.key));
      plan.read_.push_back(std::move(p));
    }
    plan.index_names();
    return plan;
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path, 0, 0, fmt::format("{}: not a batch plan: {}", path, e.what()));
  } catch (const InputError& e) {
    throw FileError(path, 0, 0, fmt::format("{}: not a batch plan: {}", path, e.what()));
  } catch (const std::invalid_argument& e) {
    throw FileError(path, 0, 0, fmt::format("{}: not a batch plan: {}", path, e.what()));
  }
}

std::string plan_path(const std::string& folder, const std::string& digest) {
  return (std::filesystem::path(folder) / ("plan-" + digest + ".json")).string();
}

void save_plan(const BatchPlan& plan, const std::string& folder) {
  const std::string path = plan_path(folder, plan.digest);
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) return;
  nlohmann::ordered_json head;
  head["fabmesh_batch_plan"] = 1;
  head["digest"] = plan.digest;
  head["manifest"] = plan.manifest;
  head["parameters"] = plan.parameters;
  std::string text = head.dump();
  text.pop_back();  // the closing brace: the variants follow, one a line
  PendingFile file(path);
  file.write(text + ",\n\"variants\": [\n");
  for (std::size_t i = 0; i < plan.size(); ++i)
    file.write((i == 0 ? "" : ",\n") + variant_json(plan.variant(i)));
  file.write("\n]}\n");
  commit_file(std::move(file));
}

}  // namespace fabmesh
