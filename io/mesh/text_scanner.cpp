#include "io/mesh/text_scanner.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r' || c == '\n'; }

std::string printable(std::string_view token) {
  std::string out;
  for (const char c : token.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
  if (token.size() > 40) out += "...";
  return out;
}

}  // namespace

TextScanner::TextScanner(std::string_view data, std::string name, int first_line)
    : data_(data), name_(std::move(name)), line_(first_line - 1) {}

bool TextScanner::next_line(std::string_view& line) {
  if (pos_ >= data_.size()) return false;
  std::size_t end = pos_;
  while (end < data_.size() && data_[end] != '\n' && data_[end] != '\r') ++end;
  line = data_.substr(pos_, end - pos_);
  if (end < data_.size() && data_[end] == '\r') {
    ++end;
    if (end < data_.size() && data_[end] == '\n') ++end;
  } else if (end < data_.size()) {
    ++end;  // '\n'
  }
  pos_ = end;
  ++line_;
  return true;
}

bool TextScanner::next_content_line(std::string_view& line, char comment) {
  while (next_line(line)) {
    if (comment != '\0') {
      const std::size_t c = line.find(comment);
      if (c != std::string_view::npos) line = line.substr(0, c);
    }
    std::string_view probe = line;
    if (!next_token(probe).empty()) return true;
  }
  return false;
}

void TextScanner::fail(const std::string& message) const {
  throw FileError(name_, line_, 0, fmt::format("{}:{}: {}", name_, line_, message));
}

double TextScanner::to_double(std::string_view token, const char* what) const {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || token.empty()) {
    fail(fmt::format("{}: '{}' is not a number", what, printable(token)));
  }
  if (!std::isfinite(value)) fail(fmt::format("{}: '{}' is not a finite number", what, printable(token)));
  return value;
}

std::int64_t TextScanner::to_int(std::string_view token, const char* what) const {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || token.empty()) {
    fail(fmt::format("{}: '{}' is not an integer", what, printable(token)));
  }
  return value;
}

std::string_view next_token(std::string_view& rest) {
  std::size_t b = 0;
  while (b < rest.size() && is_space(rest[b])) ++b;
  std::size_t e = b;
  while (e < rest.size() && !is_space(rest[e])) ++e;
  const std::string_view token = rest.substr(b, e - b);
  rest.remove_prefix(e);
  return token;
}

}  // namespace fabmesh
