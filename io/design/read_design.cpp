#include "io/design/read_design.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <type_traits>
#include <utility>

#include "geometry/core/error_checks.h"
#include "geometry/core/units.h"
#include "io/design/number_limits.h"
#include "io/design/utf8.h"
#include "io/design/yaml/design_tree.h"
#include "io/design/yaml/fields.h"
#include "io/design/yaml/node_budget.h"
#include "io/design/yaml/parameter_sets.h"
#include "io/design/yaml/read_countertop.h"
#include "io/design/yaml/read_curve.h"
#include "io/design/yaml/read_surface.h"
#include "io/design/yaml/read_vessel.h"
#include "io/file.h"

namespace fabmesh {
namespace {

// Reading a design stays within a stated memory bound (docs/design-files.md):
// yaml-cpp spends about 470 bytes per node, so the node count is what bounds
// the tree; the byte limit (kMaxDesignFileBytes) bounds the text and long scalars.
constexpr std::size_t kMaxDesignNodes = 1u << 18;
constexpr std::size_t kMaxNameBytes = 120;

template <class Body>
struct KindTag {};

// One reader per kind: a DesignBody alternative without one does not compile.
CurveDesign read_kind(KindTag<CurveDesign>, const yaml::Fields& f, const YAML::Node& root,
                      const DesignCommon&) {
  return CurveDesign{read_curve(f, f.required(root, "curve", "curve"), "curve")};
}
VesselDesign read_kind(KindTag<VesselDesign>, const yaml::Fields& f, const YAML::Node& root,
                       const DesignCommon& common) {
  return read_vessel(f, root, common);
}
CountertopDesign read_kind(KindTag<CountertopDesign>, const yaml::Fields& f, const YAML::Node& root,
                           const DesignCommon& common) {
  return read_countertop(f, root, common);
}
SurfaceDesign read_kind(KindTag<SurfaceDesign>, const yaml::Fields& f, const YAML::Node& root,
                        const DesignCommon&) {
  return read_surface(f, root);
}

// The alternative of DesignBody whose kKind is `kind`, read from `root`.
template <std::size_t I = 0>
DesignBody read_body(const std::string& kind, const yaml::Fields& f, const YAML::Node& root,
                     const DesignCommon& common) {
  if constexpr (I == std::variant_size_v<DesignBody>) {
    std::string names;
    for (const std::string& n : kind_names()) names += (names.empty() ? "" : ", ") + n;
    f.fail(root["kind"], "kind", fmt::format("'{}' is not one of: {}", kind, names));
  } else {
    using Body = std::variant_alternative_t<I, DesignBody>;
    if (kind != Body::kKind) return read_body<I + 1>(kind, f, root, common);
    f.require_map(root, "", key_group(Body::kKind));
    return read_kind(KindTag<Body>{}, f, root, common);
  }
}

// One step of an override's path: a map key or a list index.
struct PathStep {
  std::string key;
  std::size_t index = 0;
  bool is_index = false;
};

std::vector<PathStep> path_steps(const std::string& path) {
  std::vector<PathStep> steps;
  for (std::size_t i = 0; i < path.size();) {
    if (path[i] == '.') {
      ++i;
    } else if (path[i] == '[') {
      const std::size_t close = path.find(']', i);
      steps.push_back({"", static_cast<std::size_t>(std::stoul(path.substr(i + 1, close - i - 1))), true});
      i = close + 1;
    } else {
      std::size_t j = i;
      while (j < path.size() && path[j] != '.' && path[j] != '[') ++j;
      steps.push_back({path.substr(i, j - i), 0, false});
      i = j;
    }
  }
  return steps;
}

// Puts `value` at `o.path` in the tree; maps on the way are created when missing.
// NOLINTNEXTLINE(performance-unnecessary-value-param): a handle, the tree is changed through it
void apply_override(YAML::Node root, const Override& o, const YAML::Node& value) {
  const std::vector<PathStep> steps = path_steps(o.path);
  YAML::Node cur = root;
  std::string where;  // the path walked so far, for messages
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const PathStep& step = steps[i];
    const bool last = i + 1 == steps.size();
    if (step.is_index) {
      if (!cur.IsSequence()) {
        throw FileError("", 0, 0,
                        fmt::format("-D {}: {} is not a list", o.text, where.empty() ? "the design" : where));
      }
      if (step.index >= cur.size()) {
        throw FileError("", 0, 0,
                        fmt::format("-D {}: {} has {} entries; [{}] is out of range", o.text, where,
                                    cur.size(), step.index));
      }
      where += fmt::format("[{}]", step.index);
      if (last) {
        cur[step.index] = value;
        return;
      }
      YAML::Node next = cur[step.index];
      cur.reset(next);
      continue;
    }
    if (!cur.IsMap() && !(cur.IsNull() && i > 0)) {
      throw FileError("", 0, 0,
                      fmt::format("-D {}: {} is not a map (it has no key '{}')", o.text,
                                  where.empty() ? "the design" : where, step.key));
    }
    where += (where.empty() ? "" : ".") + step.key;
    if (last) {
      cur[step.key] = value;
      return;
    }
    if (!cur[step.key].IsDefined()) cur[step.key] = YAML::Node(YAML::NodeType::Map);
    YAML::Node next = cur[step.key];
    cur.reset(next);
  }
}

// `o`, or for `-D NAME=VALUE` naming a parameter the design declares, the
// override of that parameter's value (`parameters.NAME`, or
// `parameters.NAME.value` when it is declared with a range).
Override parameter_path(const YAML::Node& root, const Override& o) {
  if (o.path.find_first_of(".[") != std::string::npos) return o;
  const YAML::Node parameters = root["parameters"];
  if (!parameters.IsDefined() || !parameters.IsMap()) return o;
  const YAML::Node entry = parameters[o.path];
  if (!entry.IsDefined()) return o;
  Override to_parameter = o;
  to_parameter.path = "parameters." + o.path + (entry.IsMap() ? ".value" : "");
  return to_parameter;
}

// Why `name` is not a plain file name (empty when it is). Names become file
// names in the output folder: nothing that could leave it, hide a file or
// break a message.
std::string name_problem(const std::string& name) {
  if (name.empty()) return "it is empty";
  if (name.size() > kMaxNameBytes) return fmt::format("it is longer than {} bytes", kMaxNameBytes);
  if (name.front() == '.' || name.front() == '-' || name.front() == ' ')
    return "it starts with '.', '-' or a space";
  if (name.back() == ' ' || name.back() == '.') return "it ends with a space or '.'";
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '_' || c == '-' || c == '.' || c == '+' || c == ' ' || c == '(' || c == ')';
    if (plain) continue;
    if (c < 0x80) return fmt::format("it contains the character {:#04x}", c);
    // A UTF-8 sequence of 2 to 4 bytes (letters beyond ASCII: "tasse_à_café").
    const int length = c >= 0xf0 && c < 0xf5 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 && c < 0xe0 ? 2 : 0;
    if (length == 0 || i + static_cast<std::size_t>(length) > name.size()) return "it is not valid UTF-8";
    for (int k = 1; k < length; ++k) {
      if ((static_cast<unsigned char>(name[i + static_cast<std::size_t>(k)]) & 0xc0) != 0x80)
        return "it is not valid UTF-8";
    }
    i += static_cast<std::size_t>(length - 1);
  }
  return "";
}

DesignCommon read_common(const yaml::Fields& f, const YAML::Node& root) {
  DesignCommon c;
  c.path = f.path();
  c.name = f.text_or(root, "name", "name", std::filesystem::path(f.path()).stem().string());
  if (const std::string problem = name_problem(c.name); !problem.empty()) {
    const std::string shown = fmt::format("{:?}", c.name);
    f.fail(root["name"].IsDefined() ? root["name"] : root, "name",
           fmt::format(
               "{} is not a plain file name: {} (names use letters, digits, spaces and _ - . + ( ), at most "
               "{} bytes, and do not start with '.', '-' or a space{})",
               shown, problem, kMaxNameBytes,
               root["name"].IsDefined() ? "" : "; the default name is the file's; set `name:`"));
  }
  c.units =
      f.choice(root["units"].IsDefined() ? root["units"] : YAML::Node("mm"), "units", length_unit_names());
  c.export_units = f.choice(root["export_units"].IsDefined() ? root["export_units"] : YAML::Node("mm"),
                            "export_units", length_unit_names());
  if (root["purpose"].IsDefined()) {
    c.purpose = f.choice(root["purpose"], "purpose", {"fabrication", "view"}) == "view"
                    ? Purpose::View
                    : Purpose::Fabrication;
  }
  if (root["on_output_error"].IsDefined()) {
    c.on_output_error = f.choice(root["on_output_error"], "on_output_error", {"skip", "fail"}) == "fail"
                            ? OutputErrorPolicy::Fail
                            : OutputErrorPolicy::Skip;
  }
  c.tolerance = f.number_or(root, "tolerance", "tolerance", 0.01);
  if (c.tolerance <= 0.0) {
    f.fail(root["tolerance"], "tolerance", fmt::format("tolerance = {} must be > 0", c.tolerance));
  }
  if (c.tolerance < kMinDesignTolerance) {
    // As written (a subnormal like 4.9e-324 must not read as "0").
    f.fail(root["tolerance"], "tolerance",
           fmt::format("tolerance = {} is below {:g}, the smallest tolerance fabmesh accepts",
                       root["tolerance"].Scalar(), kMinDesignTolerance));
  }
  if (root["outputs"].IsDefined()) {
    const YAML::Node outs = root["outputs"];
    f.require_list(outs, "outputs", 1);
    for (std::size_t i = 0; i < outs.size(); ++i) {
      const std::string field = fmt::format("outputs[{}]", i);
      const YAML::Mark m = outs[i].Mark();
      c.outputs.push_back({f.text(outs[i], field), f.label(outs[i], field), m.line + 1, m.column + 1});
    }
  }
  return c;
}

}  // namespace

namespace {

// Throws FileError at the first byte of `text` that is not UTF-8 (names and
// messages made from the design, and its JSON report, must be UTF-8).
void require_utf8(const std::string& text, const std::string& path, const std::string& override_text) {
  const std::size_t bad = invalid_utf8_offset(text);
  if (bad == std::string::npos) return;
  const std::string byte = fmt::format("0x{:02X}", static_cast<unsigned char>(text[bad]));
  if (!override_text.empty()) {
    throw FileError(path, 0, 0, fmt::format("-D: the value is not UTF-8 text (byte {})", byte));
  }
  const auto before = text.begin() + static_cast<std::ptrdiff_t>(bad);
  const auto line = static_cast<int>(std::count(text.begin(), before, '\n') + 1);
  const std::size_t line_start = text.find_last_of('\n', bad == 0 ? std::string::npos : bad - 1);
  const std::size_t column = bad == 0 || line_start == std::string::npos ? bad + 1 : bad - line_start;
  throw FileError(
      path, line, static_cast<int>(column),
      fmt::format("{}:{}:{}: the design is not UTF-8 text (byte {} here)", path, line, column, byte));
}

// Throws FileError when an override's value holds a control character YAML
// does not allow (below 0x20 but tab, line feed and carriage return; DEL):
// yaml-cpp misreads it (a NUL after the first byte makes it read the value
// as UTF-16), and a message quoting it would end at a NUL. The message
// shows it escaped (Override::text).
void require_printable(const Override& o, const std::string& path) {
  const auto bad = std::find_if(o.value.begin(), o.value.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return (u < 0x20 && c != '\t' && c != '\n' && c != '\r') || u == 0x7f;
  });
  if (bad == o.value.end()) return;
  throw FileError(path, 0, 0,
                  fmt::format("-D {}: the value holds a control character (\\x{:02x}, byte {}), which YAML "
                              "does not allow",
                              o.text, static_cast<unsigned char>(*bad), bad - o.value.begin() + 1));
}

}  // namespace

namespace {

// The key path one level up: "holes[1]" of "holes[1].segments", "holes" of
// "holes[1]", "" for a top-level key.
std::string enclosing_key(const std::string& key) {
  const std::size_t last = key.find_last_of(".[");
  return last == std::string::npos ? std::string() : key.substr(0, last);
}

bool is_name_start(char c) { return c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Whether `key` is names joined by '.', each followed by any number of [index].
bool is_key_path(const std::string& key) {
  std::size_t i = 0;
  while (true) {
    if (i >= key.size() || !is_name_start(key[i])) return false;
    while (i < key.size() && (is_name_start(key[i]) || is_digit(key[i]))) ++i;
    while (i < key.size() && key[i] == '[') {
      const std::size_t digits = ++i;
      while (i < key.size() && is_digit(key[i])) ++i;
      if (i == digits || i >= key.size() || key[i] != ']') return false;
      ++i;
    }
    if (i == key.size()) return true;
    if (key[i++] != '.') return false;
  }
}

// Records where the design gives every key under `node` (at key path `path`):
// map entries and list elements, descending into maps (not into lists of lists).
void record_sources(const yaml::Fields& f, const YAML::Node& node, const std::string& path,
                    std::map<std::string, KeySource>& where) {
  auto record = [&](const std::string& key, const YAML::Node& value) {
    KeySource source = f.source(value);
    source.holds_keys = !value.IsScalar();  // a map, a list, or empty
    where[key] = std::move(source);
    if (value.IsMap() || value.IsSequence()) record_sources(f, value, key, where);
  };
  if (node.IsMap()) {
    for (const auto& kv : node) {
      if (kv.first.IsScalar())
        record(path.empty() ? kv.first.Scalar() : path + "." + kv.first.Scalar(), kv.second);
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      if (!node[i].IsSequence()) record(fmt::format("{}[{}]", path, i), node[i]);
    }
  }
}

}  // namespace

ErrorLocation placed(const DesignCommon& common, ErrorLocation location) {
  if (location.key.empty() || !location.place.empty()) return location;
  for (std::string k = location.key; !k.empty(); k = enclosing_key(k)) {
    const auto it = common.where.find(k);
    if (it == common.where.end()) continue;
    if (k != location.key && it->second.holds_keys) break;  // absent from a map the design gives
    const KeySource& source = it->second;  // the key itself, or the value it lies in (`keys: 4`)
    location.place = source.place;
    location.file = source.file;
    location.line = source.line;
    location.column = source.column;
    location.override_text = source.override_text;
    return location;
  }
  location.place = common.path;
  location.file = common.path;
  location.is_default = true;
  return location;
}

bool is_design_key(const Design& design, const std::string& key) {
  if (!is_key_path(key)) return false;
  const std::string root = key.substr(0, key.find_first_of(".["));
  const std::vector<std::string>& top = key_group(kind_name(design)).keys;
  return std::find(top.begin(), top.end(), root) != top.end();
}

std::string key_label(const DesignCommon& common, const std::string& key) {
  return location_text(placed(common, ErrorLocation{key}));
}

std::string plain_name_problem(const std::string& name) { return name_problem(name); }

namespace yaml {

YAML::Node load_design_tree(const std::string& text, const std::string& path) {
  require_utf8(text, path, "");
  YAML::Node root;
  try {
    yaml::require_node_budget(text, path, kMaxDesignNodes);
    std::vector<YAML::Node> documents = YAML::LoadAll(text);
    if (documents.size() > 1) {
      const YAML::Mark m = documents[1].Mark();
      throw FileError(path, m.line + 1, m.column + 1,
                      fmt::format("{}:{}:{}: a design file holds one YAML document; a second one starts here",
                                  path, m.line + 1, m.column + 1));
    }
    if (!documents.empty()) root = documents.front();
  } catch (const YAML::Exception& e) {
    throw FileError(
        path, e.mark.line + 1, e.mark.column + 1,
        fmt::format("{}:{}:{}: invalid YAML: {}", path, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  if (!root.IsMap()) throw FileError(path, 0, 0, fmt::format("{}: a design file must be a YAML map", path));
  return root;
}

// NOLINTNEXTLINE(performance-unnecessary-value-param): a handle, the tree is changed through it
std::vector<OverrideOrigin> apply_overrides(YAML::Node root, const std::string& path,
                                            const std::vector<Override>& overrides) {
  std::vector<YAML::Node> values;
  values.reserve(overrides.size());
  for (const Override& o : overrides) {
    require_utf8(o.text, path, o.text);
    require_printable(o, path);
    try {
      yaml::require_node_budget(o.value, path, kMaxDesignNodes, o.text);
      values.push_back(YAML::Load(o.value));
    } catch (const YAML::Exception& e) {
      throw FileError(path, 0, 0, fmt::format("-D {}: the value is not valid YAML: {}", o.text, e.msg));
    }
  }
  std::vector<OverrideOrigin> origins;
  const auto apply = [&](const Override& o, const YAML::Node& value) {
    // The kind decides which keys exist: changing it would only be reported as the
    // old kind's keys being unknown to the new one.
    if (o.path == "kind" &&
        !(value.IsScalar() && root["kind"].IsScalar() && value.Scalar() == root["kind"].Scalar())) {
      throw FileError(
          path, 0, 0,
          fmt::format("-D {}: kind: an override cannot change the design's kind{}: write a design "
                      "of that kind",
                      o.text, root["kind"].IsScalar() ? " (" + root["kind"].Scalar() + ")" : std::string()));
    }
    const Override target = parameter_path(root, o);
    // The design declares what a parameter is: a switch stays a switch (`-D
    // hollow=1` is refused, not read as the number 1), a number a number.
    if (target.path != o.path) {
      const YAML::Node entry = root["parameters"][o.path];
      const bool choice = entry.IsMap() && entry["choices"].IsDefined();
      const YAML::Node current = entry.IsMap() ? entry["value"] : entry;
      const bool was_switch = is_switch_value(current), is_switch = is_switch_value(value);
      if (was_switch != is_switch && (was_switch || !choice)) {
        const std::string field = "parameters." + o.path;
        ErrorLocation at;
        at.key = field;
        at.place = "-D " + o.text;
        at.file = path;
        at.override_text = o.text;
        throw FileError(path, 0, 0,
                        fmt::format("-D {}: {}: {} is {}", o.text, field, o.path,
                                    was_switch ? "a switch: true or false" : "a number, not a switch"),
                        at);
      }
    }
    try {
      apply_override(root, target, value);
    } catch (const FileError& e) {
      throw FileError(path, 0, 0, e.what());
    }
    origins.push_back({value, o.text});
  };
  // The sets as edited, then the set chosen (the last `-D parameter_set=NAME`,
  // else the design's own `parameter_set`), then every other override: a
  // `-D NAME=VALUE` wins over the set's value, whatever the order given.
  const auto choosing = [](const Override& o) { return o.path == "parameter_set"; };
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    if (edits_parameter_sets(overrides[i].path) || choosing(overrides[i])) apply(overrides[i], values[i]);
  }
  apply_parameter_set(root, Fields(path, origins));
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    if (!edits_parameter_sets(overrides[i].path) && !choosing(overrides[i])) apply(overrides[i], values[i]);
  }
  return origins;
}

Design read_design_tree(const YAML::Node& root, const std::string& path,
                        std::vector<OverrideOrigin> origins) {
  const Fields f(path, std::move(origins));
  std::vector<ParameterSet> sets = parameter_sets_of(root);  // as written, before evaluation
  std::vector<DesignParameter> parameters = resolve_parameters(root, f);
  const std::string kind = f.text(f.required(root, "kind", "kind"), "kind");
  Design d;
  d.common = read_common(f, root);
  try {
    d.body = read_body(kind, f, root, d.common);
  } catch (const UnknownKeyError& e) {
    // A top-level key that is not a key of designs may be meant as a parameter (`-D heigth=12`).
    if (parameters.empty() || e.field().find_first_of(".[") != std::string::npos) throw;
    std::string names;
    for (const DesignParameter& p : parameters) names += (names.empty() ? "" : ", ") + p.name;
    throw UnknownKeyError(e.field(), e.path(), e.line(), e.column(),
                          fmt::format("{}, or a parameter of the design: {}", e.what(), names));
  }
  d.common.parameters = std::move(parameters);
  d.common.parameter_sets = std::move(sets);
  if (root["parameter_set"].IsDefined() && root["parameter_set"].IsScalar())
    d.common.parameter_set = root["parameter_set"].Scalar();
  d.common.notes = f.notes();
  d.common.inputs = f.inputs();
  // Where each key is given (the design is valid by now: keys are scalars).
  record_sources(f, root, "", d.common.where);
  return d;
}

}  // namespace yaml

Design parse_design(const std::string& text, const std::string& path,
                    const std::vector<Override>& overrides) {
  YAML::Node root = yaml::load_design_tree(text, path);
  std::vector<yaml::OverrideOrigin> origins = yaml::apply_overrides(root, path, overrides);
  return yaml::read_design_tree(root, path, std::move(origins));
}

std::string parameter_set_name_problem(const std::string& name) {
  constexpr std::size_t kMaxSetNameBytes = 64;
  const bool plain = !name.empty() && name.size() <= kMaxSetNameBytes && name.front() != '-' &&
                     std::all_of(name.begin(), name.end(), [](char c) {
                       return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                              c == '_' || c == '-';
                     });
  if (plain) return "";
  return fmt::format(
      "{:?} is not a parameter set's name: 1 to {} letters, digits, _ and -, not starting with -", name,
      kMaxSetNameBytes);
}

std::string read_design_text(const std::string& path) {
  return read_file(path, kMaxDesignFileBytes, "design file");
}

Design read_design(const std::string& path, const std::vector<Override>& overrides) {
  return parse_design(read_design_text(path), path, overrides);
}

}  // namespace fabmesh
