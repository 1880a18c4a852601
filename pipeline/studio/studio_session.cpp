#include "pipeline/studio/studio_session.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "geometry/curves/basis.h"
#include "geometry/fairing/build_curve.h"
#include "io/cutting/layout.h"
#include "io/cutting/toolpath_svg.h"
#include "io/design/edit_values.h"
#include "io/design/file_references.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/gltf.h"
#include "io/pictures/curve_plot.h"
#include "pipeline/design_curves.h"
#include "pipeline/encoders/encoding.h"
#include "pipeline/failure.h"
#include "pipeline/job.h"
#include "pipeline/load_design.h"
#include "pipeline/output_table.h"
#include "pipeline/parameter_schema.h"
#include "pipeline/pictures.h"
#include "pipeline/report.h"
#include "pipeline/validate_parts.h"

namespace fabmesh {
namespace {

using Json = nlohmann::ordered_json;

// A request the API cannot take: HTTP 400, naming the request's field.
struct BadRequest {
  std::string field;
  std::string message;
};

StudioResponse json_response(int status, const Json& body) {
  return {status, "application/json", body.dump(-1, ' ', false, Json::error_handler_t::replace)};
}

StudioResponse bad_request(const BadRequest& e) {
  return json_response(400, {{"error", {{"message", e.message}, {"field", e.field}}}});
}

// The design's overrides of a request's "overrides" object, as `-D` takes them.
struct Request {
  std::vector<Override> overrides;
  std::string energy;  ///< fairest: "strain" or "curvature_variation"
  bool draft = false;  ///< build: a draft (docs/studio.md)
};

// What a request may have besides "overrides".
enum class RequestFields {
  Overrides,  ///< export, save
  Build,      ///< "draft"
  Fairest,    ///< "energy"
};

std::string number_text(double value) { return fmt::format("{}", value); }

// The field of a request body that a JSON error is in ("overrides.height"),
// from the keys read up to it: a SAX reader that keeps the open keys.
class ErrorField : public nlohmann::json_sax<Json> {
 public:
  std::string field;  ///< once parse_error came: the keys open there, joined by '.'
  std::string token;  ///< the text at fault ("1e999")

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return open(); }
  bool key(string_t& name) override {
    keys_.back() = name;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string& last_token, const Json::exception&) override {
    for (const std::string& k : keys_) {
      if (!k.empty()) field += (field.empty() ? "" : ".") + k;
    }
    token = last_token;
    return false;
  }

 private:
  bool open() {
    keys_.emplace_back();
    return true;
  }
  bool close() {
    keys_.pop_back();
    return true;
  }
  std::vector<std::string> keys_;  ///< the key of each open object, "" for a list
};

// The request body as JSON. A number beyond a double's range (1e999) is a
// request's error at its field, as any other value the API cannot take.
Json parse_body(const std::string& body) {
  try {
    return Json::parse(body);
  } catch (const Json::out_of_range&) {
    ErrorField at;
    (void)Json::sax_parse(body, &at);
    throw BadRequest{at.field, fmt::format("{}: {} is not a number fabmesh can take (beyond a double's "
                                           "range, about 1.8e308)",
                                           at.field.empty() ? "the request" : at.field, at.token)};
  } catch (const Json::exception& e) {
    throw BadRequest{"", fmt::format("the request body is not JSON: {}", e.what())};
  }
}

Request parse_request(const std::string& body, RequestFields fields = RequestFields::Overrides) {
  const bool takes_energy = fields == RequestFields::Fairest;
  const bool takes_draft = fields == RequestFields::Build;
  Request request;
  if (body.empty()) return request;
  const Json j = parse_body(body);
  if (!j.is_object()) throw BadRequest{"", "the request body must be a JSON object"};
  for (const auto& [key, value] : j.items()) {
    if (key == "overrides" || (takes_energy && key == "energy") || (takes_draft && key == "draft")) continue;
    throw BadRequest{key, fmt::format("unknown field '{}' (the request takes: overrides{})", key,
                                      takes_energy  ? ", energy"
                                      : takes_draft ? ", draft"
                                                    : "")};
  }
  if (takes_draft && j.contains("draft")) {
    if (!j["draft"].is_boolean()) throw BadRequest{"draft", "draft must be true or false"};
    request.draft = j["draft"].get<bool>();
  }
  if (takes_energy) {
    const Json* energy = j.contains("energy") ? &j["energy"] : nullptr;
    if (energy == nullptr || !energy->is_string() ||
        (*energy != "strain" && *energy != "curvature_variation")) {
      throw BadRequest{"energy", "energy must be \"strain\" or \"curvature_variation\""};
    }
    request.energy = energy->get<std::string>();
  }
  if (!j.contains("overrides")) return request;
  const Json& overrides = j["overrides"];
  if (!overrides.is_object()) throw BadRequest{"overrides", "overrides must be an object {NAME: value}"};
  for (const auto& [name, value] : overrides.items()) {
    const std::string field = "overrides." + name;
    std::string text;
    if (value.is_number()) {
      const double v = value.get<double>();
      if (!std::isfinite(v))
        throw BadRequest{field, fmt::format("{}: the value is not a finite number", field)};
      text = number_text(v);
    } else if (value.is_string()) {
      text = value.get<std::string>();
      if (text.empty() || text.find_first_of("\r\n") != std::string::npos)
        throw BadRequest{field, fmt::format("{}: the value must be a number or a one-line text", field)};
    } else if (value.is_boolean()) {
      text = value.get<bool>() ? "true" : "false";  // a switch
    } else if (value.is_null() && name == "parameter_set") {
      text = "null";  // no parameter set, whatever the file's `parameter_set`
    } else {
      throw BadRequest{field, fmt::format("{}: the value must be a number or a text", field)};
    }
    try {
      request.overrides.push_back(make_override(name, text));
    } catch (const InputError& e) {
      throw BadRequest{field, e.what()};
    }
  }
  return request;
}

// Plain names must be declared parameters (a -D path has a '.' or a '['),
// or `parameter_set` (the design judges the set's name).
void require_known_names(const Request& request, const std::vector<std::string>& declared) {
  for (const Override& o : request.overrides) {
    if (o.path.find_first_of(".[") != std::string::npos || o.path == "parameter_set") continue;
    bool known = false;
    std::string names;
    for (const std::string& name : declared) {
      known = known || name == o.path;
      names += (names.empty() ? "" : ", ") + name;
    }
    if (!known) {
      throw BadRequest{"overrides." + o.path,
                       fmt::format("overrides.{}: the design declares no parameter '{}' ({})", o.path, o.path,
                                   names.empty() ? "it declares none" : "its parameters are: " + names)};
    }
  }
}

// The 422 (or 500) answer of a failure: describe_failure's message, the
// same the command line prints, and where it is as data.
StudioResponse failure_response(const std::exception_ptr& error, const std::string& subject) {
  const Failure failure = describe_failure(error, subject);
  Json e = {{"message", failure.message}, {"exit_code", failure.exit_code}};
  try {
    std::rethrow_exception(error);
  } catch (const InputError& input) {
    const ErrorLocation& at = input.location();
    e["key"] = at.key.empty() ? Json(nullptr) : Json(at.key);
    // The override that gave the value at fault names the page's field.
    const std::string& given = at.override_text;
    e["field"] = given.empty() ? Json(nullptr) : Json(given.substr(0, given.find('=')));
    // The same as the request names it, as 400 answers name theirs.
    e["request_field"] =
        given.empty() ? Json(nullptr) : Json("overrides." + given.substr(0, given.find('=')));
    int line = at.line, column = at.column;
    if (const auto* file = dynamic_cast<const FileError*>(&input); file != nullptr && line == 0) {
      line = file->line();
      column = file->column();
    }
    e["line"] = line > 0 ? Json(line) : Json(nullptr);
    e["column"] = column > 0 ? Json(column) : Json(nullptr);
  } catch (...) {
    e["key"] = nullptr;
    e["field"] = nullptr;
    e["request_field"] = nullptr;
  }
  const int status = failure.exit_code == kExitBadInput || failure.exit_code == kExitInvalid ? 422 : 500;
  return json_response(status, {{"error", e}});
}

Json range_json(const std::string& key, double value, double min, double max, double step) {
  return {{"key", key}, {"value", value}, {"min", min}, {"max", max}, {"step", step}};
}

// The shape parameters of the design's curves that the design writes, with
// the ranges the schema gives them (docs/design-files.md, "Curves").
Json shape_parameters(const Design& design) {
  Json out = Json::array();
  const auto& where = design.common.where;
  for (const NamedCurve& c : design_curves(design)) {
    if (c.spec.family == CurveFamily::QuasiBSpline) {
      for (std::size_t i = 0; i < c.spec.bspline_lambdas.size(); ++i) {
        const std::string key = fmt::format("{}.lambdas[{}]", c.name, i);
        if (where.count(key) != 0) out.push_back(range_json(key, c.spec.bspline_lambdas[i], -8.0, 1.0, 0.01));
      }
      continue;
    }
    for (const SegmentSpec& s : c.spec.segments) {
      if (s.key.empty() || (s.kind != SegmentKind::TBezier && s.kind != SegmentKind::HBezier)) continue;
      double lo = -2.0;
      if (s.kind == SegmentKind::HBezier) {
        lo = hbezier_lambda_min(s.alpha);
        if (where.count(s.key + ".alpha") != 0)
          out.push_back(range_json(s.key + ".alpha", s.alpha, 0.01, 10.0, 0.01));
      }
      for (const auto& [name, value] : {std::pair{".lambda", s.lambda}, std::pair{".mu", s.mu}}) {
        Json r = range_json(s.key + name, value, lo, 1.0, 0.01);
        if (s.kind == SegmentKind::HBezier) r["min_exclusive"] = true;
        out.push_back(std::move(r));
      }
    }
  }
  return out;
}

constexpr int kLeastBSplinePoints = 3;  // n >= 2, as the reader requires

// The value at a key as `text` writes it; empty when it does not write it as one value.
using WrittenText = std::function<std::string(const std::string&)>;

// A quasi-B-spline's entry: its points (a curve through points: those, the
// plot's dots on its joints), its whole list and its lambdas as written (a
// point added or deleted adds or drops one; none when the text writes none:
// all 0). Null when a point is not written as a value.
Json quasi_bspline_points(const NamedCurve& c, const WrittenText& written) {
  const bool through = !c.spec.bspline_through.empty();
  const std::vector<Vec2>& given = through ? c.spec.bspline_through : c.spec.bspline_points;
  const std::string list = c.name + (through ? ".through" : ".points");
  Json points = Json::array();
  for (std::size_t i = 0; i < given.size(); ++i) {
    const std::string key = fmt::format("{}[{}]", list, i);
    const std::string as_written = written(key);
    if (as_written.empty()) return nullptr;
    points.push_back({{"key", key}, {"x", given[i].x()}, {"y", given[i].y()}, {"text", as_written}});
  }
  Json curve = {{"curve", c.name},
                {"group", through ? "through-points" : "control-polygon"},
                {"points", points},
                {"list", list},
                {"min_points", kLeastBSplinePoints}};
  Json lambdas = Json::array();
  for (std::size_t i = 0; i < c.spec.bspline_lambdas.size(); ++i) {
    const std::string as_written = written(fmt::format("{}.lambdas[{}]", c.name, i));
    if (as_written.empty()) break;
    lambdas.push_back(as_written);
  }
  if (lambdas.size() == c.spec.bspline_lambdas.size() && !lambdas.empty())
    curve["lambdas"] = {{"key", c.name + ".lambdas"}, {"texts", lambdas}};
  return curve;
}

// A T- or H-Bézier composite's entry: the points its segments give (the
// free ones after a join) that the text writes; and when every segment is
// a cubic the file writes whole, its segments (each one's entries as
// one-line YAML), which adding or deleting a segment replaces. Null when
// it gives no point.
Json composite_points(const NamedCurve& c, const WrittenText& written, const std::string& text,
                      const std::string& path) {
  Json points = Json::array();
  bool whole = !c.spec.segments.empty();
  Json segments = Json::array();
  for (const SegmentSpec& s : c.spec.segments) {
    if ((s.kind != SegmentKind::TBezier && s.kind != SegmentKind::HBezier) || s.key.empty()) {
      whole = false;
      continue;
    }
    Json keys = Json::array();
    for (std::size_t j = 0; j < s.points.size(); ++j) {
      const std::string key = fmt::format("{}.points[{}]", s.key, j);
      const std::string as_written = written(key);
      if (as_written.empty()) {
        whole = false;
        continue;
      }
      points.push_back({{"key", key}, {"x", s.points[j].x()}, {"y", s.points[j].y()}, {"text", as_written}});
      keys.push_back(key);
    }
    if (!whole) continue;
    try {
      Json entries = Json::array();
      for (const auto& [name, value] : flow_entries(text, path, s.key)) entries.push_back({name, value});
      segments.push_back(
          {{"key", s.key}, {"entries", entries}, {"points", keys}, {"joined", s.join.has_value()}});
    } catch (const FileError&) {
      whole = false;  // a segment written as an expression: not rewritten
    }
  }
  if (points.empty()) return nullptr;
  Json curve = {{"curve", c.name}, {"by", "position"}, {"points", points}};
  if (whole) {
    const std::string& first = c.spec.segments.front().key;
    curve["segments"] = {
        {"key", first.substr(0, first.rfind('['))}, {"closed", c.spec.closed}, {"items", segments}};
  }
  return curve;
}

// The control points the page may drag on the plot, each with the -D path
// save replaces: a quasi-B-spline's points (the plot's circles of its curve,
// one to one, in order), and the points a T- or H-Bézier segment gives (the
// free ones after a join), found on the plot by position ("by": "position";
// a point two segments share is one circle per segment). A point is offered
// only where the text writes it, as a value save can replace (a point given
// as an expression becomes the numbers it is dragged to), with its text as
// written. A quasi-B-spline's whole list (`list`, with its lambdas as
// written) is what adding or deleting a point replaces.
Json draggable_points(const Design& design, const std::string& text) {
  const WrittenText written = [&](const std::string& key) -> std::string {
    try {
      const ValueSpan span = value_span(text, design.common.path, key);
      return text.substr(span.begin, span.end - span.begin);
    } catch (const FileError&) {
      return {};
    }
  };
  Json out = Json::array();
  for (const NamedCurve& c : design_curves(design)) {
    Json curve = c.spec.family == CurveFamily::QuasiBSpline
                     ? quasi_bspline_points(c, written)
                     : composite_points(c, written, text, design.common.path);
    if (!curve.is_null()) out.push_back(std::move(curve));
  }
  return out;
}

// The design's text with the request's overrides written in, as save would
// write them (each one that save can place; the others are left out): where
// the draggable points of these values are written, and how.
std::string text_with(const std::string& text, const std::string& path, const Request& request) {
  std::string edited = text;
  for (const Override& o : request.overrides) {
    try {
      edited = edit_values(edited, path, {o});
    } catch (const FileError&) {
      // not a value save can write (a key the file does not have): its points stay as the file has them
    }
  }
  return edited;
}

// Why fairing for `mode` leaves curve `c` as it is; empty when it fairs it:
// a quasi-B-spline given by control points (either energy), or a T-Bézier
// composite whose cubic segments have shape parameters (curvature variation).
std::string not_faired(const CurveSpec& c, FairMode mode) {
  if (c.family == CurveFamily::QuasiBSpline) {
    return c.bspline_through.empty() ? ""
                                     : "a curve through points keeps them; fairing its lambdas with its "
                                       "control points fixed would move it off them";
  }
  if (c.family != CurveFamily::TBezier || mode == FairMode::Strain) {
    return fmt::format(
        "{} fairing applies to {}", to_string(mode),
        mode == FairMode::Strain ? "quasi_bspline curves" : "tbezier and quasi_bspline curves");
  }
  const bool cubic = std::any_of(c.segments.begin(), c.segments.end(), [](const SegmentSpec& s) {
    return s.kind == SegmentKind::TBezier && !s.key.empty();
  });
  return cubic ? "" : "its segments are lines and arcs, which have no shape parameters";
}

// The energies the page's "fairest" buttons can minimise for this design.
Json fair_energies(const Design& design) {
  Json out = Json::array();
  const std::vector<NamedCurve> curves = design_curves(design);
  for (const FairMode mode : {FairMode::Strain, FairMode::CurvatureVariation}) {
    if (std::any_of(curves.begin(), curves.end(),
                    [&](const NamedCurve& c) { return not_faired(c.spec, mode).empty(); }))
      out.push_back(to_string(mode));
  }
  return out;
}

Json parameters_json(const Design& design) {
  Json out = Json::array();
  for (const DesignParameter& p : design.common.parameters) {
    Json j = {{"name", p.name}, {"value", p.value}};
    j["kind"] = p.kind == ParameterKind::Choice   ? "choice"
                : p.kind == ParameterKind::Switch ? "switch"
                                                  : "number";
    if (p.kind != ParameterKind::Number) j["text"] = p.text;
    if (p.kind == ParameterKind::Choice) j["choices"] = p.choices;
    j["min"] = p.min ? Json(*p.min) : Json(nullptr);
    j["max"] = p.max ? Json(*p.max) : Json(nullptr);
    j["step"] = p.step ? Json(*p.step) : Json(nullptr);
    j["description"] = p.description;
    out.push_back(std::move(j));
  }
  return out;
}

std::string file_version(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return "missing";
  return fmt::format("{}.{:09d}-{}", st.st_mtim.tv_sec, st.st_mtim.tv_nsec, st.st_size);
}

double elapsed_ms(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since).count();
}

// The design file's text, checked for the names the request uses, and the
// design it makes with the request's overrides.
struct Requested {
  std::string text;
  Design design;
};

// The request field of the override that put `key` in the design: the last
// one whose path is `key` or holds it ("outline" holds "outline.dxf").
std::string request_field(const Request& request, const std::string& key) {
  for (auto o = request.overrides.rbegin(); o != request.overrides.rend(); ++o) {
    const std::string& p = o->path;
    if (key.compare(0, p.size(), p) == 0 &&
        (key.size() == p.size() || key[p.size()] == '.' || key[p.size()] == '['))
      return "overrides." + p;
  }
  return "overrides";
}

// Overrides may name only the files the design names itself (or none): a
// request must not make the studio read, and quote in a message, a file the
// design does not use (/etc/passwd as outline.dxf). Checked in the tree,
// before anything but the design's text is read.
void require_referenced_files(const Request& request, const std::string& text, const std::string& path) {
  if (request.overrides.empty()) return;
  std::set<std::string> named;
  for (const FileReference& r : file_references(text, path)) named.insert(r.file);
  for (const FileReference& r : file_references(text, path, request.overrides)) {
    if (named.count(r.file) != 0) continue;
    const std::string field = request_field(request, r.key);
    throw BadRequest{field, fmt::format("{}: {} may only name a file the design names itself (the "
                                        "studio reads no other file); change the file in the design",
                                        field, r.key)};
  }
}

Requested read_requested(const Request& request, const std::string& path, const DeclaredNames& names) {
  std::string text = read_design_text(path);
  require_known_names(request, names.of(text, path));
  require_referenced_files(request, text, path);
  Design design = load_design_text(text, path, request.overrides);
  return {std::move(text), std::move(design)};
}

// A build's report, `run --json`'s item of a result that encoded nothing: the
// facts only encoding gives (the files, their added errors, the outputs
// skipped) are left out, and "pending" says so, with the formats export encodes.
Json pending_outputs(Json item, const std::vector<const OutputFormat*>& formats) {
  Json names = Json::array();
  for (const OutputFormat* f : formats) names.push_back(std::string(f->name));
  for (const char* key : {"outputs", "files", "skipped_outputs"}) item.erase(key);
  item["pending"] = {
      {"formats", names}, {"facts", {"outputs", "files", "skipped_outputs"}}, {"until", "export"}};
  return item;
}

// A request's answer: `f`'s, or 400 for a bad request, or the command line's
// failure as JSON.
template <class F>
StudioResponse answered(const std::string& path, F&& f) {
  try {
    return f();
  } catch (const BadRequest& e) {
    return bad_request(e);
  } catch (...) {
    return failure_response(std::current_exception(), path);
  }
}

}  // namespace

std::string studio_build_report(const std::string& design_path, const Result& result,
                                const std::vector<const OutputFormat*>& formats) {
  return pending_outputs(design_item(design_path, result), formats).dump();
}

std::vector<std::string> DeclaredNames::of(const std::string& text, const std::string& path) const {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (read_ && text_ == text) return names_;
  }
  std::vector<std::string> names;
  for (const DesignParameter& p : load_design_text(text, path).common.parameters) names.push_back(p.name);
  const std::lock_guard<std::mutex> lock(mutex_);
  read_ = true;
  text_ = text;
  names_ = names;
  return names;
}

StudioSession::StudioSession(StudioSessionOptions options) : options_(std::move(options)) {
  (void)load_design(options_.design_path);
}

StudioSession::~StudioSession() = default;

StudioResponse StudioSession::design() const {
  try {
    const std::string version = file_version(options_.design_path);
    const std::string text = read_design_text(options_.design_path);
    const Design design = load_design_text(text, options_.design_path);
    Json j = {{"path", options_.design_path}, {"name", design.common.name}, {"kind", kind_name(design)},
              {"units", design.common.units}, {"version", version},         {"text", text}};
    j["parameters"] = parameters_json(design);
    // A set that does not make a design with the file's values now (an
    // expression out of its range) has no example: the page still opens,
    // and picking the set shows the error.
    j["schema"] = parameter_schema(design, [&](const std::string& set) -> std::optional<Design> {
      try {
        return load_design_text(text, options_.design_path, {make_override("parameter_set", set)});
      } catch (const InputError&) {
        return std::nullopt;
      }
    });
    j["parameter_set"] = design.common.parameter_set;
    Json sets = Json::array();
    for (const ParameterSet& set : design.common.parameter_sets) sets.push_back(set.name);
    j["parameter_sets"] = std::move(sets);
    j["shape_parameters"] = shape_parameters(design);
    j["control_points"] = draggable_points(design, text);
    j["fair_energies"] = fair_energies(design);
    j["out_dir"] = options_.out_dir;
    return json_response(200, j);
  } catch (...) {
    return failure_response(std::current_exception(), options_.design_path);
  }
}

StudioResponse StudioSession::build(const std::string& request_body) {
  const auto start = std::chrono::steady_clock::now();
  return answered(options_.design_path, [&] {
    const Request request = parse_request(request_body, RequestFields::Build);
    Requested requested = read_requested(request, options_.design_path, names_);
    Design& design = requested.design;
    Json stages = Json::object();  // the studio's own times, ms (the job's are the report's timings_ms)
    stages["design"] = elapsed_ms(start);
    std::optional<std::string> glb;
    std::string plot_svg;
    std::optional<std::string> layout_svg;  // a kitchen's slabs
    Json router_paths = Json::array();      // a countertop's router programs, drawn
    Json mesh_parts = Json::array();        // the mesh's parts, when it has several
    std::size_t triangles = 0;
    const auto show = [&](const Result& built) {
      auto lap = std::chrono::steady_clock::now();
      plot_svg = plot_curves_svg(shape_plot(design.common, built));
      if (const auto* top = std::get_if<CountertopProducts>(&built.products);
          top != nullptr && top->kitchen) {
        LayoutOptions layout;
        layout.units = design.common.units;
        layout.title = design.common.name;
        layout_svg =
            encode_layout_svg(top->kitchen->split.pieces, top->kitchen->stock, top->kitchen->nesting, layout);
      }
      // With `cnc`: each program's path over what it cuts, as the toolpath_svg output draws it.
      if (const auto* top = std::get_if<CountertopProducts>(&built.products);
          top != nullptr &&
          (top->kitchen ? !top->kitchen->slab_toolpaths.empty() : top->toolpath.has_value())) {
        ToolpathSvgOptions drawing;
        drawing.units = design.common.units;
        for (const RouterProgram& program : router_programs(*top)) {
          router_paths.push_back({{"program", design.common.name + program.suffix},
                                  {"parts", program.parts},
                                  {"svg", encode_toolpath_svg(program.part, *program.path, drawing)}});
        }
      }
      stages["plot"] = elapsed_ms(lap);
      if (product(built) != nullptr) {
        lap = std::chrono::steady_clock::now();
        GlbOptions glb_options;
        glb_options.name = design.common.name;
        glb_options.scale_to_metres = metres_per_unit(design.common.units);
        // A mould's parts apart, as in the preview; several parts are one
        // primitive each, named by its material, so the page can hide them.
        const ExplodedScene scene = exploded_scene_parts(built);
        triangles = scene.soup.triangles.size();
        if (scene.parts.size() > 1) {
          for (const ExplodedScene::Range& part : scene.parts) {
            glb_options.face_materials.insert(glb_options.face_materials.end(), part.triangles,
                                              static_cast<std::uint32_t>(glb_options.materials.size()));
            glb_options.materials.push_back({part.name, {0.8, 0.8, 0.8, 1.0}});
            mesh_parts.push_back(part.name);
          }
        }
        glb = encode_glb(scene.soup, glb_options);
        stages["mesh"] = elapsed_ms(lap);
      }
    };
    Json j;
    if (request.draft) {
      // A coarser mesh of the same shape to show at once; no verdict: the
      // proven build's answer gives that.
      auto lap = std::chrono::steady_clock::now();
      const Result built = build_draft(design);
      stages["build"] = elapsed_ms(lap);
      show(built);
      j = {{"draft", {{"tolerance", built.tolerance}, {"triangles", triangles}}}, {"plot_svg", plot_svg}};
    } else {
      // The proven build, shown valid or not; export encodes the outputs, so
      // the report says which facts wait for it.
      JobOptions options;
      options.out_dir = options_.out_dir;
      auto lap = std::chrono::steady_clock::now();
      const JobPlan plan = plan_job(design, options);
      const Result built = build_job(design, plan);
      show(built);
      require_fit(built, design.common.purpose);
      stages["job"] = elapsed_ms(lap);
      j = {{"report", Json::parse(studio_build_report(options_.design_path, built, plan.formats))},
           {"plot_svg", plot_svg}};
    }
    // Where the draggable points are with these values (a dragged or
    // parameter-driven point has moved from where the file puts it).
    j["control_points"] = draggable_points(design, text_with(requested.text, options_.design_path, request));
    // The shape parameters of these values (a point added adds a lambda).
    j["shape_parameters"] = shape_parameters(design);
    j["layout_svg"] = layout_svg ? Json(*layout_svg) : Json(nullptr);
    j["router_paths"] = std::move(router_paths);
    j["mesh_parts"] = std::move(mesh_parts);
    j["mesh"] = nullptr;
    if (glb) {
      const std::lock_guard<std::mutex> lock(mutex_);
      const std::string id = fmt::format("m{}", next_mesh_++);
      meshes_.emplace_back(id, std::move(*glb));
      while (meshes_.size() > options_.kept_meshes) meshes_.pop_front();
      j["mesh"] = "/api/mesh/" + id + ".glb";
    }
    j["build_ms"] = elapsed_ms(start);
    j["stages_ms"] = stages;
    return json_response(200, j);
  });
}

StudioResponse StudioSession::mesh(const std::string& id) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [mesh_id, bytes] : meshes_) {
    if (mesh_id == id) return {200, "model/gltf-binary", bytes};
  }
  return json_response(404, {{"error", {{"message", fmt::format("no mesh '{}' (build again)", id)}}}});
}

StudioResponse StudioSession::export_outputs(const std::string& request_body) {
  return answered(options_.design_path, [&] {
    const Design design = read_requested(parse_request(request_body), options_.design_path, names_).design;
    JobOptions job;
    job.out_dir = options_.out_dir;
    auto [report, encoded] = prepare_job(design, job);
    StageTimer watch(report.timings_ms);
    write_job(encoded);
    watch.lap("write");
    Json j = {{"out_dir", options_.out_dir}, {"files", written_paths(report)}};
    j["report"] = design_item(options_.design_path, report);
    return json_response(200, j);
  });
}

StudioResponse StudioSession::save(const std::string& request_body) {
  return answered(options_.design_path, [&] {
    const Request request = parse_request(request_body);
    // The values must make a design before they replace the file's.
    const std::string text = read_requested(request, options_.design_path, names_).text;
    const std::string edited = edit_values(text, options_.design_path, request.overrides);
    (void)load_design_text(edited, options_.design_path);
    write_file_atomically(options_.design_path, edited);
    Json changed = Json::array();
    for (const Override& o : request.overrides) changed.push_back(o.path);
    return json_response(200, {{"saved", options_.design_path},
                               {"changed", changed},
                               {"version", file_version(options_.design_path)}});
  });
}

StudioResponse StudioSession::save_set(const std::string& request_body) {
  return answered(options_.design_path, [&] {
    const Json body = parse_body(request_body);
    if (!body.is_object() || !body.contains("name") || !body["name"].is_string())
      throw BadRequest{"name", "name: the set's name, a text, is required"};
    const std::string name = body["name"].get<std::string>();
    if (const std::string problem = parameter_set_name_problem(name); !problem.empty())
      throw BadRequest{"name", "name: " + problem};
    Json rest = body;
    rest.erase("name");
    const Request request = parse_request(rest.dump());
    const Requested requested = read_requested(request, options_.design_path, names_);
    if (requested.design.common.parameters.empty())
      throw BadRequest{"name", "name: the design declares no parameters: a set gives values to `parameters`"};
    // Every parameter's value as the page shows it: the set reproduces this design.
    std::vector<std::pair<std::string, std::string>> values;
    for (const DesignParameter& p : requested.design.common.parameters)
      values.emplace_back(p.name, number_text(p.value));
    const std::string edited = add_parameter_set(requested.text, options_.design_path, name, values);
    (void)load_design_text(edited, options_.design_path);
    write_file_atomically(options_.design_path, edited);
    return json_response(200, {{"saved", options_.design_path},
                               {"parameter_set", name},
                               {"version", file_version(options_.design_path)}});
  });
}

StudioResponse StudioSession::fairest(const std::string& request_body) {
  return answered(options_.design_path, [&] {
    const Request request = parse_request(request_body, RequestFields::Fairest);
    const Design design = read_requested(request, options_.design_path, names_).design;
    const FairMode mode = request.energy == "strain" ? FairMode::Strain : FairMode::CurvatureVariation;
    Json overrides = Json::object();
    Json skipped = Json::array();
    for (const NamedCurve& c : design_curves(design)) {
      const bool bspline = c.spec.family == CurveFamily::QuasiBSpline;
      const std::string reason = not_faired(c.spec, mode);
      if (!reason.empty()) {
        skipped.push_back({{"curve", c.name}, {"reason", reason}});
        continue;
      }
      CurveSpec spec = c.spec;
      spec.fair = mode;
      const BuiltCurve built = in_design(design, [&] { return build_curve(spec); });
      if (bspline && built.bspline) {
        for (std::size_t i = 0; i < built.bspline->lambdas.size(); ++i)
          overrides[fmt::format("{}.lambdas[{}]", c.name, i)] = built.bspline->lambdas[i];
      }
      for (const SegmentFairing& f : built.segments) {
        const std::string& key = spec.segments.at(f.index).key;
        if (key.empty()) continue;
        overrides[key + ".lambda"] = f.lambda;
        overrides[key + ".mu"] = f.mu;
      }
    }
    return json_response(200, {{"energy", request.energy}, {"overrides", overrides}, {"skipped", skipped}});
  });
}

StudioResponse StudioSession::version() const {
  return json_response(200, {{"version", file_version(options_.design_path)}});
}

}  // namespace fabmesh
