#include "io/dxf/dxf_groups.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

// At most this much of a value is quoted in a message.
constexpr std::size_t kQuoted = 40;

std::string quoted(std::string_view value) {
  return value.size() <= kQuoted ? std::string(value) : std::string(value.substr(0, kQuoted)) + "...";
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  return s;
}

// The value without one leading '+' (from_chars takes none).
std::string_view unsigned_form(std::string_view s) {
  if (s.size() > 1 && s.front() == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
  return s;
}

}  // namespace

std::optional<double> dxf_number(std::string_view value) {
  const std::string_view text = unsigned_form(value);
  double out = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty() || !std::isfinite(out))
    return std::nullopt;
  return out;
}

std::optional<long long> dxf_integer(std::string_view value) {
  const std::string_view text = unsigned_form(value);
  long long out = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return out;
}

DxfGroupReader::DxfGroupReader(std::string_view bytes, std::string path)
    : bytes_(bytes),
      path_(std::move(path)),
      lines_(static_cast<std::size_t>(std::count(bytes.begin(), bytes.end(), '\n')) + 1) {}

std::string_view DxfGroupReader::next_line() {
  const std::size_t nl = bytes_.find('\n', pos_);
  const std::size_t end = nl == std::string_view::npos ? bytes_.size() : nl;
  const std::string_view s = bytes_.substr(pos_, end - pos_);
  pos_ = nl == std::string_view::npos ? bytes_.size() : nl + 1;
  ++line_;
  return trimmed(s);
}

bool DxfGroupReader::next(DxfGroup& group) {
  if (pos_ >= bytes_.size()) return false;
  const std::size_t code_line = line_ + 1;
  const std::string_view code_text = next_line();
  if (code_text.empty() && pos_ >= bytes_.size()) return false;  // the last line break
  int code = 0;
  const auto [end, ec] = std::from_chars(code_text.data(), code_text.data() + code_text.size(), code);
  if (ec != std::errc() || end != code_text.data() + code_text.size()) {
    fail(code_line, fmt::format("'{}' is not a DXF group code{}", quoted(code_text),
                                first_ ? ": the file is not a DXF drawing" : ""));
  }
  if (pos_ >= bytes_.size()) {
    fail(code_line, fmt::format("group code {} has no value: the file ends there (it is cut short)", code));
  }
  group.code = code;
  group.value = next_line();
  group.line = code_line;
  if (first_ && code != 999 && !(code == 0 && group.value == "SECTION")) {
    throw FileError(path_, static_cast<int>(code_line), 1,
                    fmt::format("{}: the file does not start with a DXF SECTION: not a DXF drawing", path_));
  }
  first_ = false;
  return true;
}

void DxfGroupReader::bad_value(const DxfGroup& group, std::string_view what, std::string_view kind) const {
  fail(group.line + 1,
       fmt::format("{}: group {}: '{}' is not {}", what, group.code, quoted(group.value), kind));
}

void DxfGroupReader::fail(std::size_t line, const std::string& why) const {
  throw FileError(path_, static_cast<int>(line), 1, fmt::format("{}:{}: {}", path_, line, why));
}

}  // namespace fabmesh
