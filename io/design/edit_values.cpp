#include "io/design/edit_values.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <map>
#include <optional>
#include <variant>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

using Step = std::variant<std::string, std::size_t>;  // a map key or a list index

// The steps of a -D path ("profile.segments[1].lambda"); parse_override has
// already checked its form, so this only splits it.
std::vector<Step> path_steps(const std::string& path) {
  std::vector<Step> steps;
  std::size_t i = 0;
  while (i < path.size()) {
    if (path[i] == '.') {
      ++i;
    } else if (path[i] == '[') {
      const std::size_t close = path.find(']', i);
      steps.emplace_back(static_cast<std::size_t>(std::stoul(path.substr(i + 1, close - i - 1))));
      i = close + 1;
    } else {
      const std::size_t end = path.find_first_of(".[", i);
      steps.emplace_back(path.substr(i, end == std::string::npos ? std::string::npos : end - i));
      i = end == std::string::npos ? path.size() : end;
    }
  }
  return steps;
}

// The byte offset of 0-based (line, column) in `text`, when the text has it.
std::optional<std::size_t> offset_of(const std::string& text, int line, int column) {
  std::size_t at = 0;
  for (int l = 0; l < line; ++l) {
    at = text.find('\n', at);
    if (at == std::string::npos) return std::nullopt;
    ++at;
  }
  const std::size_t offset = at + static_cast<std::size_t>(column);
  if (offset > text.size()) return std::nullopt;
  return offset;
}

// Where the quoted scalar that starts at `begin` ends: after its closing
// quote; npos when it does not end on its line.
std::size_t quoted_end(const std::string& text, std::size_t begin) {
  const char quote = text[begin];
  for (std::size_t i = begin + 1; i < text.size(); ++i) {
    if (text[i] == '\n') return std::string::npos;  // a quoted scalar over several lines
    if (quote == '"' && text[i] == '\\') {
      ++i;
    } else if (text[i] == quote) {
      if (quote == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
        ++i;  // '' is a quote inside single quotes
        continue;
      }
      return i + 1;
    }
  }
  return std::string::npos;
}

// Where the flow sequence that starts at `begin` ('[') ends: after its
// closing bracket, when it is on the same line; npos otherwise.
std::size_t flow_sequence_end(const std::string& text, std::size_t begin) {
  int depth = 0;
  for (std::size_t i = begin; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n' || c == '#' || c == '{') return std::string::npos;
    if (c == '"' || c == '\'') {
      i = quoted_end(text, i);
      if (i == std::string::npos) return i;
      --i;
    } else if (c == '[') {
      ++depth;
    } else if (c == ']' && --depth == 0) {
      return i + 1;
    }
  }
  return std::string::npos;
}

// Where a scalar that starts at `begin` ends: after its closing quote, or
// after its plain text when the text there is `scalar`. npos when neither.
std::size_t scalar_end(const std::string& text, std::size_t begin, const std::string& scalar) {
  if (begin >= text.size()) return std::string::npos;
  if (text[begin] == '"' || text[begin] == '\'') return quoted_end(text, begin);
  if (!scalar.empty() && text.compare(begin, scalar.size(), scalar) == 0) return begin + scalar.size();
  return std::string::npos;
}

// The path as the reader takes it: a declared parameter's name stands for its value.
std::string value_path(const YAML::Node& root, const std::string& path) {
  if (path.find_first_of(".[") != std::string::npos) return path;
  const YAML::Node parameters = root["parameters"];
  if (!parameters.IsMap()) return path;
  const YAML::Node entry = parameters[path];
  if (!entry.IsDefined()) return path;
  return "parameters." + path + (entry.IsMap() ? ".value" : "");
}

}  // namespace

ValueSpan value_span(const std::string& text, const std::string& file, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw FileError(file, e.mark.line + 1, e.mark.column + 1,
                    fmt::format("{}:{}:{}: {}", file, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  const std::string full = value_path(root, path);
  YAML::Node node = root;
  for (const Step& step : path_steps(full)) {
    YAML::Node next;
    if (const auto* key = std::get_if<std::string>(&step)) {
      if (node.IsMap()) next = node[*key];
    } else if (node.IsSequence() && std::get<std::size_t>(step) < node.size()) {
      next = node[std::get<std::size_t>(step)];
    }
    if (!next.IsDefined()) {
      throw FileError(file, 0, 0, fmt::format("{}: {}: the design does not write this value", file, full));
    }
    node.reset(next);
  }
  const YAML::Mark mark = node.Mark();
  const std::string where = fmt::format("{}:{}:{}", file, mark.line + 1, mark.column + 1);
  const std::optional<std::size_t> begin = offset_of(text, mark.line, mark.column);
  // A list written [a, b] on one line (a point) is replaced whole.
  const bool flow_list = node.IsSequence() && begin && *begin < text.size() && text[*begin] == '[';
  if (!node.IsScalar() && !flow_list) {
    throw FileError(
        file, mark.line + 1, mark.column + 1,
        fmt::format("{}: {}: the value is not a single number, text or [list] on one line", where, full));
  }
  std::size_t end = std::string::npos;
  if (begin) end = flow_list ? flow_sequence_end(text, *begin) : scalar_end(text, *begin, node.Scalar());
  if (end == std::string::npos) {
    throw FileError(
        file, mark.line + 1, mark.column + 1,
        fmt::format("{}: {}: the value is not written on one line; edit it in the file", where, full));
  }
  return ValueSpan{*begin, end, mark.line + 1, mark.column + 1};
}

std::string edit_values(const std::string& text, const std::string& file,
                        const std::vector<Override>& values) {
  std::map<std::size_t, std::pair<ValueSpan, std::string>> edits;  // by where they start
  for (const Override& o : values) {
    if (o.value.find_first_of("\r\n") != std::string::npos) {
      throw FileError(file, 0, 0, fmt::format("{}: {}: the new value is not one line", file, o.path));
    }
    const ValueSpan span = value_span(text, file, o.path);
    edits[span.begin] = {span, o.value};
  }
  std::string out;
  out.reserve(text.size());
  std::size_t at = 0;
  for (const auto& [begin, edit] : edits) {
    out.append(text, at, begin - at);
    out += edit.second;
    at = edit.first.end;
  }
  out.append(text, at, std::string::npos);
  return out;
}

}  // namespace fabmesh
