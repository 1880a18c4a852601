#include "io/design/edit_values.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <optional>
#include <variant>

#include "geometry/core/errors.h"
#include "io/design/yaml/double_quoted.h"

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
  if (!parameters.IsDefined() || !parameters.IsMap()) return path;  // a missing key's node throws on IsMap
  const YAML::Node entry = parameters[path];
  if (!entry.IsDefined()) return path;
  return "parameters." + path + (entry.IsMap() ? ".value" : "");
}

// The node at `full` (a value_path) below `root`; an undefined node when the tree has none there.
YAML::Node node_at(const YAML::Node& root, const std::string& full) {
  YAML::Node node = root;
  for (const Step& step : path_steps(full)) {
    YAML::Node next;
    if (const auto* key = std::get_if<std::string>(&step)) {
      if (node.IsMap()) next = node[*key];
    } else if (node.IsSequence() && std::get<std::size_t>(step) < node.size()) {
      next = node[std::get<std::size_t>(step)];
    }
    if (!next.IsDefined()) return next;
    node.reset(next);
  }
  return node;
}

YAML::Node load_text(const std::string& text, const std::string& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw FileError(file, e.mark.line + 1, e.mark.column + 1,
                    fmt::format("{}:{}:{}: {}", file, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
}

// True when `a` and `b` are the same YAML values: the same kinds, scalars of
// the same text (quoted or plain: the reader takes either), lists and maps
// of the same entries in the same order.
bool same_value(const YAML::Node& a, const YAML::Node& b) {
  if (a.Type() != b.Type()) return false;
  if (a.IsScalar()) return a.Scalar() == b.Scalar();
  if (a.IsSequence()) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!same_value(a[i], b[i])) return false;
    }
    return true;
  }
  if (!a.IsMap()) return true;  // both null
  if (a.size() != b.size()) return false;
  auto i = a.begin();
  for (auto j = b.begin(); j != b.end(); ++i, ++j) {
    if (!same_value(i->first, j->first) || !same_value(i->second, j->second)) return false;
  }
  return true;
}

bool is_number(const std::string& text) {
  if (text.empty() || text.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
  char* end = nullptr;
  (void)std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

// `value` as YAML on one line that reads back the same wherever it is put,
// in a block or inside a flow list or map: numbers plain, other scalars in
// double quotes, lists and maps in flow style.
std::string flow_text(const YAML::Node& value) {
  std::string out;
  if (value.IsScalar())
    return value.Tag() == "?" && is_number(value.Scalar()) ? value.Scalar()
                                                           : yaml::double_quoted(value.Scalar());
  if (value.IsSequence()) {
    for (std::size_t i = 0; i < value.size(); ++i) out += (i == 0 ? "" : ", ") + flow_text(value[i]);
    return "[" + out + "]";
  }
  if (value.IsMap()) {
    for (const auto& kv : value) {
      // A key that is a plain name stays plain ("continuity"), as designs write keys.
      const std::string& key = kv.first.Scalar();
      const bool plain =
          kv.first.IsScalar() && !key.empty() && !is_number(key) &&
          key.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") ==
              std::string::npos &&
          key != "true" && key != "false" && key != "null" && key != "yes" && key != "no" && key != "on" &&
          key != "off" && key != "y" && key != "n" && key != "~";
      out += (out.empty() ? "" : ", ") + (plain ? key : flow_text(kv.first)) + ": " + flow_text(kv.second);
    }
    return "{" + out + "}";
  }
  return "null";
}

// `text`, and a line break at its end when it has none.
std::string ends_with_newline(const std::string& text) {
  return text.empty() || text.back() == '\n' ? text : text + "\n";
}

// `edited`, when it reads as `expected`; else a FileError: the edit would
// change more than it should (an edit fabmesh cannot place in this layout).
std::string checked_edit(const std::string& edited, const YAML::Node& expected, const std::string& file,
                         const std::string& what) {
  try {
    if (same_value(YAML::Load(edited), expected)) return edited;
  } catch (const YAML::Exception&) {
    // it breaks the file: refused below
  }
  throw FileError(file, 0, 0,
                  fmt::format("{}: {}: the value cannot be added in this file's layout; edit it in the file",
                              file, what));
}

// Where the flow map that starts at `begin` ('{') closes: the offset of its
// '}' (quotes, nested brackets and comments skipped); npos when it does not.
std::size_t flow_map_close(const std::string& text, std::size_t begin) {
  int depth = 0;
  for (std::size_t i = begin; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"' || c == '\'') {
      i = quoted_end(text, i);
      if (i == std::string::npos) return i;
      --i;
    } else if (c == '#' && i > 0 && (text[i - 1] == ' ' || text[i - 1] == '\t' || text[i - 1] == '\n')) {
      i = text.find('\n', i);
      if (i == std::string::npos) return i;
    } else if (c == '{' || c == '[') {
      ++depth;
    } else if ((c == '}' || c == ']') && --depth == 0) {
      return c == '}' ? i : std::string::npos;
    }
  }
  return std::string::npos;
}

// The offset just after the last line of the block map whose first key is
// at (line, column), 0-based: its entries and their values are the lines
// indented at least `column` (blank and comment lines between them too).
std::size_t block_map_end(const std::string& text, int line, int column) {
  std::size_t at = *offset_of(text, line, 0);
  std::size_t end = text.find('\n', at);
  end = end == std::string::npos ? text.size() : end + 1;
  for (std::size_t next = end; next < text.size();) {
    std::size_t stop = text.find('\n', next);
    stop = stop == std::string::npos ? text.size() : stop + 1;
    const std::size_t content = text.find_first_not_of(" \t\r\n", next);
    const bool blank = content == std::string::npos || content >= stop;
    if (!blank && text[content] != '#') {
      if (static_cast<int>(content - next) < column) break;
      end = stop;
    }
    next = stop;
  }
  return end;
}

// The top-level items of the flow list `value` ("[a, [b, c], \"d, e\"]"),
// each as written (trimmed); none when it is not one flow list.
std::optional<std::vector<std::string>> flow_items(const std::string& value) {
  const std::size_t open = value.find_first_not_of(" \t");
  if (open == std::string::npos || value[open] != '[') return std::nullopt;
  std::vector<std::string> items;
  const auto add = [&](std::size_t from, std::size_t to) {
    const std::size_t b = value.find_first_not_of(" \t", from);
    const std::size_t e = value.find_last_not_of(" \t", to - 1);
    if (b != std::string::npos && b < to) items.push_back(value.substr(b, e + 1 - b));
  };
  int depth = 0;  // of lists and maps
  std::size_t start = open + 1;
  for (std::size_t i = open; i < value.size(); ++i) {
    const char c = value[i];
    if (c == '"' || c == '\'') {
      i = quoted_end(value, i);
      if (i == std::string::npos) return std::nullopt;
      --i;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      if (--depth < 0) return std::nullopt;
      if (depth == 0) {
        if (c != ']' || value.find_first_not_of(" \t", i + 1) != std::string::npos) return std::nullopt;
        add(start, i);
        return items;
      }
    } else if (c == ',' && depth == 1) {
      add(start, i);
      start = i + 1;
    } else if (c == '#' || c == '\n') {
      return std::nullopt;
    }
  }
  return std::nullopt;
}

// The offset where the line holding `offset` starts, and where the next one does.
std::pair<std::size_t, std::size_t> line_of(const std::string& text, std::size_t offset) {
  const std::size_t begin = offset == 0 ? 0 : text.rfind('\n', offset - 1) + 1;  // npos + 1 == 0
  const std::size_t end = text.find('\n', offset);
  return {begin, end == std::string::npos ? text.size() : end + 1};
}

// `text` with the block list at `o.path` (`- item` items) changed into the
// flow list `o.value` item by item: the items both lists have, in the same
// order, keep their lines (and comments) as written, an item over several
// lines (a segment's map) all of them; the others' lines go, and new items
// get a line of their own, in flow style, indented as their neighbours. The
// edit a designer makes when adding or deleting a control point or a
// segment. Nullopt when the list is not written so (an item not on its
// dash's line): the caller then refuses the edit.
std::optional<std::string> edit_block_list(const std::string& text, const YAML::Node& old,
                                           const YAML::Node& wanted, const Override& o) {
  const std::optional<std::vector<std::string>> given = flow_items(o.value);
  if (!given || given->size() != wanted.size() || old.size() == 0) return std::nullopt;
  struct Item {
    std::size_t line_begin, line_end;  // its lines, from its dash to its last, with their comments
    std::string prefix;                // the indentation and "- " before it
    std::size_t dash;                  // the dash's column
  };
  std::vector<Item> items;
  for (std::size_t i = 0; i < old.size(); ++i) {
    const YAML::Mark mark = old[i].Mark();
    const std::optional<std::size_t> at = offset_of(text, mark.line, mark.column);
    if (!at) return std::nullopt;
    const auto [begin, end] = line_of(text, *at);
    const std::string prefix = text.substr(begin, *at - begin);
    const std::size_t dash = prefix.find_first_not_of(' ');
    // The item starts on its dash's line: "  - item".
    const bool after_dash = dash != std::string::npos && prefix[dash] == '-' &&
                            prefix.find_first_not_of(' ', dash + 1) == std::string::npos &&
                            prefix.size() > dash + 1;
    if (!after_dash || (!items.empty() && begin < items.back().line_end)) return std::nullopt;
    items.push_back({begin, end, prefix, dash});
  }
  // Each item's last line: the last one before the next item (or the list's
  // end) indented beyond its dash, comment lines aside (a comment between two
  // items stays between them).
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::size_t limit = i + 1 < items.size() ? items[i + 1].line_begin : text.size();
    for (std::size_t next = items[i].line_end; next < limit;) {
      std::size_t stop = text.find('\n', next);
      stop = stop == std::string::npos ? text.size() : std::min(stop + 1, limit);
      const std::size_t content = text.find_first_not_of(" \t\r\n", next);
      if (content != std::string::npos && content < stop && text[content] != '#') {
        if (content - next <= items[i].dash) break;  // a line of the block around the list
        items[i].line_end = stop;
      }
      next = stop;
    }
  }
  // The longest run of items kept in order (equal values), by dynamic programming.
  const std::size_t n = old.size(), m = wanted.size();
  if (n * m > 1000000) return std::nullopt;
  std::vector<std::vector<std::size_t>> keep(n + 1, std::vector<std::size_t>(m + 1, 0));
  for (std::size_t i = n; i-- > 0;) {
    for (std::size_t j = m; j-- > 0;) {
      keep[i][j] =
          same_value(old[i], wanted[j]) ? keep[i + 1][j + 1] + 1 : std::max(keep[i + 1][j], keep[i][j + 1]);
    }
  }
  // The last item's line may end the file without a line break.
  const std::string t = ends_with_newline(text);
  if (items.back().line_end == text.size()) items.back().line_end = t.size();
  std::string edited = t.substr(0, items.front().line_begin);
  std::string prefix = items.front().prefix;
  std::size_t i = 0, j = 0;
  while (i < n || j < m) {
    const bool kept = i < n && j < m && same_value(old[i], wanted[j]) && keep[i][j] == keep[i + 1][j + 1] + 1;
    if (!kept && j < m && (i == n || keep[i][j + 1] >= keep[i + 1][j])) {
      edited += prefix + (*given)[j++] + "\n";  // a new item, indented as the one before it
      continue;
    }
    // What lies between the previous item and this one (a comment line) stays, above it.
    if (i > 0) edited += t.substr(items[i - 1].line_end, items[i].line_begin - items[i - 1].line_end);
    if (kept) {
      edited += t.substr(items[i].line_begin, items[i].line_end - items[i].line_begin);
      ++j;
    }  // else the old item's lines go
    prefix = items[i].prefix;
    ++i;
  }
  edited += t.substr(items.back().line_end);
  if (t.size() != text.size() && !edited.empty() && edited.back() == '\n') edited.pop_back();
  return edited;
}

// `text` with the value at `o.path` replaced by `o.value`: as the user wrote
// it when the file then reads back as the old tree with that value at the
// path, else in flow_text's form (an expression "=max(w, 5)" goes into a flow
// map `{value: 4}` quoted, or its comma would end the value).
std::string edit_value(const std::string& text, const std::string& file, const Override& o) {
  if (o.value.find_first_of("\r\n") != std::string::npos) {
    throw FileError(file, 0, 0, fmt::format("{}: {}: the new value is not one line", file, o.path));
  }
  YAML::Node wanted;
  try {
    wanted = YAML::Load(o.value);
  } catch (const YAML::Exception& e) {
    throw FileError(file, 0, 0, fmt::format("-D {}: the value is not valid YAML: {}", o.text, e.msg));
  }
  // A top-level key the design does not write yet (`parameter_set`): a new last line.
  if (o.path.find_first_of(".[") == std::string::npos) {
    const YAML::Node root = load_text(text, file);
    if (root.IsMap() && !root[o.path].IsDefined() && value_path(root, o.path) == o.path) {
      YAML::Node expected = YAML::Clone(root);
      expected[o.path] = wanted;
      // As given when it reads back so, else in flow_text's form.
      std::string as_given = ends_with_newline(text);
      as_given.append(o.path).append(": ").append(o.value).append("\n");
      try {
        if (same_value(YAML::Load(as_given), expected)) return as_given;
      } catch (const YAML::Exception&) {
        // not as given: below
      }
      return checked_edit(ends_with_newline(text) + o.path + ": " + flow_text(wanted) + "\n", expected, file,
                          o.path);
    }
  }
  {
    // A list written as `- item` lines, changed item by item (a point added or deleted).
    const YAML::Node root = load_text(text, file);
    const YAML::Node old = node_at(root, value_path(root, o.path));
    if (old.IsDefined() && old.IsSequence() && old.Style() == YAML::EmitterStyle::Block &&
        wanted.IsSequence()) {
      YAML::Node expected = YAML::Clone(root);
      YAML::Node at = node_at(expected, value_path(expected, o.path));
      at = wanted;
      if (const std::optional<std::string> edited = edit_block_list(text, old, wanted, o))
        return checked_edit(*edited, expected, file, o.path);
    }
  }
  const ValueSpan span = value_span(text, file, o.path);
  // The tree the edited text must read as.
  const YAML::Node expected = YAML::Clone(load_text(text, file));
  YAML::Node at = node_at(expected, value_path(expected, o.path));
  at = wanted;
  for (const std::string& written : {o.value, flow_text(wanted)}) {
    std::string edited = text.substr(0, span.begin) + written + text.substr(span.end);
    try {
      if (same_value(YAML::Load(edited), expected)) return edited;
    } catch (const YAML::Exception&) {
      // as written it breaks the file: try the next form
    }
  }
  throw FileError(file, span.line, span.column,
                  fmt::format("{}:{}:{}: {}: the value cannot be written there; edit it in the file", file,
                              span.line, span.column, o.path));
}

}  // namespace

ValueSpan value_span(const std::string& text, const std::string& file, const std::string& path) {
  const YAML::Node root = load_text(text, file);
  const std::string full = value_path(root, path);
  const YAML::Node node = node_at(root, full);
  if (!node.IsDefined()) {
    throw FileError(file, 0, 0, fmt::format("{}: {}: the design does not write this value", file, full));
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

std::vector<std::pair<std::string, std::string>> flow_entries(const std::string& text,
                                                              const std::string& file,
                                                              const std::string& path) {
  const YAML::Node root = load_text(text, file);
  const YAML::Node node = node_at(root, value_path(root, path));
  if (!node.IsDefined() || !node.IsMap())
    throw FileError(file, 0, 0, fmt::format("{}: {}: the design writes no map there", file, path));
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& entry : node) out.emplace_back(entry.first.Scalar(), flow_text(entry.second));
  return out;
}

std::string add_parameter_set(const std::string& text, const std::string& file, const std::string& name,
                              const std::vector<std::pair<std::string, std::string>>& values) {
  const YAML::Node root = load_text(text, file);
  if (!root.IsMap()) throw FileError(file, 0, 0, fmt::format("{}: the design is not a YAML map", file));
  std::string entry;
  for (const auto& [parameter, value] : values)
    entry.append(entry.empty() ? "" : ", ").append(parameter).append(": ").append(value);
  entry = name + ": {" + entry + "}";
  YAML::Node added;
  try {
    added = YAML::Load("{" + entry + "}");
  } catch (const YAML::Exception& e) {
    throw FileError(file, 0, 0, fmt::format("{}: parameter set '{}': not YAML: {}", file, name, e.msg));
  }
  const YAML::Node sets = root["parameter_sets"];
  if (sets.IsDefined() && sets.IsMap() && sets[name].IsDefined()) {
    const YAML::Mark m = sets[name].Mark();
    throw FileError(
        file, m.line + 1, m.column + 1,
        fmt::format("{}:{}:{}: parameter_sets.{}: the design has this set already: choose another "
                    "name, or edit the set in the file",
                    file, m.line + 1, m.column + 1, name));
  }
  YAML::Node expected = YAML::Clone(root);
  expected["parameter_sets"][name] = added[name];
  std::string edited;
  if (!sets.IsDefined()) {
    edited = ends_with_newline(text) + "parameter_sets:\n  " + entry + "\n";
  } else if (sets.IsMap() && sets.Style() == YAML::EmitterStyle::Flow) {  // defined: not the first branch
    const std::optional<std::size_t> open = offset_of(text, sets.Mark().line, sets.Mark().column);
    const std::size_t close = open ? flow_map_close(text, *open) : std::string::npos;
    if (close != std::string::npos)
      edited = text.substr(0, close) + (sets.size() == 0 ? "" : ", ") + entry + text.substr(close);
  } else if (sets.IsMap() && sets.size() > 0) {
    const std::size_t end = block_map_end(text, sets.Mark().line, sets.Mark().column);
    const std::string before = ends_with_newline(text.substr(0, end));
    edited = before + std::string(static_cast<std::size_t>(sets.Mark().column), ' ') + entry + "\n" +
             text.substr(end);
  }
  return checked_edit(edited, expected, file, "parameter_sets." + name);
}

std::string edit_values(const std::string& text, const std::string& file,
                        const std::vector<Override>& values) {
  std::string edited = text;
  for (const Override& o : values) edited = edit_value(edited, file, o);
  return edited;
}

}  // namespace fabmesh
