#include "pipeline/batch/csv_cell.h"

#include <cstdlib>
#include <string>

namespace fabmesh {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

// Whether the whole of `text` is a decimal number (as strtod reads one, no
// inf or nan): such a cell is data, not a formula, whatever its sign.
bool is_number(std::string_view text) {
  if (text.empty() || text.find_first_not_of("+-.0123456789eE") != std::string_view::npos) return false;
  const std::string copy(text);
  char* end = nullptr;
  std::strtod(copy.c_str(), &end);
  return end == copy.c_str() + copy.size();
}

// Spreadsheets run a cell that starts with one of these as a formula.
bool starts_formula(std::string_view text) {
  return !text.empty() && std::string_view("=+-@\t\r").find(text.front()) != std::string_view::npos &&
         !is_number(text);
}

bool needs_quotes(std::string_view text) {
  return text.find_first_of(",\"\r\n") != std::string_view::npos ||
         (!text.empty() && (text.front() == ' ' || text.back() == ' '));
}

bool is_control(char c) {
  const auto u = static_cast<unsigned char>(c);
  return (u < 0x20 && c != '\t' && c != '\r' && c != '\n') || u == 0x7F;
}

}  // namespace

std::string csv_cell(std::string_view text) {
  std::string body = starts_formula(text) ? "'" : "";
  for (const char c : text) {
    if (is_control(c)) {
      body += kReplacement;
    } else {
      body += c;
    }
  }
  if (!needs_quotes(body)) return body;
  std::string out = "\"";
  for (const char c : body) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace fabmesh
