#include "io/design/manifest.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <unordered_map>
#include <utility>

#include "geometry/core/errors.h"
#include "io/design/csv_table.h"
#include "io/design/read_design.h"
#include "io/design/yaml/fields.h"
#include "io/file.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxManifestBytes = 1u << 20;
constexpr int kMaxRangeSteps = 1000000;

// One parameter value of a variant: its override and its text in names.
struct Value {
  Override override;
  std::string shown;
};
using ValueSet = std::vector<Value>;

// The override sets of one form (`variants`, `table`, `zip` or `grid`).
struct Form {
  std::vector<ValueSet> sets;
};

// A piece of a name template: literal text, or a placeholder ({index}, {design}, {path}).
struct TemplatePart {
  std::string text;
  bool placeholder = false;
};

const KeyGroup& manifest_keys() {
  static const KeyGroup keys{"manifest", {"design", "name", "set", "variants", "table", "zip", "grid"}};
  return keys;
}

const KeyGroup& range_keys() {
  static const KeyGroup keys{"manifest.grid range", {"from", "to", "steps"}};
  return keys;
}

// A YAML value as the text of an override (flow style, quoted where needed).
std::string yaml_text(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

// A number of a range as an override writes it: 12 significant digits, no "-0".
std::string number_text(double x) { return fmt::format("{:.12g}", x + 0.0); }

class ManifestReader {
 public:
  explicit ManifestReader(const std::string& path) : f_(path), folder_(fs::path(path).parent_path()) {}

  BatchManifest read(const YAML::Node& root);

 private:
  std::string where(const YAML::Node& node) const {
    const YAML::Mark m = node.Mark();
    return fmt::format("{}:{}:{}", f_.path(), m.line + 1, m.column + 1);
  }

  fs::path relative_to_manifest(const std::string& name) const {
    const fs::path p(name);
    return p.is_absolute() ? p : folder_ / p;
  }

  void read_bases(const YAML::Node& node, BatchManifest& m) const;
  // The override path of a map key: checked, and owned by one form only.
  std::string parameter(const YAML::Node& key, const std::string& field, const std::string& form);
  // Calls `each(path, value, field)` for each entry of a map keyed by override paths.
  template <class Each>
  void parameters_of(const YAML::Node& map, const std::string& field, const std::string& form, Each each);
  Value value(const std::string& path, const YAML::Node& node) const {
    return {{path, yaml_text(node), fmt::format("{}={} ({})", path, yaml_text(node), where(node))},
            node.IsScalar() ? node.Scalar() : yaml_text(node)};
  }

  Form read_variants(const YAML::Node& node);
  Form read_table(const YAML::Node& node);
  Form read_zip(const YAML::Node& node);
  Form read_grid(const YAML::Node& node);
  std::vector<Value> grid_values(const std::string& path, const YAML::Node& node,
                                 const std::string& field) const;

  void expand(const std::vector<Form>& forms, const ValueSet& common, const YAML::Node& root,
              BatchManifest& m);
  std::vector<TemplatePart> name_template(const YAML::Node& root, const BatchManifest& m) const;
  std::string render(const std::vector<TemplatePart>& parts, const ValueSet& values, const ValueSet& common,
                     const std::string& design, std::size_t index, std::size_t count,
                     const YAML::Node& at) const;

  yaml::Fields f_;
  fs::path folder_;
  std::map<std::string, std::string> owner_;  // parameter path -> the form that sets it
};

void ManifestReader::read_bases(const YAML::Node& node, BatchManifest& m) const {
  std::vector<YAML::Node> entries;
  if (node.IsSequence()) {
    f_.require_list(node, "design", 1);
    for (const YAML::Node& n : node) entries.push_back(n);
  } else {
    entries.push_back(node);
  }
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const std::string field = node.IsSequence() ? fmt::format("design[{}]", i) : "design";
    const std::string label = f_.text(entries[i], field);
    try {
      m.bases.push_back(DesignSource::read(relative_to_manifest(label).string()));
    } catch (const FileError& e) {
      f_.fail(entries[i], field, e.what());
    }
    m.base_labels.push_back(label);
  }
}

std::string ManifestReader::parameter(const YAML::Node& key, const std::string& field,
                                      const std::string& form) {
  std::string path = f_.text(key, field);
  try {
    parse_override(path + "=0");
  } catch (const InputError& e) {
    // parse_override's message starts with "-D path=0: "; keep what follows.
    const std::string what = e.what();
    const std::size_t colon = what.find(": ");
    f_.fail(key, field, colon == std::string::npos ? what : what.substr(colon + 2));
  }
  if (path == "kind") f_.fail(key, field, "a variant cannot change the design's kind");
  const auto [it, fresh] = owner_.emplace(path, form);
  if (!fresh)
    f_.fail(key, field,
            fmt::format("'{}' is also set by `{}`: give each parameter one place", path, it->second));
  return path;
}

template <class Each>
void ManifestReader::parameters_of(const YAML::Node& map, const std::string& field, const std::string& form,
                                   Each each) {
  if (!map.IsMap()) f_.fail(map, field, "expected a map of override paths (e.g. body.wall) to values");
  for (const auto& kv : map) {
    const std::string path = parameter(kv.first, field, form);
    each(path, kv.second, fmt::format("{}.{}", field, path));
  }
}

Form ManifestReader::read_variants(const YAML::Node& node) {
  f_.require_list(node, "variants", 1);
  Form form;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string field = fmt::format("variants[{}]", i);
    if (!node[i].IsMap()) f_.fail(node[i], field, "expected a map of override paths to values");
    ValueSet set;
    for (const auto& kv : node[i]) {
      const std::string path = f_.text(kv.first, field);
      for (const Value& v : set) {
        if (v.override.path == path) f_.fail(kv.first, field, fmt::format("'{}' is given twice", path));
      }
      // A path may appear in every entry of the list, but in no other form.
      if (const auto it = owner_.find(path); it == owner_.end() || it->second != "variants") {
        parameter(kv.first, field, "variants");
      }
      set.push_back(value(path, kv.second));
    }
    form.sets.push_back(std::move(set));
  }
  return form;
}

Form ManifestReader::read_table(const YAML::Node& node) {
  const std::string name = f_.text(node, "table");
  const std::string path = relative_to_manifest(name).string();
  CsvTable table;
  try {
    table = read_csv_table(path);
  } catch (const FileError& e) {
    if (e.line() > 0) throw;  // a location in the table itself
    f_.fail(node, "table", e.what());
  }
  std::vector<std::string> paths;
  for (const CsvCell& h : table.header) {
    const std::string at = fmt::format("{}:{}:{}", path, h.line, h.column);
    try {
      parse_override(h.text + "=0");
    } catch (const InputError& e) {
      const std::string what = e.what();
      throw FileError(path, h.line, h.column,
                      fmt::format("{}: column '{}' is not an override path: {}", at, h.text,
                                  what.substr(std::min(what.size(), what.find(": ") + 2))));
    }
    if (const auto [it, fresh] = owner_.emplace(h.text, "table"); !fresh) {
      throw FileError(path, h.line, h.column,
                      fmt::format("{}: column '{}' is also set by `{}`: give each parameter one place", at,
                                  h.text, it->second));
    }
    paths.push_back(h.text);
  }
  if (table.rows.empty()) f_.fail(node, "table", fmt::format("{} has a header and no rows", path));
  Form form;
  for (const std::vector<CsvCell>& row : table.rows) {
    ValueSet set;
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (row[c].text.empty()) continue;  // not overridden in this row
      const std::string at = fmt::format("{}:{}:{}", path, row[c].line, row[c].column);
      set.push_back(
          {{paths[c], row[c].text, fmt::format("{}={} ({})", paths[c], row[c].text, at)}, row[c].text});
    }
    form.sets.push_back(std::move(set));
  }
  return form;
}

Form ManifestReader::read_zip(const YAML::Node& node) {
  std::vector<std::vector<Value>> columns;
  std::string first_field;
  parameters_of(node, "zip", "zip",
                [&](const std::string& path, const YAML::Node& list, const std::string& field) {
                  f_.require_list(list, field, 1);
                  if (!columns.empty() && list.size() != columns.front().size()) {
                    f_.fail(list, field,
                            fmt::format("{} values, but {} has {}: zip pairs the lists entry by entry",
                                        list.size(), first_field, columns.front().size()));
                  }
                  if (columns.empty()) first_field = field;
                  std::vector<Value> column;
                  for (const YAML::Node& v : list) column.push_back(value(path, v));
                  columns.push_back(std::move(column));
                });
  if (columns.empty()) f_.fail(node, "zip", "expected at least one parameter");
  Form form;
  for (std::size_t i = 0; i < columns.front().size(); ++i) {
    ValueSet set;
    for (const auto& column : columns) set.push_back(column[i]);
    form.sets.push_back(std::move(set));
  }
  return form;
}

std::vector<Value> ManifestReader::grid_values(const std::string& path, const YAML::Node& node,
                                               const std::string& field) const {
  std::vector<Value> values;
  if (node.IsSequence()) {
    f_.require_list(node, field, 1);
    for (const YAML::Node& v : node) values.push_back(value(path, v));
    return values;
  }
  if (!node.IsMap()) f_.fail(node, field, "expected a list of values or a range {from, to, steps}");
  f_.require_map(node, field, range_keys());
  const double from = f_.number(f_.required(node, "from", field), field + ".from");
  const double to = f_.number(f_.required(node, "to", field), field + ".to");
  const YAML::Node steps_node = f_.required(node, "steps", field);
  const double steps = f_.number(steps_node, field + ".steps");
  if (steps != std::floor(steps) || steps < 1 || steps > kMaxRangeSteps || (steps == 1 && from != to)) {
    f_.fail(steps_node, field + ".steps",
            fmt::format("steps = {} must be a whole number of values in [2, {}] (1 when from = to)",
                        steps_node.Scalar(), kMaxRangeSteps));
  }
  const int n = static_cast<int>(steps);
  for (int i = 0; i < n; ++i) {
    // The ends exactly as given; the values between rounded to 12 significant digits.
    const double x = i == 0 ? from : i == n - 1 ? to : from + (to - from) * i / (n - 1);
    const std::string text = number_text(x);
    values.push_back(
        {{path, text, fmt::format("{}={} ({}, value {} of {})", path, text, where(node), i + 1, n)}, text});
  }
  return values;
}

Form ManifestReader::read_grid(const YAML::Node& node) {
  Form form;
  form.sets.emplace_back();
  std::size_t count = 1;
  parameters_of(
      node, "grid", "grid", [&](const std::string& path, const YAML::Node& spec, const std::string& field) {
        const std::vector<Value> values = grid_values(path, spec, field);
        count *= values.size();
        if (count > kMaxBatchVariants) {
          f_.fail(spec, field, fmt::format("the grid makes more than {} variants", kMaxBatchVariants));
        }
        // Earlier keys vary slowest: each set so far is followed by every value of this key.
        std::vector<ValueSet> next;
        next.reserve(form.sets.size() * values.size());
        for (const ValueSet& set : form.sets) {
          for (const Value& v : values) {
            next.push_back(set);
            next.back().push_back(v);
          }
        }
        form.sets = std::move(next);
      });
  if (node.size() == 0) f_.fail(node, "grid", "expected at least one parameter");
  return form;
}

std::vector<TemplatePart> ManifestReader::name_template(const YAML::Node& root,
                                                        const BatchManifest& m) const {
  const YAML::Node node = root["name"];
  std::string text;
  if (node.IsDefined()) {
    text = f_.text(node, "name");
  } else {
    text = owner_.count("name")                           ? "{name}"
           : m.bases.size() > 1 || m.variants.size() != 1 ? "{design}_{index}"
                                                          : "{design}";
  }
  std::vector<TemplatePart> parts;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t open = text.find('{', i);
    if (open == std::string::npos) {
      parts.push_back({text.substr(i), false});
      break;
    }
    if (open > i) parts.push_back({text.substr(i, open - i), false});
    const std::size_t close = text.find('}', open);
    if (close == std::string::npos)
      f_.fail(node.IsDefined() ? node : root, "name", fmt::format("'{{' at {} is never closed", open));
    const std::string key = text.substr(open + 1, close - open - 1);
    if (key != "index" && key != "design" && owner_.count(key) == 0) {
      std::string known = "index, design";
      for (const auto& [path, form] : owner_) known += ", " + path;
      f_.fail(node.IsDefined() ? node : root, "name",
              fmt::format("{{{}}} is not a parameter of the variants (known: {})", key, known));
    }
    parts.push_back({key, true});
    i = close + 1;
  }
  return parts;
}

std::string ManifestReader::render(const std::vector<TemplatePart>& parts, const ValueSet& values,
                                   const ValueSet& common, const std::string& design, std::size_t index,
                                   std::size_t count, const YAML::Node& at) const {
  std::string name;
  for (const TemplatePart& p : parts) {
    if (!p.placeholder) {
      name += p.text;
    } else if (p.text == "index") {
      name += fmt::format("{:0{}}", index + 1, std::to_string(count).size());
    } else if (p.text == "design") {
      name += design;
    } else {
      const Value* found = nullptr;
      for (const ValueSet* set : {&values, &common}) {
        for (const Value& v : *set) {
          if (v.override.path == p.text) found = &v;
        }
      }
      if (found == nullptr) {
        f_.fail(at, "name", fmt::format("variant {} sets no {} for {{{}}}", index + 1, p.text, p.text));
      }
      name += found->shown;
    }
  }
  return name;
}

void ManifestReader::expand(const std::vector<Form>& forms, const ValueSet& common, const YAML::Node& root,
                            BatchManifest& m) {
  std::size_t per_base = 1;
  for (const Form& form : forms) {
    per_base *= form.sets.size();
    if (per_base > kMaxBatchVariants) break;
  }
  const std::size_t count = per_base * m.bases.size();
  if (per_base > kMaxBatchVariants || count > kMaxBatchVariants) {
    f_.fail(root, "", fmt::format("the manifest makes more than {} variants", kMaxBatchVariants));
  }
  const std::vector<TemplatePart> parts = name_template(root, m);
  const YAML::Node at = root["name"].IsDefined() ? root["name"] : root;
  std::unordered_map<std::string, std::size_t> first;
  m.variants.reserve(count);
  for (std::size_t b = 0; b < m.bases.size(); ++b) {
    const std::string design = m.bases[b].name();
    for (std::size_t k = 0; k < per_base; ++k) {
      // k in mixed radix, the last form's digit fastest.
      ValueSet values;
      std::size_t rest = k, stride = per_base;
      for (const Form& form : forms) {
        stride /= form.sets.size();
        const ValueSet& set = form.sets[rest / stride];
        rest %= stride;
        values.insert(values.end(), set.begin(), set.end());
      }
      const std::size_t index = m.variants.size();
      Variant v;
      v.base = b;
      v.name = render(parts, values, common, design, index, count, at);
      if (const std::string problem = plain_name_problem(v.name); !problem.empty()) {
        f_.fail(
            at, "name",
            fmt::format("variant {} is named {:?}, not a plain file name: {}", index + 1, v.name, problem));
      }
      for (const std::string& reserved : reserved_variant_names()) {
        if (v.name == reserved)
          f_.fail(at, "name",
                  fmt::format("variant {} is named '{}', a file of the batch's own", index + 1, v.name));
      }
      if (const auto [it, fresh] = first.emplace(v.name, index); !fresh) {
        f_.fail(at, "name",
                fmt::format("variants {} and {} are both named '{}': make the name template tell them apart "
                            "(e.g. add {{index}} or a parameter that differs)",
                            it->second + 1, index + 1, v.name));
      }
      for (Value& value : values) v.overrides.push_back(std::move(value.override));
      m.variants.push_back(std::move(v));
    }
  }
}

BatchManifest ManifestReader::read(const YAML::Node& root) {
  BatchManifest m;
  m.path = f_.path();
  f_.require_map(root, "", manifest_keys());
  read_bases(f_.required(root, "design", "design"), m);
  ValueSet common;
  if (root["set"].IsDefined()) {
    parameters_of(root["set"], "set", "set",
                  [&](const std::string& path, const YAML::Node& v, const std::string&) {
                    common.push_back(value(path, v));
                  });
  }
  std::vector<Form> forms;
  if (root["variants"].IsDefined()) forms.push_back(read_variants(root["variants"]));
  if (root["table"].IsDefined()) forms.push_back(read_table(root["table"]));
  if (root["zip"].IsDefined()) forms.push_back(read_zip(root["zip"]));
  if (root["grid"].IsDefined()) forms.push_back(read_grid(root["grid"]));
  // The summary's parameter columns: `name`, when a form sets it, is the name column.
  for (const auto& [path, form] : owner_) {
    if (form != "set" && path != "name") m.parameters.push_back(path);
  }
  for (const Value& v : common) m.common.push_back(v.override);
  expand(forms, common, root, m);
  // Parameters in order of first appearance in the variants.
  std::vector<std::string> ordered;
  for (const Variant& v : m.variants) {
    for (const Override& o : v.overrides) {
      if (o.path != "name" && std::find(ordered.begin(), ordered.end(), o.path) == ordered.end())
        ordered.push_back(o.path);
    }
    if (ordered.size() == m.parameters.size()) break;
  }
  m.parameters = std::move(ordered);
  return m;
}

}  // namespace

BatchManifest parse_manifest(const std::string& text, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw FileError(
        path, e.mark.line + 1, e.mark.column + 1,
        fmt::format("{}:{}:{}: invalid YAML: {}", path, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  if (!root.IsMap()) throw FileError(path, 0, 0, fmt::format("{}: a manifest must be a YAML map", path));
  return ManifestReader(path).read(root);
}

BatchManifest read_manifest(const std::string& path) {
  return parse_manifest(read_file(path, kMaxManifestBytes, "manifest"), path);
}

std::vector<Override> variant_overrides(const BatchManifest& manifest, const Variant& v) {
  std::vector<Override> all = manifest.common;
  all.insert(all.end(), v.overrides.begin(), v.overrides.end());
  all.push_back({"name", fmt::format("\"{}\"", v.name), "name=" + v.name});
  return all;
}

}  // namespace fabmesh
