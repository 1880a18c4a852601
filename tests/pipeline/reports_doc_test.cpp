// The user's reference is a contract: docs/reports.md names every key the
// --json reports print, and docs/design-files.md's output table is the
// program's. These tests read the documents and hold the program to them.

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "pipeline/output_table.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;

namespace {

std::string document(const std::string& name) {
  std::ifstream in(std::string(FABMESH_SOURCE_DIR) + "/docs/" + name, std::ios::binary);
  REQUIRE(in);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The cells of a Markdown table row "| a | b |" (trimmed), or nothing for
// another line or the |---| rule.
std::vector<std::string> table_cells(const std::string& line) {
  if (line.rfind("| ", 0) != 0) return {};
  std::vector<std::string> cells;
  std::size_t start = 1;
  for (std::size_t bar; (bar = line.find('|', start)) != std::string::npos; start = bar + 1) {
    std::string cell = line.substr(start, bar - start);
    cell.erase(0, cell.find_first_not_of(' '));
    cell.erase(cell.find_last_not_of(' ') + 1);
    cells.push_back(cell);
  }
  return cells;
}

// The `code` spans of `text` that are one identifier each (`max_deviation`, not `{min, max}`).
std::vector<std::string> code_names(const std::string& text) {
  std::vector<std::string> names;
  for (std::size_t open = text.find('`'); open != std::string::npos; open = text.find('`', open)) {
    const std::size_t close = text.find('`', open + 1);
    if (close == std::string::npos) break;
    const std::string span = text.substr(open + 1, close - open - 1);
    if (!span.empty() &&
        span.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_.") == std::string::npos)
      names.push_back(span);
    open = close + 1;
  }
  return names;
}

// The names in the first column of every table in the section of `doc`
// headed by a line starting with `heading` (up to the next heading of that
// level or above).
std::set<std::string> table_keys(const std::string& doc, const std::string& heading) {
  const std::size_t level = heading.find(' ');
  std::set<std::string> keys;
  bool inside = false;
  for (const std::string& line : lines_of(document(doc))) {
    if (line.rfind(heading, 0) == 0) {
      inside = true;
      continue;
    }
    const std::size_t hashes = line.find_first_not_of('#');
    if (inside && hashes > 0 && hashes <= level && line.size() > hashes && line[hashes] == ' ') break;
    const auto cells = table_cells(line);
    if (inside && !cells.empty())
      for (const std::string& name : code_names(cells.front())) keys.insert(name);
  }
  REQUIRE_FALSE(keys.empty());
  return keys;
}

// Every `code` identifier anywhere in `doc`.
std::set<std::string> all_code_names(const std::string& doc) {
  const auto names = code_names(document(doc));
  return {names.begin(), names.end()};
}

nlohmann::json run_report(const std::vector<std::string>& args) {
  std::vector<std::string> all = {"run", "--json", "-q", "-o", fresh_dir("reports_doc").string() + "/"};
  all.insert(all.end(), args.begin(), args.end());
  const CliResult r = run_fabmesh(all);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return only_item(r.out);
}

std::set<std::string> keys_of(const nlohmann::json& item) {
  std::set<std::string> keys;
  for (const auto& [key, value] : item.items()) keys.insert(key);
  return keys;
}

const std::set<std::string> kRunOnlyFacts = {"topology_proof", "embedding_margin", "self_intersection_proof"};

const char* const kKindNames[] = {"curve", "vessel", "countertop", "surface"};  // DesignBody's order

// "vessel, countertop with `cnc`" or "every kind" or "-": the kinds named.
KindSet kinds_named(const std::string& cell) {
  KindSet set;
  for (std::size_t i = 0; i < std::size(kKindNames); ++i) {
    if (cell == "every kind" || cell.find(kKindNames[i]) != std::string::npos) set.set(i);
  }
  return set;
}

}  // namespace

TEST_CASE("docs: every key run --json prints is documented in reports.md, for every kind",
          "[pipeline][docs]") {
  std::set<std::string> documented = table_keys("reports.md", "## `fabmesh run --json`");
  documented.merge(table_keys("reports.md", "### Validation facts"));
  std::set<std::string> seen;
  for (const char* design : {"vessel_golden_solid.yaml", "countertop_cnc.yaml", "surface_basin_shell.yaml",
                             "example4_profile.yaml", "mould_golden.yaml"}) {
    const nlohmann::json item = run_report({example(design)});
    for (const std::string& key : keys_of(item)) {
      INFO(design << ": " << key);
      CHECK(documented.count(key) == 1);
      seen.insert(key);
    }
  }
  // ... and every documented key is printed by one of them, but those that
  // only some inputs give (checked where they are made: honest_exits_test,
  // hostile_input_test, surface_test, orientation tests).
  for (const std::string& key : documented) {
    // parameter_set: with -P only (tests/python/test_params_schema.py, the studio's tests).
    if (key == "notes" || key == "warnings" || key == "fabrication" || key == "parameter_set") continue;
    INFO(key);
    CHECK(seen.count(key) == 1);
  }
}

TEST_CASE("docs: every key check --json prints is documented in reports.md", "[pipeline][docs]") {
  const std::set<std::string> documented = all_code_names("reports.md");
  const std::set<std::string> facts = table_keys("reports.md", "### Validation facts");
  const std::filesystem::path dir = fresh_dir("reports_doc_check");
  REQUIRE(run_fabmesh({"run", "-q", "-o", dir.string() + "/", example("mould_golden.yaml")}).code == 0);
  std::set<std::string> fact_seen;
  for (const std::filesystem::directory_entry& file : std::filesystem::directory_iterator(dir)) {
    const std::string ext = file.path().extension().string();
    if (ext != ".stl" && ext != ".3mf") continue;
    const CliResult r = run_fabmesh({"check", "--json", file.path().string()});
    const nlohmann::json item = only_item(r.out);
    std::vector<nlohmann::json> reports = {item};
    if (item.contains("objects"))
      reports.insert(reports.end(), item["objects"].begin(), item["objects"].end());
    for (const nlohmann::json& report : reports) {
      for (const std::string& key : keys_of(report)) {
        INFO(file.path().filename().string() << ": " << key);
        CHECK(documented.count(key) == 1);
        fact_seen.insert(key);
      }
    }
  }
  for (const std::string& key : facts) {
    INFO(key);
    // The builders' proofs come with `run` only: a file read back has none.
    CHECK((fact_seen.count(key) == 1 || kRunOnlyFacts.count(key) == 1));
  }
}

TEST_CASE("docs: a failed input is an item of the JSON array, for every command", "[pipeline][docs]") {
  const CliResult check = run_fabmesh({"check", "--json", "/nonexistent/mesh.stl"});
  CHECK(check.code == 2);
  const nlohmann::json c = only_item(check.out);
  CHECK(c["file"] == "/nonexistent/mesh.stl");
  CHECK(c["exit_code"] == 2);
  CHECK(c["valid"] == false);
  CHECK_THAT(c["error"].get<std::string>(), Catch::Contains("cannot open"));

  const CliResult run = run_fabmesh({"run", "--json", "-q", "/nonexistent/design.yaml"});
  CHECK(run.code == 2);
  const nlohmann::json r = only_item(run.out);
  CHECK(r["design"] == "/nonexistent/design.yaml");
  CHECK(r["exit_code"] == 2);

  // Before any input has an item: one item for the command.
  const std::filesystem::path dir = fresh_dir("reports_doc_clash");
  const CliResult clash =
      run_fabmesh({"run", "--json", "-q", "-o", dir.string() + "/", example("vessel_golden_solid.yaml"),
                   example("vessel_golden_solid.yaml")});
  CHECK(clash.code == 2);
  const nlohmann::json k = only_item(clash.out);
  CHECK(k["command"] == "run");
  CHECK(k["inputs"].size() == 2);
  CHECK_THAT(k["error"].get<std::string>(), Catch::Contains("both named"));
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"optimize", "--json", "/nonexistent/design.yaml"},
        std::vector<std::string>{"batch", "--json", "/nonexistent/manifest.yaml", "-o",
                                 dir.string() + "/b"}}) {
    const CliResult failed = run_fabmesh(args);
    INFO(args.front());
    CHECK(failed.code == 2);
    CHECK(only_item(failed.out)["exit_code"] == 2);
  }
}

TEST_CASE("docs: design-files.md's output table is the program's", "[pipeline][docs]") {
  std::vector<std::vector<std::string>> rows;
  bool inside = false;
  for (const std::string& line : lines_of(document("design-files.md"))) {
    const auto cells = table_cells(line);
    if (!cells.empty() && cells.front() == "format") inside = true;
    if (inside && cells.empty() && !line.empty() && line.rfind("|", 0) != 0) break;
    if (inside && cells.size() == 5 && cells.front() != "format") rows.push_back(cells);
  }
  const std::vector<OutputFormat>& formats = output_formats();
  REQUIRE(rows.size() == formats.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const OutputFormat& f = formats[i];
    INFO(rows[i][0]);
    CHECK(rows[i][0] == "`" + std::string(f.name) + "`");
    // A format of several files writes its suffix with PART where the table gives the first.
    std::string suffix(f.file_suffix);
    if (const std::size_t part = suffix.find("PART"); part != std::string::npos) suffix.erase(part);
    CHECK(rows[i][1].rfind("`NAME" + suffix, 0) == 0);
    CHECK(kinds_named(rows[i][2]) == f.kinds);
    CHECK(kinds_named(rows[i][3]) == f.default_for);
  }
  // run --help lists the same names, in the same order.
  const CliResult help = run_fabmesh({"run", "--help"});
  std::string names;
  for (const OutputFormat& f : formats) names += (names.empty() ? "" : ", ") + std::string(f.name);
  CHECK_THAT(help.out, Catch::Contains("(" + names + ")"));
}
