#include "io/design/csv_table.h"

#include <fmt/format.h>

#include <set>

#include "geometry/core/errors.h"
#include "io/file.h"

namespace fabmesh {
namespace {

constexpr std::size_t kMaxTableBytes = 64u << 20;

class Scanner {
 public:
  Scanner(std::string_view text, const std::string& path) : text_(text), path_(path) {}

  bool done() const { return pos_ >= text_.size(); }

  // One record (a row of cells); an empty vector for a blank line.
  std::vector<CsvCell> record() {
    std::vector<CsvCell> cells;
    if (at_line_end()) {
      skip_line_end();
      return cells;
    }
    while (true) {
      cells.push_back(cell());
      if (done() || at_line_end()) break;
      ++pos_, ++column_;  // the comma
    }
    skip_line_end();
    return cells;
  }

  [[noreturn]] void fail(int line, int column, const std::string& message) const {
    throw FileError(path_, line, column, fmt::format("{}:{}:{}: {}", path_, line, column, message));
  }

 private:
  bool at_line_end() const { return !done() && (text_[pos_] == '\n' || text_[pos_] == '\r'); }

  void skip_line_end() {
    if (done()) return;
    if (text_[pos_] == '\r') ++pos_;
    if (!done() && text_[pos_] == '\n') ++pos_;
    ++line_;
    column_ = 1;
  }

  void skip_spaces() {
    while (!done() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_, ++column_;
  }

  CsvCell cell() {
    skip_spaces();
    CsvCell c{"", line_, column_};
    if (!done() && text_[pos_] == '"') return quoted(c);
    while (!done() && text_[pos_] != ',' && !at_line_end()) {
      if (text_[pos_] == '"') fail(line_, column_, "a quote inside an unquoted cell (quote the whole cell)");
      refuse_nul();
      c.text += text_[pos_];
      ++pos_, ++column_;
    }
    while (!c.text.empty() && (c.text.back() == ' ' || c.text.back() == '\t')) c.text.pop_back();
    return c;
  }

  CsvCell quoted(CsvCell c) {
    ++pos_, ++column_;  // the opening quote
    while (true) {
      if (done()) fail(c.line, c.column, "this quoted cell is never closed");
      const char ch = text_[pos_];
      refuse_nul();
      if (ch == '"') {
        if (pos_ + 1 < text_.size() && text_[pos_ + 1] == '"') {
          c.text += '"';
          pos_ += 2, column_ += 2;
          continue;
        }
        ++pos_, ++column_;
        break;
      }
      c.text += ch;
      ++pos_, ++column_;
      if (ch == '\n') ++line_, column_ = 1;
    }
    skip_spaces();
    if (!done() && text_[pos_] != ',' && !at_line_end())
      fail(line_, column_, "text after a closing quote (a cell is quoted whole)");
    return c;
  }

  // A NUL byte is no text: every message quoting the cell would end at it.
  void refuse_nul() const {
    if (text_[pos_] == '\0') fail(line_, column_, "a NUL byte in a cell: a table is text");
  }

  std::string_view text_;
  const std::string& path_;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1;
};

}  // namespace

CsvTable parse_csv_table(std::string_view text, const std::string& path) {
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF")
    text.remove_prefix(3);  // a UTF-8 byte order mark
  Scanner scan(text, path);
  CsvTable table;
  while (!scan.done() && table.header.empty()) table.header = scan.record();
  if (table.header.empty())
    throw FileError(path, 0, 0, fmt::format("{}: the table is empty (no header row)", path));
  std::set<std::string> seen;
  for (const CsvCell& h : table.header) {
    if (h.text.empty()) scan.fail(h.line, h.column, "an empty column name in the header");
    if (!seen.insert(h.text).second)
      scan.fail(h.line, h.column, fmt::format("the column '{}' is repeated", h.text));
  }
  while (!scan.done()) {
    std::vector<CsvCell> row = scan.record();
    if (row.empty() || (row.size() == 1 && row[0].text.empty())) continue;  // a blank line
    if (row.size() != table.header.size()) {
      scan.fail(row.front().line, 1,
                fmt::format("this row has {} cell(s), the header has {}", row.size(), table.header.size()));
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

CsvTable read_csv_table(const std::string& path) {
  return parse_csv_table(read_file(path, kMaxTableBytes, "table"), path);
}

}  // namespace fabmesh
