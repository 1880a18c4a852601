#include "pipeline/batch/plan.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <filesystem>
#include <nlohmann/json.hpp>

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

BatchPlan plan_batch(const BatchManifest& manifest) {
  BatchPlan plan;
  plan.manifest = manifest.path;
  plan.parameters = manifest.parameters;
  plan.variants.resize(manifest.variants.size());
  std::vector<std::string> base_canonical(manifest.bases.size());
  for (std::size_t b = 0; b < manifest.bases.size(); ++b) {
    try {
      base_canonical[b] = manifest.bases[b].canonical({});
    } catch (const FileError& e) {
      base_canonical[b] = std::string("unreadable base\n") + e.what();
    }
  }
  tbb::parallel_for(std::size_t{0}, manifest.variants.size(), [&](std::size_t i) {
    const Variant& v = manifest.variants[i];
    PlannedVariant& p = plan.variants[i];
    p.name = v.name;
    p.design = manifest.base_labels[v.base];
    for (const Override& o : v.overrides) p.overrides.emplace_back(o.path, o.value);
    const std::vector<Override> all = variant_overrides(manifest, v);
    try {
      p.key = variant_key(manifest.bases[v.base].canonical(all));
    } catch (const FileError&) {
      p.key = unresolvable_key(base_canonical[v.base], all);
    }
  });
  Sha256 digest;
  digest.update("fabmesh batch plan 1\n");
  for (const PlannedVariant& p : plan.variants)
    digest.update(p.name).update(std::string_view("\0", 1)).update(p.key).update("\n");
  plan.digest = digest.hex_digest();
  return plan;
}

std::string plan_text(const BatchPlan& plan) {
  nlohmann::ordered_json j;
  j["fabmesh_batch_plan"] = 1;
  j["digest"] = plan.digest;
  j["manifest"] = plan.manifest;
  j["parameters"] = plan.parameters;
  j["variants"] = nlohmann::ordered_json::array();
  for (const PlannedVariant& p : plan.variants) {
    nlohmann::ordered_json v;
    v["name"] = p.name;
    v["design"] = p.design;
    v["overrides"] = nlohmann::ordered_json::object();
    for (const auto& [path, value] : p.overrides) v["overrides"][path] = value;
    v["key"] = p.key;
    j["variants"].push_back(std::move(v));
  }
  return j.dump(1) + "\n";
}

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
      plan.variants.push_back(std::move(p));
    }
    return plan;
  } catch (const nlohmann::json::exception& e) {
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
  write_file_atomically(path, plan_text(plan));
}

}  // namespace fabmesh
