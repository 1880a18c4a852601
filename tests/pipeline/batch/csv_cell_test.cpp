// csv_cell: one CSV cell that a CSV reader gives back whole and a
// spreadsheet shows as text.

#include "pipeline/batch/csv_cell.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/io/mesh/external_tool.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;

namespace {

struct Case {
  std::string text;
  std::string shown;  ///< what a CSV reader must give back
};

const std::vector<Case>& hostile_cases() {
  static const std::vector<Case> cases = {
      {"plain", "plain"},
      {"", ""},
      {"a,b", "a,b"},
      {"\"quoted\"", "\"quoted\""},
      {"line\nbreak", "line\nbreak"},
      {"cr\r\nlf", "cr\r\nlf"},
      {" edge ", " edge "},
      {"$(touch PWNED)", "$(touch PWNED)"},
      {"`touch PWNED`", "`touch PWNED`"},
      {"<script>alert(1)</script>", "<script>alert(1)</script>"},
      {"=HYPERLINK(\"http://x\",\"y\")", "'=HYPERLINK(\"http://x\",\"y\")"},
      {"=1+2", "'=1+2"},
      {"+SUM(A1:A2)", "'+SUM(A1:A2)"},
      {"-2+3", "'-2+3"},
      {"@cmd", "'@cmd"},
      {"\t=1", "'\t=1"},
      {"-0.3", "-0.3"},
      {"+4", "+4"},
      {"-1e-05", "-1e-05"},
      {"cup_=1", "cup_=1"},
      {std::string("nul\0byte", 8),
       "nul\xEF\xBF\xBD"
       "byte"},
      {"bell\a", "bell\xEF\xBF\xBD"},
      {"caf\xC3\xA9", "caf\xC3\xA9"},
  };
  return cases;
}

}  // namespace

TEST_CASE("csv_cell: formulas stay text, numbers stay numbers", "[pipeline][batch]") {
  CHECK(csv_cell("=1+2") == "'=1+2");
  CHECK(csv_cell("-0.3") == "-0.3");
  CHECK(csv_cell("-D x") == "'-D x");
  CHECK(csv_cell("-") == "'-");
  CHECK(csv_cell("a,b") == "\"a,b\"");
  CHECK(csv_cell("=a,b") == "\"'=a,b\"");
  CHECK(csv_cell("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(csv_cell(std::string("\0", 1)) == "\xEF\xBF\xBD");
}

TEST_CASE("csv_cell: Python's csv module reads hostile names back whole", "[pipeline][batch]") {
  const std::filesystem::path dir = testing::fresh_dir("csv_cell");
  const std::filesystem::path csv = dir / "cells.csv";
  {
    std::ofstream out(csv, std::ios::binary);
    out << "index,text\n";
    for (std::size_t i = 0; i < hostile_cases().size(); ++i)
      out << i << "," << csv_cell(hostile_cases()[i].text) << "\n";
  }
  const test::ToolRun read = test::run_command(
      "/usr/bin/python3 -c 'import csv, json, sys\n"
      "rows = list(csv.DictReader(open(sys.argv[1], newline=\"\", encoding=\"utf-8\")))\n"
      "print(json.dumps([r[\"text\"] for r in rows]))' '" +
      csv.string() + "'");
  REQUIRE(read.code == 0);
  const auto cells = nlohmann::json::parse(read.output).get<std::vector<std::string>>();
  REQUIRE(cells.size() == hostile_cases().size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    INFO("case " << i);
    CHECK(cells[i] == hostile_cases()[i].shown);
  }
}
