#include "pipeline/batch/summary.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "pipeline/batch/ledger.h"

namespace fabmesh {

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
    case VariantStatus::Environment:
      ++environment;
      break;
  }
  exit_code = std::max(exit_code, code);
}

PlanRows::PlanRows(const BatchPlan& plan)
    : plan_(plan), places_(plan.size()), status_(plan.size(), VariantStatus::Missing) {}

std::size_t PlanRows::add_ledger(const std::string& path) {
  ledgers_.push_back(path);
  return ledgers_.size() - 1;
}

std::optional<std::string> PlanRows::row(std::size_t i) const {
  if (status_[i] == VariantStatus::Missing) return std::nullopt;
  const Place& p = places_[i];
  return read_row(ledgers_[p.ledger], p.offset, p.size);
}

void PlanRows::offer(std::string_view json, std::size_t ledger, std::uint64_t offset) {
  const nlohmann::json j = nlohmann::json::parse(json, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return;
  const auto name = j.find("name");
  const auto key = j.find("key");
  const auto status = j.find("status");
  if (name == j.end() || key == j.end() || status == j.end() || !name->is_string() || !status->is_string())
    return;
  const std::optional<std::size_t> found = plan_.find(name->get<std::string>());
  if (!found || !key->is_string() || plan_.key(*found) != key->get<std::string>()) return;
  VariantStatus s;
  try {
    s = parse_variant_status(status->get<std::string>());
  } catch (const InputError&) {
    return;
  }
  const std::size_t i = *found;
  // A final row is never replaced by one that is not (another shard's error, say).
  if (s == VariantStatus::Missing || (is_final(status_[i]) && !is_final(s))) return;
  places_[i] = {offset, static_cast<std::uint32_t>(json.size()), static_cast<std::uint32_t>(ledger)};
  status_[i] = s;
}

void PlanRows::offer_ledgers(const std::string& folder) {
  for (const LedgerFile& file : list_ledgers(folder)) {
    const std::size_t ledger = add_ledger(file.path);
    for_each_row(file, [&](std::string_view json, std::uint64_t offset) { offer(json, ledger, offset); });
  }
}

BatchRow summary_row(const BatchPlan& plan, const PlanRows& rows, std::size_t i) {
  const PlannedVariant p = plan.variant(i);
  BatchRow row;
  if (const std::optional<std::string> json = rows.row(i))
    row = row_from_json(nlohmann::ordered_json::parse(*json));
  row.index = i;
  row.name = p.name;
  row.design = p.design;
  row.overrides = p.overrides;
  row.key = p.key;
  return row;
}

SummaryCounts write_summary(const BatchPlan& plan, const PlanRows& rows, const std::string& out_dir) {
  SummaryCounts counts;
  const std::filesystem::path dir(out_dir);
  PendingFile jsonl((dir / "summary.jsonl").string());
  PendingFile csv((dir / "summary.csv").string());
  csv.write(csv_header(plan.parameters));
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const BatchRow row = summary_row(plan, rows, i);
    counts.add(row.status, exit_code_of(row.status));
    jsonl.write(row_json(row).dump() + "\n");
    csv.write(csv_line(row, plan.parameters));
  }
  commit_file(std::move(jsonl));
  commit_file(std::move(csv));
  return counts;
}

std::string ledger_folder(const std::string& out_dir) {
  return (std::filesystem::path(out_dir) / ".batch").string();
}

}  // namespace fabmesh
