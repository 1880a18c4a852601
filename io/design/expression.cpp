// Expressions and named parameters of design files, evaluated with muparser
// (Debian: libmuparser-dev). This is the one file that includes it.
//
// muparser is restricted to what docs/design-files.md allows: its built-in
// functions, constants and binary operators are cleared, and + - * / ^,
// pi, min, max, abs, sqrt, sin, cos, tan and atan2 are defined again here,
// each checking its own result. What muparser reads beyond them (the
// conditional `?:`, `=`, string literals) is refused by names() before an
// expression is evaluated.
//
// Thread safety: a mu::Parser holds its own definitions, expression and
// bytecode; muparser's only static mutable state is the locale that
// SetDecSep, SetThousandsSep and ResetLocale write (never called here) and
// debug flags (never set). Each design being read has its own evaluator.

#include "io/design/expression.h"

#include <fmt/format.h>
#include <muParser.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include "geometry/core/errors.h"
#include "io/design/number_limits.h"
#include "io/design/yaml/design_tree.h"

namespace fabmesh {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Long enough for any formula; short enough that checking one stays cheap.
constexpr std::size_t kMaxExpressionBytes = 4096;

// The allowed grammar in words, appended to every refusal.
std::string allowed_text() {
  return "expressions use numbers, parameter names, + - * / ^, parentheses, a ? b : c, pi and the functions "
         "min, max, abs, sqrt, sin, cos, tan, atan2";
}

// Each step of an evaluation stays finite: a later step could hide an
// infinity (1 / (1 / 0) is 0).
double finite(double result, const std::string& step) {
  if (!std::isfinite(result)) throw InputError(fmt::format("{} is not a finite number", step));
  return result;
}

double add(double a, double b) { return finite(a + b, fmt::format("{} + {}", a, b)); }
double subtract(double a, double b) { return finite(a - b, fmt::format("{} - {}", a, b)); }
double multiply(double a, double b) { return finite(a * b, fmt::format("{} * {}", a, b)); }
double divide(double a, double b) {
  if (b == 0.0) throw InputError(fmt::format("division by zero ({} / 0)", a));
  return finite(a / b, fmt::format("{} / {}", a, b));
}
double power(double a, double b) {
  if (a == 0.0 && b < 0.0) throw InputError(fmt::format("division by zero (0 ^ {})", b));
  if (a < 0.0 && b != std::floor(b))
    throw InputError(
        fmt::format("{} ^ {}: a negative number to a fractional power is not a real number", a, b));
  return finite(std::pow(a, b), fmt::format("{} ^ {}", a, b));
}
double square_root(double a) {
  if (a < 0.0) throw InputError(fmt::format("sqrt({}): the square root of a negative number", a));
  return std::sqrt(a);
}
double absolute(double a) { return std::abs(a); }
double sine(double a) { return std::sin(a); }
double cosine(double a) { return std::cos(a); }
double tangent(double a) { return finite(std::tan(a), fmt::format("tan({})", a)); }
double arc_tangent2(double y, double x) { return std::atan2(y, x); }
double minimum(const double* values, int count) {
  return *std::min_element(values, values + std::max(count, 1));
}
double maximum(const double* values, int count) {
  return *std::max_element(values, values + std::max(count, 1));
}

bool is_name_start(char c) { return c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c); }
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
// `?` and `:` are muparser's conditional, which is not among the built-in
// operators cleared here: `a ? b : c` is b when a is not 0 (a switch is 1 or 0).
bool is_structure(char c) {
  return c == '+' || c == '-' || c == '*' || c == '/' || c == '^' || c == '(' || c == ')' || c == ',' ||
         c == '?' || c == ':';
}

// Why the run of characters `run` (none allowed) is refused.
std::string refusal(const std::string& run) {
  static const std::set<std::string> operators{
      "&&", "||", "<", "<=", ">", ">=", "==", "!=", "!", "=", "%", "&", "|"};
  if (operators.count(run) != 0)
    return fmt::format("the operator '{}' is not allowed: {}", run, allowed_text());
  std::string shown;
  for (const char c : run) {
    const auto u = static_cast<unsigned char>(c);
    shown += u < 0x20 || u >= 0x7f ? fmt::format("\\x{:02X}", u) : std::string(1, c);
  }
  return fmt::format("'{}' is not allowed: {}", shown, allowed_text());
}

}  // namespace

const std::vector<std::string>& expression_functions() {
  static const std::vector<std::string> names{"min", "max", "abs", "sqrt", "sin", "cos", "tan", "atan2"};
  return names;
}

bool is_expression_builtin(const std::string& name) {
  // muparser's own functions and constants (allowed here or not) and pi.
  static const std::set<std::string> names{"pi",   "_pi",   "_e",   "sin",  "cos",  "tan",   "asin",  "acos",
                                           "atan", "atan2", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh",
                                           "log2", "log10", "log",  "ln",   "exp",  "sqrt",  "sign",  "rint",
                                           "abs",  "sum",   "avg",  "min",  "max"};
  return names.count(name) != 0;
}

bool is_identifier(const std::string& name) {
  return !name.empty() && is_name_start(name.front()) &&
         std::all_of(name.begin(), name.end(), [](char c) { return is_name_char(c); });
}

struct ExpressionEvaluator::Impl {
  mu::Parser parser;
  std::map<std::string, double> values;  // a map: muparser keeps the address of each
};

ExpressionEvaluator::ExpressionEvaluator() : impl_(std::make_unique<Impl>()) {
  mu::Parser& p = impl_->parser;
  p.ClearFun();
  p.ClearConst();
  p.ClearOprt();
  p.ClearPostfixOprt();
  // The built-in binary operators include comparisons and logic: define the five allowed ones.
  p.EnableBuiltInOprt(false);
  p.DefineOprt("+", add, mu::prADD_SUB);
  p.DefineOprt("-", subtract, mu::prADD_SUB);
  p.DefineOprt("*", multiply, mu::prMUL_DIV);
  p.DefineOprt("/", divide, mu::prMUL_DIV);
  p.DefineOprt("^", power, mu::prPOW, mu::oaRIGHT);
  p.DefineConst("pi", kPi);
  p.DefineFun("min", minimum);
  p.DefineFun("max", maximum);
  p.DefineFun("abs", absolute);
  p.DefineFun("sqrt", square_root);
  p.DefineFun("sin", sine);
  p.DefineFun("cos", cosine);
  p.DefineFun("tan", tangent);
  p.DefineFun("atan2", arc_tangent2);
}

ExpressionEvaluator::~ExpressionEvaluator() = default;

std::vector<std::string> ExpressionEvaluator::names(const std::string& text) const {
  if (text.size() > kMaxExpressionBytes) {
    throw InputError(fmt::format("the expression is {} characters long; an expression is at most {}",
                                 text.size(), kMaxExpressionBytes));
  }
  std::vector<std::string> found;
  std::set<std::string> seen;
  bool empty = true;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (is_space(c)) {
      ++i;
      continue;
    }
    empty = false;
    if (is_digit(c) || c == '.') {
      while (i < text.size() && (is_digit(text[i]) || text[i] == '.')) ++i;
      // An exponent: e, an optional sign, digits.
      if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        std::size_t j = i + 1;
        if (j < text.size() && (text[j] == '+' || text[j] == '-')) ++j;
        if (j < text.size() && is_digit(text[j])) {
          while (j < text.size() && is_digit(text[j])) ++j;
          i = j;
        }
      }
    } else if (is_name_start(c)) {
      std::size_t j = i;
      while (j < text.size() && is_name_char(text[j])) ++j;
      const std::string name = text.substr(i, j - i);
      std::size_t next = j;
      while (next < text.size() && is_space(text[next])) ++next;
      const bool call = next < text.size() && text[next] == '(';
      const std::vector<std::string>& functions = expression_functions();
      const bool function = std::find(functions.begin(), functions.end(), name) != functions.end();
      if (call && !function) {
        throw InputError(fmt::format("{} '{}' is not allowed: {}",
                                     is_expression_builtin(name) ? "the function" : "there is no function",
                                     name, allowed_text()));
      }
      if (!call && function) throw InputError(fmt::format("'{}' is a function: write {}(...)", name, name));
      if (!call && name != "pi") {
        if (is_expression_builtin(name))
          throw InputError(fmt::format("the constant '{}' is not allowed: {}", name, allowed_text()));
        if (seen.insert(name).second) found.push_back(name);
      }
      i = j;
    } else if (is_structure(c)) {
      ++i;
    } else {
      std::size_t j = i;
      while (j < text.size() && !is_space(text[j]) && !is_name_char(text[j]) && !is_structure(text[j]) &&
             text[j] != '.')
        ++j;
      throw InputError(refusal(text.substr(i, j - i)));
    }
  }
  if (empty) throw InputError("the expression is empty: write a number or a formula after '='");
  return found;
}

void ExpressionEvaluator::define(const std::string& name, double value) {
  const auto [it, fresh] = impl_->values.emplace(name, value);
  it->second = value;
  if (fresh) impl_->parser.DefineVar(name, &it->second);
}

double ExpressionEvaluator::evaluate(const std::string& text) {
  mu::Parser& p = impl_->parser;
  double value = 0.0;
  try {
    p.SetExpr(text);
    value = p.Eval();
    if (p.GetNumResults() != 1)
      throw InputError("a ',' outside a function's parentheses: an expression gives one number");
  } catch (const mu::ParserError& e) {
    std::string message = e.GetMsg();
    while (!message.empty() && (message.back() == '.' || message.back() == ' ')) message.pop_back();
    throw InputError(fmt::format("syntax error: {}", message));
  }
  finite(value, fmt::format("the result {}", value));
  if (std::abs(value) > kMaxDesignNumber) {
    throw InputError(
        fmt::format("the result {} is too large: numbers in a design are at most {:g} in magnitude", value,
                    kMaxDesignNumber));
  }
  return value + 0.0;  // no -0
}

// --- parameters and expressions in a design's tree ---

namespace yaml {
namespace {

// At most this many parameters: a design names a handful; resolving them
// recurses along their references.
constexpr std::size_t kMaxParameters = 1000;
constexpr std::size_t kMaxParameterNameBytes = 64;
constexpr std::size_t kMaxChoices = 100;

bool is_expression(const YAML::Node& node) {
  return node.IsScalar() && !node.Scalar().empty() && node.Scalar().front() == '=';
}

// One entry of `parameters:` while it is resolved.
struct Parameter {
  std::string name;
  ParameterKind kind = ParameterKind::Number;
  std::vector<std::string> choices;  // a choice's, as declared
  std::string field;                 // "parameters.height"
  std::string value_field;           // where the value is given: `field`, or "parameter_sets.tall.height"
  YAML::Mark key_mark;
  YAML::Node value;
  std::optional<YAML::Node> min, max, step;  // when the entry is a map that gives them
  std::string description;
  enum class State { Waiting, Resolving, Done } state = State::Waiting;
  DesignParameter resolved;
};

class Resolver {
 public:
  explicit Resolver(const Fields& f) : f_(f) {}

  std::vector<DesignParameter> run(const YAML::Node& root) {
    declare(root);
    for (Parameter& p : parameters_) resolve(p);
    std::string field;
    walk(root, field);
    std::vector<DesignParameter> out;
    out.reserve(parameters_.size());
    for (const Parameter& p : parameters_) out.push_back(p.resolved);
    return out;
  }

 private:
  [[noreturn]] void fail(const YAML::Node& node, const std::string& field, const std::string& message) const {
    f_.fail(node, field, fmt::format("{:?}: {}", node.Scalar(), message));
  }

  Parameter* find(const std::string& name) {
    const auto it = index_.find(name);
    return it == index_.end() ? nullptr : &parameters_[it->second];
  }

  std::string names_text() const {
    std::string out;
    for (const Parameter& p : parameters_) out += (out.empty() ? "" : ", ") + p.name;
    return out;
  }

  void declare(const YAML::Node& root) {
    const YAML::Node params = root["parameters"];
    if (!params.IsDefined()) return;
    if (!params.IsMap()) {
      f_.fail(params, "parameters",
              "expected a map of names to values, e.g. parameters: {height: 10, wall: 0.3}");
    }
    if (params.size() > kMaxParameters) {
      f_.fail(params, "parameters",
              fmt::format("{} parameters; a design declares at most {}", params.size(), kMaxParameters));
    }
    std::set<std::string> design_keys;
    for (const std::string& kind : kind_names()) {
      for (const std::string& key : key_group(kind).keys) design_keys.insert(key);
    }
    for (const auto& kv : params) {
      if (!kv.first.IsScalar())
        f_.fail_key(kv.first, kv.second, "parameters",
                    "a parameter's name must be a plain name, not a list or a map");
      Parameter p;
      p.name = kv.first.Scalar();
      p.field = "parameters." + p.name;
      p.key_mark = kv.first.Mark();
      if (const Parameter* earlier = find(p.name)) {
        const YAML::Mark m = earlier->key_mark;
        f_.fail_key(kv.first, kv.second, p.field,
                    fmt::format("parameter '{}' is declared twice (first at line {}, column {})", p.name,
                                m.line + 1, m.column + 1));
      }
      if (!is_identifier(p.name) || p.name.size() > kMaxParameterNameBytes) {
        f_.fail_key(kv.first, kv.second, p.field,
                    fmt::format("'{}' is not a parameter name: letters, digits and _, not starting with a "
                                "digit, at most {} characters",
                                p.name, kMaxParameterNameBytes));
      }
      if (is_expression_builtin(p.name)) {
        f_.fail_key(
            kv.first, kv.second, p.field,
            fmt::format("'{}' names a function or constant of expressions: choose another name", p.name));
      }
      if (design_keys.count(p.name) != 0) {
        f_.fail_key(kv.first, kv.second, p.field,
                    fmt::format("'{}' is a top-level key of designs: choose another name", p.name));
      }
      const YAML::Node entry = kv.second;
      if (entry.IsMap()) {
        f_.require_map(entry, p.field, key_group("parameters.NAME"));
        p.value = f_.required(entry, "value", p.field);
        for (auto [key, bound] :
             {std::pair{"min", &p.min}, std::pair{"max", &p.max}, std::pair{"step", &p.step}}) {
          if (entry[key].IsDefined()) *bound = entry[key];
        }
        if (entry["description"].IsDefined())
          p.description = f_.text(entry["description"], p.field + ".description");
        if (entry["choices"].IsDefined()) {
          p.kind = ParameterKind::Choice;
          p.choices = choice_list(entry["choices"], p.field + ".choices");
        }
      } else if (entry.IsScalar()) {
        p.value = entry;
      } else {
        f_.fail(entry, p.field,
                "expected a number, an expression \"=...\", true or false, or a map {value, min, max, step, "
                "choices, description}");
      }
      if (p.kind == ParameterKind::Number && is_switch_value(p.value)) p.kind = ParameterKind::Switch;
      if (p.kind != ParameterKind::Number) {
        for (auto [key, bound] :
             {std::pair{"min", &p.min}, std::pair{"max", &p.max}, std::pair{"step", &p.step}}) {
          if (*bound)
            f_.fail(**bound, p.field + "." + key,
                    fmt::format("a {} has no {}: it takes {}",
                                p.kind == ParameterKind::Choice ? "choice" : "switch", key,
                                p.kind == ParameterKind::Choice ? "one of its choices" : "true or false"));
        }
      }
      p.value_field = set_field(root, p);
      index_.emplace(p.name, parameters_.size());
      parameters_.push_back(std::move(p));
    }
  }

  // A choice's values: at least two different plain texts.
  std::vector<std::string> choice_list(const YAML::Node& node, const std::string& field) const {
    f_.require_list(node, field, 2);
    if (node.size() > kMaxChoices)
      f_.fail(node, field, fmt::format("{} choices; a choice has at most {}", node.size(), kMaxChoices));
    std::vector<std::string> out;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string at = fmt::format("{}[{}]", field, i);
      const std::string text = f_.text(node[i], at);
      if (text.empty() || text.front() == '=' || text.find_first_of("\r\n") != std::string::npos)
        f_.fail(node[i], at,
                fmt::format("{:?} is not a choice: a plain text on one line, not an expression", text));
      if (std::find(out.begin(), out.end(), text) != out.end())
        f_.fail(node[i], at, fmt::format("the choice '{}' is given twice", text));
      out.push_back(text);
    }
    return out;
  }

  static std::string joined(const std::vector<std::string>& texts) {
    std::string out;
    for (const std::string& t : texts) out += (out.empty() ? "" : ", ") + t;
    return out;
  }

  // The parameter an expression names alone ("=mode"), if any.
  Parameter* named_alone(const YAML::Node& node) {
    std::string text = node.Scalar().substr(1);
    const std::size_t first = text.find_first_not_of(" \t");
    const std::size_t last = text.find_last_not_of(" \t");
    if (first == std::string::npos) return nullptr;
    text = text.substr(first, last - first + 1);
    return is_identifier(text) ? find(text) : nullptr;
  }

  // A choice's or a switch's value, checked: the text it stands for.
  void resolve_named(Parameter& p) {
    DesignParameter& r = p.resolved;
    r.name = p.name;
    r.description = p.description;
    r.kind = p.kind;
    r.choices = p.choices;
    const bool choice = p.kind == ParameterKind::Choice;
    const std::string allowed =
        choice ? "one of the choices: " + joined(p.choices) : std::string("true or false");
    if (!p.value.IsScalar() || is_expression(p.value))
      f_.fail(p.value, p.value_field,
              fmt::format("{} is a {}: expected {}", p.name, choice ? "choice" : "switch", allowed));
    const std::string text = p.value.Scalar();
    if (choice) {
      const auto it = std::find(p.choices.begin(), p.choices.end(), text);
      if (it == p.choices.end())
        f_.fail(p.value, p.value_field, fmt::format("{:?} is not {}", text, allowed));
      r.text = text;
      r.value = static_cast<double>(it - p.choices.begin());
    } else {
      if (!is_switch_value(p.value))
        f_.fail(p.value, p.value_field, fmt::format("{:?}: {} is a switch: {}", text, p.name, allowed));
      const bool on = text == "true" || text == "True" || text == "TRUE";
      r.text = on ? "true" : "false";
      r.value = on ? 1.0 : 0.0;
      evaluator_.define(p.name, r.value);
    }
    p.state = Parameter::State::Done;
  }

  // Where `p`'s value is given: in the chosen parameter set (apply_parameter_set
  // put that set's node there), or in `parameters`.
  static std::string set_field(const YAML::Node& root, const Parameter& p) {
    const YAML::Node chosen = root["parameter_set"];
    const YAML::Node sets = root["parameter_sets"];
    if (!chosen.IsDefined() || !chosen.IsScalar() || !sets.IsDefined() || !sets.IsMap()) return p.field;
    const YAML::Node set = sets[chosen.Scalar()];
    if (!set.IsDefined() || !set.IsMap()) return p.field;
    const YAML::Node given = set[p.name];
    return given.IsDefined() && given.is(p.value) ? "parameter_sets." + chosen.Scalar() + "." + p.name
                                                  : p.field;
  }

  // The number `node` holds, its expression evaluated (and the node set to the result).
  // NOLINTNEXTLINE(performance-unnecessary-value-param): a handle, the tree is changed through it
  double number(YAML::Node node, const std::string& field) {
    if (!is_expression(node)) return f_.number(node, field);
    const std::string text = node.Scalar().substr(1);
    std::vector<std::string> names;
    try {
      names = evaluator_.names(text);
    } catch (const InputError& e) {
      fail(node, field, e.what());
    }
    for (const std::string& name : names) {
      Parameter* p = find(name);
      if (p == nullptr) {
        fail(node, field,
             parameters_.empty()
                 ? fmt::format("unknown name '{}' (the design declares no parameters)", name)
                 : fmt::format("unknown name '{}' (the parameters are: {})", name, names_text()));
      }
      if (p->state == Parameter::State::Resolving) {
        std::string chain;
        const auto first = std::find(resolving_.begin(), resolving_.end(), name);
        for (auto it = first; it != resolving_.end(); ++it) chain += *it + " -> ";
        fail(node, field, fmt::format("the parameters refer to each other in a cycle: {}{}", chain, name));
      }
      resolve(*p);
      if (p->kind == ParameterKind::Choice) {
        fail(node, field,
             fmt::format("'{}' is a choice ({}): write \"={}\" alone where the design takes a text, not in a "
                         "formula",
                         name, joined(p->choices), name));
      }
    }
    double value = 0.0;
    try {
      value = evaluator_.evaluate(text);
    } catch (const InputError& e) {
      std::string values;  // "height = 10, wall = 0.3": what the expression was given
      for (const std::string& name : names)
        values += fmt::format("{}{} = {}", values.empty() ? "" : ", ", name, find(name)->resolved.value);
      fail(node, field,
           values.empty() ? std::string(e.what()) : fmt::format("{} (with {})", e.what(), values));
    }
    node = fmt::format("{}", value);  // in place: the node keeps its mark, its override origin
    return value;
  }

  std::optional<double> optional_number(const std::optional<YAML::Node>& node, const std::string& field) {
    if (!node) return std::nullopt;
    return number(*node, field);
  }

  void resolve(Parameter& p) {
    if (p.state == Parameter::State::Done) return;
    if (p.kind != ParameterKind::Number) {
      resolve_named(p);
      return;
    }
    p.state = Parameter::State::Resolving;
    resolving_.push_back(p.name);
    DesignParameter& r = p.resolved;
    r.name = p.name;
    r.description = p.description;
    r.value = number(p.value, p.value_field);
    r.min = optional_number(p.min, p.field + ".min");
    r.max = optional_number(p.max, p.field + ".max");
    r.step = optional_number(p.step, p.field + ".step");
    if (p.step && r.step && *r.step <= 0.0)
      f_.fail(*p.step, p.field + ".step", fmt::format("step = {} must be > 0", *r.step));
    if (p.max && r.min && r.max && *r.min > *r.max)
      f_.fail(*p.max, p.field + ".max", fmt::format("max = {} is below min = {}", *r.max, *r.min));
    if (r.min && r.max && (r.value < *r.min || r.value > *r.max))
      f_.fail(p.value, p.value_field, fmt::format("{} is outside [{}, {}]", r.value, *r.min, *r.max));
    if (r.min && r.value < *r.min)
      f_.fail(p.value, p.value_field, fmt::format("{} is below the minimum {}", r.value, *r.min));
    if (r.max && r.value > *r.max)
      f_.fail(p.value, p.value_field, fmt::format("{} is above the maximum {}", r.value, *r.max));
    evaluator_.define(p.name, r.value);
    resolving_.pop_back();
    p.state = Parameter::State::Done;
  }

  // Evaluates every expression under `node` but `parameters`; `field` is its key path,
  // extended in place while descending and restored on the way back.
  // NOLINTNEXTLINE(misc-no-recursion): as deep as the tree, at most 64 levels
  void walk(const YAML::Node& node, std::string& field) {
    const std::size_t length = field.size();
    if (is_expression(node)) {
      // "=mode" alone, a choice or a switch: its text where the design takes one.
      if (Parameter* p = named_alone(node); p != nullptr && p->kind != ParameterKind::Number) {
        resolve(*p);
        YAML::Node handle = node;  // in place: the node keeps its mark, its override origin
        handle = p->resolved.text;
        handle.SetTag(kChosenTag);
        return;
      }
      number(node, field);
    } else if (node.IsSequence()) {
      for (std::size_t i = 0; i < node.size(); ++i) {
        field.append("[").append(std::to_string(i)).append("]");
        walk(node[i], field);
        field.resize(length);
      }
    } else if (node.IsMap()) {
      for (const auto& kv : node) {
        if (!kv.first.IsScalar()) continue;  // the reader refuses it
        const std::string& key = kv.first.Scalar();
        if (length == 0 && key == "parameters") continue;
        field.append(length == 0 ? "" : ".").append(key);
        walk(kv.second, field);
        field.resize(length);
      }
    }
  }

  const Fields& f_;
  ExpressionEvaluator evaluator_;
  std::vector<Parameter> parameters_;
  std::map<std::string, std::size_t> index_;  // name -> its entry in parameters_
  std::vector<std::string> resolving_;        // the parameters being resolved, outermost first
};

}  // namespace

bool is_switch_value(const YAML::Node& node) {
  if (!node.IsDefined() || !node.IsScalar() || node.Tag() == "!") return false;  // "true" quoted is a text
  static const std::set<std::string> texts{"true", "True", "TRUE", "false", "False", "FALSE"};
  return texts.count(node.Scalar()) != 0;
}

std::vector<DesignParameter> resolve_parameters(const YAML::Node& root, const Fields& f) {
  return Resolver(f).run(root);
}

}  // namespace yaml
}  // namespace fabmesh
