#include "io/design/manifest.h"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "geometry/core/errors.h"
#include "io/design/csv_table.h"
#include "io/design/read_design.h"
#include "io/design/yaml/fields.h"
#include "io/file.h"

namespace fabmesh {

// One parameter value of a variant: its override and its text in names.
struct ManifestValue {
  Override override;
  std::string shown;
};

// The variants of a manifest, made on demand: the value lists of its forms,
// never their product, so a manifest's memory does not grow with its count.
struct ManifestExpansion {
  using ValueSet = std::vector<ManifestValue>;
  // A piece of a name template: literal text, or a placeholder ({index}, {design}, {path}).
  struct TemplatePart {
    std::string text;
    bool placeholder = false;
  };

  // The axes of the product, slowest first: `variants`, `table` and `zip`
  // are one axis each, a `grid` one per key. Variant k of a base takes one set
  // of each axis, k in mixed radix with the last axis fastest.
  std::vector<std::vector<ValueSet>> axes;
  ValueSet common;                       // `set`, for {path} in names
  std::vector<TemplatePart> name_parts;  // the name template
  std::vector<std::string> designs;      // each base's name, for {design}
  std::size_t per_base = 1;              // variants per base
  std::size_t count = 0;                 // every variant

  // The values of variant i (in axis order); its base in `base`.
  ValueSet values(std::size_t i, std::size_t& base) const {
    base = i / per_base;
    ValueSet out;
    std::size_t rest = i % per_base, stride = per_base;
    for (const auto& axis : axes) {
      stride /= axis.size();
      const ValueSet& set = axis[rest / stride];
      rest %= stride;
      out.insert(out.end(), set.begin(), set.end());
    }
    return out;
  }

  // Variant i's name, or "" with `error` set when the template names a value it lacks.
  std::string name(const ValueSet& values, std::size_t base, std::size_t i, std::string& error) const {
    std::string out;
    for (const TemplatePart& p : name_parts) {
      if (!p.placeholder) {
        out += p.text;
      } else if (p.text == "index") {
        out += fmt::format("{:0{}}", i + 1, std::to_string(count).size());
      } else if (p.text == "design") {
        out += designs[base];
      } else {
        const ManifestValue* found = nullptr;
        for (const ValueSet* set : {&values, &common}) {
          for (const ManifestValue& v : *set) {
            if (v.override.path == p.text) found = &v;
          }
        }
        if (found == nullptr) {
          error = fmt::format("variant {} sets no {} for {{{}}}", i + 1, p.text, p.text);
          return "";
        }
        out += found->shown;
      }
    }
    return out;
  }
};

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxManifestBytes = 1u << 20;
constexpr int kMaxRangeSteps = 1000000;

using Value = ManifestValue;
using ValueSet = ManifestExpansion::ValueSet;
using TemplatePart = ManifestExpansion::TemplatePart;

// The override sets of one axis of the product (see ManifestExpansion::axes).
struct Form {
  std::vector<ValueSet> sets;
};

const KeyGroup& manifest_keys() {
  static const KeyGroup keys{"manifest",
                             {"design", "name", "set", "sets", "variants", "table", "zip", "grid"}};
  return keys;
}

const KeyGroup& range_keys() {
  static const KeyGroup keys{"manifest.grid range", {"from", "to", "steps"}};
  return keys;
}

// Throws parse_override's InputError unless `path` is an override path.
// parse_override splits at the first '=', so it reads "p=" + "=0" as path "p":
// a '=' in `path` is refused here.
void require_override_path(const std::string& path) {
  if (path.find('=') != std::string::npos)
    throw InputError(fmt::format("-D {}=0: unexpected '=' in path '{}'", path, path));
  parse_override(path + "=0");
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

  Form read_sets(const YAML::Node& node, const BatchManifest& m);
  Form read_variants(const YAML::Node& node);
  Form read_table(const YAML::Node& node);
  Form read_zip(const YAML::Node& node);
  std::vector<Form> read_grid(const YAML::Node& node);
  std::vector<Value> grid_values(const std::string& path, const YAML::Node& node,
                                 const std::string& field) const;

  void expand(const std::vector<Form>& forms, const ValueSet& common, const YAML::Node& root,
              BatchManifest& m);
  std::vector<TemplatePart> name_template(const YAML::Node& root, const BatchManifest& m,
                                          std::size_t count) const;
  void check_names(const ManifestExpansion& x, const YAML::Node& at) const;

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
    require_override_path(path);
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

// `sets: all` or `sets: [NAME, ...]`: one variant per parameter set of the
// base designs (the override parameter_set=NAME, as `run -P NAME`). Every
// base declares each set named; with `all`, every base the same sets.
Form ManifestReader::read_sets(const YAML::Node& node, const BatchManifest& m) {
  const std::string owner = "sets";
  const auto [it, fresh] = owner_.emplace("parameter_set", owner);
  if (!fresh)
    f_.fail(node, "sets", fmt::format("'parameter_set' is also set by `{}`: give it one place", it->second));
  std::vector<std::string> names;
  if (node.IsScalar() && node.Scalar() == "all") {
    names = m.bases.front().parameter_set_names();
    if (names.empty()) {
      f_.fail(node, "sets",
              fmt::format("`all`: the design {} declares no parameter_sets", m.base_labels.front()));
    }
  } else if (node.IsSequence()) {
    f_.require_list(node, "sets", 1);
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string name = f_.text(node[i], fmt::format("sets[{}]", i));
      if (std::find(names.begin(), names.end(), name) != names.end())
        f_.fail(node[i], fmt::format("sets[{}]", i), fmt::format("set '{}' is named twice", name));
      names.push_back(name);
    }
  } else {
    f_.fail(node, "sets", "expected `all` (every parameter set of the design) or a list of set names");
  }
  for (std::size_t b = 0; b < m.bases.size(); ++b) {
    const std::vector<std::string> declared = m.bases[b].parameter_set_names();
    const auto list = [](const std::vector<std::string>& v) {
      std::string out;
      for (const std::string& s : v) out += (out.empty() ? "" : ", ") + s;
      return out.empty() ? std::string("none") : out;
    };
    for (const std::string& name : names) {
      if (std::find(declared.begin(), declared.end(), name) == declared.end()) {
        f_.fail(node, "sets",
                fmt::format("the design {} has no parameter set '{}' (its sets: {})", m.base_labels[b], name,
                            list(declared)));
      }
    }
    if (node.IsScalar() && declared.size() != names.size()) {
      f_.fail(node, "sets",
              fmt::format("`all`: the designs declare different sets ({}: {}; {}: {}); list the sets to use",
                          m.base_labels.front(), list(names), m.base_labels[b], list(declared)));
    }
  }
  Form form;
  for (const std::string& name : names) {
    form.sets.push_back(
        {{{"parameter_set", name, fmt::format("parameter_set={} ({}, `sets`)", name, where(node))}, name}});
  }
  return form;
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
      require_override_path(h.text);
    } catch (const InputError& e) {
      const std::string what = e.what();
      throw FileError(path, h.line, h.column,
                      fmt::format("{}: column '{}' is not an override path: {}", at, h.text,
                                  what.substr(std::min(what.size(), what.find(": ") + 2))));
    }
    if (h.text == "kind") {
      throw FileError(path, h.line, h.column,
                      fmt::format("{}: column 'kind': a variant cannot change the design's kind", at));
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

std::vector<Form> ManifestReader::read_grid(const YAML::Node& node) {
  // One axis per key, in order: earlier keys vary slowest.
  std::vector<Form> axes;
  std::size_t count = 1;
  parameters_of(
      node, "grid", "grid", [&](const std::string& path, const YAML::Node& spec, const std::string& field) {
        const std::vector<Value> values = grid_values(path, spec, field);
        count *= values.size();
        if (count > kMaxBatchVariants) {
          f_.fail(spec, field, fmt::format("the grid makes more than {} variants", kMaxBatchVariants));
        }
        Form axis;
        for (const Value& v : values) axis.sets.push_back({v});
        axes.push_back(std::move(axis));
      });
  if (node.size() == 0) f_.fail(node, "grid", "expected at least one parameter");
  return axes;
}

std::vector<TemplatePart> ManifestReader::name_template(const YAML::Node& root, const BatchManifest& m,
                                                        std::size_t count) const {
  const YAML::Node node = root["name"];
  std::string text;
  if (node.IsDefined()) {
    text = f_.text(node, "name");
  } else {
    const bool sets = owner_.count("parameter_set") != 0 && owner_.at("parameter_set") == "sets";
    const bool only_sets = sets && std::all_of(owner_.begin(), owner_.end(), [](const auto& entry) {
                             return entry.second == "sets" || entry.second == "set";
                           });
    text = owner_.count("name")               ? "{name}"
           : only_sets                        ? "{design}_{set}"
           : sets                             ? "{design}_{set}_{index}"
           : m.bases.size() > 1 || count != 1 ? "{design}_{index}"
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
    std::string key = text.substr(open + 1, close - open - 1);
    // {set}: the parameter set (`sets`, or parameter_set in another form).
    if (key == "set" && owner_.count("parameter_set") != 0) key = "parameter_set";
    if (key != "index" && key != "design" && owner_.count(key) == 0) {
      std::string known = owner_.count("parameter_set") != 0 ? "index, design, set" : "index, design";
      for (const auto& [path, form] : owner_) known += ", " + path;
      f_.fail(node.IsDefined() ? node : root, "name",
              fmt::format("{{{}}} is not a parameter of the variants (known: {})", key, known));
    }
    parts.push_back({key, true});
    i = close + 1;
  }
  return parts;
}

// Every name a plain file name, none a batch file's, all different: checked
// once, in manifest order, keeping 16 bytes a variant (a hash of its name)
// only while checking.
void ManifestReader::check_names(const ManifestExpansion& x, const YAML::Node& at) const {
  const auto name_of = [&](std::size_t i) {
    std::size_t base = 0;
    const ValueSet values = x.values(i, base);
    std::string error;
    std::string name = x.name(values, base, i, error);
    if (!error.empty()) f_.fail(at, "name", error);
    return name;
  };
  std::vector<std::pair<std::size_t, std::size_t>> hashes;  // (hash of the name, index)
  hashes.reserve(x.count);
  for (std::size_t i = 0; i < x.count; ++i) {
    const std::string name = name_of(i);
    if (const std::string problem = plain_name_problem(name); !problem.empty()) {
      f_.fail(at, "name",
              fmt::format("variant {} is named {:?}, not a plain file name: {}", i + 1, name, problem));
    }
    for (const std::string& reserved : reserved_variant_names()) {
      if (name == reserved)
        f_.fail(at, "name", fmt::format("variant {} is named '{}', a file of the batch's own", i + 1, name));
    }
    hashes.emplace_back(std::hash<std::string>{}(name), i);
  }
  std::sort(hashes.begin(), hashes.end());
  // The first variant (in manifest order) whose name an earlier one has: as a scan in order would find.
  std::optional<std::pair<std::size_t, std::size_t>> clash;  // (earlier, later)
  for (std::size_t a = 0; a < hashes.size();) {
    std::size_t b = a;
    while (b < hashes.size() && hashes[b].first == hashes[a].first) ++b;
    for (std::size_t j = a + 1; j < b; ++j) {  // same hash: compare the names
      for (std::size_t k = a; k < j; ++k) {
        const std::size_t later = hashes[j].second, earlier = hashes[k].second;
        if ((!clash || later < clash->second) && name_of(earlier) == name_of(later)) clash = {earlier, later};
      }
    }
    a = b;
  }
  if (clash) {
    f_.fail(at, "name",
            fmt::format("variants {} and {} are both named '{}': make the name template tell them apart "
                        "(e.g. add {{index}} or a parameter that differs)",
                        clash->first + 1, clash->second + 1, name_of(clash->first)));
  }
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
  auto x = std::make_shared<ManifestExpansion>();
  for (const Form& form : forms) x->axes.push_back(form.sets);
  x->common = common;
  x->name_parts = name_template(root, m, count);
  for (const DesignSource& base : m.bases) x->designs.push_back(base.name());
  x->per_base = per_base;
  x->count = count;
  check_names(*x, root["name"].IsDefined() ? root["name"] : root);
  m.expansion = std::move(x);
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
  // The sets vary slowest: each set's variants together.
  if (root["sets"].IsDefined()) forms.push_back(read_sets(root["sets"], m));
  if (root["variants"].IsDefined()) forms.push_back(read_variants(root["variants"]));
  if (root["table"].IsDefined()) forms.push_back(read_table(root["table"]));
  if (root["zip"].IsDefined()) forms.push_back(read_zip(root["zip"]));
  if (root["grid"].IsDefined()) {
    for (Form& axis : read_grid(root["grid"])) forms.push_back(std::move(axis));
  }
  // The summary's parameter columns: `name`, when a form sets it, is the name column.
  for (const auto& [path, form] : owner_) {
    if (form != "set" && path != "name") m.parameters.push_back(path);
  }
  for (const Value& v : common) m.common.push_back(v.override);
  expand(forms, common, root, m);
  // Parameters in order of first appearance in the variants.
  std::vector<std::string> ordered;
  for (std::size_t i = 0; i < m.variant_count(); ++i) {
    for (const Override& o : m.variant(i).overrides) {
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
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp's guard says only "bad file".
    throw FileError(path, e.mark.line + 1, e.mark.column + 1,
                    fmt::format("{}:{}:{}: invalid YAML: lists and maps nested more than {} deep here", path,
                                e.mark.line + 1, e.mark.column + 1, e.depth() - 1));
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

std::size_t BatchManifest::variant_count() const { return expansion ? expansion->count : 0; }

Variant BatchManifest::variant(std::size_t i) const {
  if (i >= variant_count()) throw std::out_of_range("BatchManifest::variant: no such variant");
  Variant v;
  ManifestExpansion::ValueSet values = expansion->values(i, v.base);
  std::string error;
  v.name = expansion->name(values, v.base, i, error);
  if (!error.empty()) throw std::logic_error(error);  // read_manifest checked every name
  v.overrides.reserve(values.size());
  for (ManifestValue& value : values) v.overrides.push_back(std::move(value.override));
  return v;
}

std::vector<Override> variant_overrides(const BatchManifest& manifest, const Variant& v) {
  std::vector<Override> all = manifest.common;
  all.insert(all.end(), v.overrides.begin(), v.overrides.end());
  all.push_back({"name", fmt::format("\"{}\"", v.name), "name=" + v.name});
  return all;
}

}  // namespace fabmesh
