#include "pipeline/batch/summary.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "pipeline/batch/ledger.h"

namespace fabmesh {

int exit_code_of(VariantStatus status) {
  switch (status) {
    case VariantStatus::Ok:
      return 0;
    case VariantStatus::Invalid:
      return 1;
    case VariantStatus::BadInput:
      return 2;
    case VariantStatus::Error:
      return 3;
    case VariantStatus::Missing:
      return 0;
  }
  return 3;
}

void SummaryCounts::add(VariantStatus status, int code) {
  switch (status) {
    case VariantStatus::Ok:
      ++ok;
      break;
    case VariantStatus::Invalid:
      ++invalid;
      break;
    case VariantStatus::BadInput:
      ++bad_input;
      break;
    case VariantStatus::Error:
      ++error;
      break;
    case VariantStatus::Missing:
      ++missing;
      break;
  }
  exit_code = std::max(exit_code, code);
}

PlanRows::PlanRows(const BatchPlan& plan)
    : plan_(plan), rows_(plan.variants.size()), status_(plan.variants.size(), VariantStatus::Missing) {
  by_name_.reserve(plan.variants.size());
  for (std::size_t i = 0; i < plan.variants.size(); ++i) by_name_.emplace(plan.variants[i].name, i);
}

void PlanRows::offer(std::string_view json) {
  const nlohmann::json j = nlohmann::json::parse(json, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return;
  const auto name = j.find("name");
  const auto key = j.find("key");
  const auto status = j.find("status");
  if (name == j.end() || key == j.end() || status == j.end() || !name->is_string() || !status->is_string())
    return;
  const auto it = by_name_.find(name->get<std::string>());
  if (it == by_name_.end() || plan_.variants[it->second].key != *key) return;
  VariantStatus s;
  try {
    s = parse_variant_status(status->get<std::string>());
  } catch (const InputError&) {
    return;
  }
  const std::size_t i = it->second;
  const bool kept_finished = status_[i] != VariantStatus::Missing && status_[i] != VariantStatus::Error;
  if (s == VariantStatus::Missing || (kept_finished && s == VariantStatus::Error)) return;
  rows_[i] = std::string(json);
  status_[i] = s;
}

void PlanRows::offer_ledgers(const std::string& folder) {
  for (const LedgerFile& file : list_ledgers(folder)) {
    for_each_row(file, [&](std::string_view json) { offer(json); });
  }
}

BatchRow summary_row(const BatchPlan& plan, const PlanRows& rows, std::size_t i) {
  const PlannedVariant& p = plan.variants[i];
  BatchRow row;
  if (const std::string* json = rows.row(i)) row = row_from_json(nlohmann::ordered_json::parse(*json));
  row.index = i;
  row.name = p.name;
  row.design = p.design;
  row.overrides = p.overrides;
  row.key = p.key;
  return row;
}

SummaryCounts write_summary(const BatchPlan& plan, const PlanRows& rows, const std::string& out_dir) {
  SummaryCounts counts;
  std::string jsonl, csv = csv_header(plan.parameters);
  for (std::size_t i = 0; i < plan.variants.size(); ++i) {
    const BatchRow row = summary_row(plan, rows, i);
    counts.add(row.status, exit_code_of(row.status));
    jsonl += row_json(row).dump() + "\n";
    csv += csv_line(row, plan.parameters);
  }
  const std::filesystem::path dir(out_dir);
  write_file_atomically((dir / "summary.jsonl").string(), jsonl);
  write_file_atomically((dir / "summary.csv").string(), csv);
  return counts;
}

std::string ledger_folder(const std::string& out_dir) {
  return (std::filesystem::path(out_dir) / ".batch").string();
}

}  // namespace fabmesh
