#include "io/dxf/dxf_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <optional>

#include "geometry/core/errors.h"
#include "io/dxf/dxf_groups.h"

namespace fabmesh {
namespace {

enum class Kind { Line, Arc, Circle, Ellipse, LwPolyline, Polyline, Spline, Other };

Kind kind_of(const std::string& type) {
  if (type == "LINE") return Kind::Line;
  if (type == "ARC") return Kind::Arc;
  if (type == "CIRCLE") return Kind::Circle;
  if (type == "ELLIPSE") return Kind::Ellipse;
  if (type == "LWPOLYLINE") return Kind::LwPolyline;
  if (type == "POLYLINE") return Kind::Polyline;
  if (type == "SPLINE") return Kind::Spline;
  return Kind::Other;
}

// How many points an entity of `kind` has before its groups are read.
std::size_t fixed_points(Kind kind) {
  switch (kind) {
    case Kind::Line:
    case Kind::Ellipse:
      return 2;
    case Kind::Arc:
    case Kind::Circle:
      return 1;
    default:
      return 0;
  }
}

// A handle as messages name it: 1 to 16 hexadecimal digits, upper-case.
std::string handle_of(std::string_view value) {
  if (value.empty() || value.size() > 16) return "";
  std::string out;
  for (const char c : value) {
    if (!std::isxdigit(static_cast<unsigned char>(c))) return "";
    out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return out;
}

// A POLYLINE's VERTEX as read.
struct Vertex {
  Vec3 point{0.0, 0.0, 0.0};
  double bulge = 0.0;
  int flags = 0;
};

// The counts an entity announces before its entries.
struct Announced {
  std::optional<long long> vertices;  // LWPOLYLINE [90]
  std::optional<long long> knots;     // SPLINE [72]
  std::optional<long long> control;   // SPLINE [73]
  std::optional<long long> fit;       // SPLINE [74]
};

class DrawingParser {
 public:
  DrawingParser(DxfGroupReader& reader, const DxfEntitySink& sink) : r_(reader), sink_(sink) {}

  DxfHeader run() {
    advance();
    for (;;) {
      if (!have_) cut_short("without its EOF");
      if (g_.code == 999) {
        advance();
        continue;
      }
      if (g_.code != 0 || (g_.value != "SECTION" && g_.value != "EOF"))
        r_.fail(g_.line, fmt::format("group {} '{}' where a SECTION or the EOF belongs", g_.code, quoted()));
      if (g_.value == "EOF") return header_;
      section();
    }
  }

 private:
  bool advance() {
    have_ = r_.next(g_);
    return have_;
  }
  bool at_zero(std::string_view name) const { return have_ && g_.code == 0 && g_.value == name; }
  std::string quoted() const {
    return g_.value.size() <= 40 ? std::string(g_.value) : std::string(g_.value.substr(0, 40)) + "...";
  }
  [[noreturn]] void cut_short(const std::string& where) const {
    r_.fail(r_.line(),
            fmt::format("the drawing ends {}: the file is cut short (a DXF drawing ends with 0 EOF)", where));
  }

  // From `0 SECTION` to past its `0 ENDSEC`.
  void section() {
    const std::size_t at = g_.line;
    if (!advance() || g_.code != 2) r_.fail(at, "a SECTION without its name (group 2)");
    const std::string name(g_.value);
    advance();
    if (name == "HEADER") {
      header();
    } else if (name == "ENTITIES") {
      entities();
    } else {
      skip(name);  // BLOCKS (block definitions), TABLES, OBJECTS, ...
    }
    advance();  // past ENDSEC
  }
  void end_of_section(const std::string& name) {
    if (!have_) cut_short(fmt::format("inside its {} section, before ENDSEC", name));
    if (at_zero("EOF") || at_zero("SECTION"))
      r_.fail(g_.line, fmt::format("the {} section has no ENDSEC before this {}", name, quoted()));
  }
  void skip(const std::string& name) {
    for (;;) {
      end_of_section(name);
      if (at_zero("ENDSEC")) return;
      advance();
    }
  }
  void header() {
    std::string variable;
    for (;;) {
      end_of_section("HEADER");
      if (at_zero("ENDSEC")) return;
      if (g_.code == 9) variable = std::string(g_.value);
      if (g_.code == 70 && variable == "$INSUNITS") header_.insunits = small("$INSUNITS");
      advance();
    }
  }
  void entities() {
    for (;;) {
      end_of_section("ENTITIES");
      if (at_zero("ENDSEC")) return;
      if (g_.code == 999) {
        advance();
        continue;
      }
      if (g_.code != 0)
        r_.fail(g_.line, fmt::format("group {} '{}' where an entity (group 0) belongs", g_.code, quoted()));
      entity();
    }
  }

  // One entity from its `0 TYPE`, up to the next group 0 (a POLYLINE: past its SEQEND).
  void entity() {
    e_.type = std::string(g_.value);
    e_.line = g_.line;
    e_.layer = "0";
    e_.handle.clear();
    e_.paper_space = false;
    e_.extrusion = Vec3(0.0, 0.0, 1.0);
    e_.points.assign(fixed_points(kind_of(e_.type)), Vec3(0.0, 0.0, 0.0));
    e_.bulges.clear();
    e_.elevation = e_.radius = e_.start = e_.end = 0.0;
    e_.flags = e_.degree = 0;
    e_.knots.clear();
    e_.weights.clear();
    e_.fit_points = 0;
    announced_ = Announced{};
    const Kind kind = kind_of(e_.type);
    if (e_.type == "VERTEX") r_.fail(g_.line, "a VERTEX outside a POLYLINE");
    count();
    while (advance() && g_.code != 0) group(kind);
    if (kind == Kind::Polyline) vertices();
    if (kind == Kind::LwPolyline || kind == Kind::Polyline) {
      for (Vec3& p : e_.points) p.z() += e_.elevation;
    }
    check_counts();
    sink_(e_);
  }
  // A POLYLINE's VERTEX entities and its SEQEND.
  void vertices() {
    while (at_zero("VERTEX")) {
      count();
      Vertex v;
      while (advance() && g_.code != 0) vertex_group(v);
      if ((v.flags & 16) != 0) continue;  // a spline frame's control point, not on the curve
      e_.points.push_back(v.point);
      e_.bulges.push_back(v.bulge);
    }
    if (!have_) cut_short(fmt::format("inside {}, before its SEQEND", dxf_entity_name(e_)));
    if (!at_zero("SEQEND"))
      r_.fail(g_.line, fmt::format("{} has no SEQEND before this {}", dxf_entity_name(e_), quoted()));
    while (advance() && g_.code != 0) {
    }
  }

  void group(Kind kind) {
    switch (g_.code) {
      case 5:
        e_.handle = handle_of(g_.value);
        return;
      case 8:
        e_.layer = std::string(g_.value);
        return;
      case 67:
        e_.paper_space = integer() == 1;
        return;
      case 210:
      case 220:
      case 230:
        e_.extrusion[g_.code / 10 - 21] = number();
        return;
      default:
        break;
    }
    switch (kind) {
      case Kind::Line:
      case Kind::Arc:
      case Kind::Circle:
      case Kind::Ellipse:
        return curve_group(kind);
      case Kind::LwPolyline:
        return lwpolyline_group();
      case Kind::Polyline:
        if (g_.code == 70) e_.flags = small();
        if (g_.code == 30) e_.elevation = number();
        return;
      case Kind::Spline:
        return spline_group();
      case Kind::Other:
        return;
    }
  }
  // LINE, ARC, CIRCLE, ELLIPSE: fixed points (10.., 11..) and numbers.
  void curve_group(Kind kind) {
    const int c = g_.code;
    const std::size_t index = static_cast<std::size_t>(c % 10);
    if (c >= 10 && c <= 31 && c % 10 <= 1 && index < e_.points.size()) {
      e_.points[index][static_cast<Eigen::Index>(c / 10 - 1)] = number();
      return;
    }
    if (c == 40) e_.radius = number();
    if (kind == Kind::Arc || kind == Kind::Ellipse) {
      if (c == (kind == Kind::Arc ? 50 : 41)) e_.start = number();
      if (c == (kind == Kind::Arc ? 51 : 42)) e_.end = number();
    }
  }
  void lwpolyline_group() {
    switch (g_.code) {
      case 90:
        announced_.vertices = announced_count();
        return;
      case 70:
        e_.flags = small();
        return;
      case 38:
        e_.elevation = number();
        return;
      case 10:
        count();
        e_.points.emplace_back(number(), 0.0, 0.0);
        e_.bulges.push_back(0.0);
        return;
      case 20:
        last_point(10).y() = number();
        return;
      case 42:
        last_point(10);
        e_.bulges.back() = number();
        return;
      default:
        return;
    }
  }
  void spline_group() {
    switch (g_.code) {
      case 70:
        e_.flags = small();
        return;
      case 71:
        e_.degree = small();
        return;
      case 72:
        announced_.knots = announced_count();
        return;
      case 73:
        announced_.control = announced_count();
        return;
      case 74:
        announced_.fit = announced_count();
        return;
      case 40:
        count();
        e_.knots.push_back(number());
        return;
      case 41:
        count();
        e_.weights.push_back(number());
        return;
      case 10:
        count();
        e_.points.emplace_back(number(), 0.0, 0.0);
        return;
      case 20:
        last_point(10).y() = number();
        return;
      case 30:
        last_point(10).z() = number();
        return;
      case 11:
        ++e_.fit_points;
        return;
      default:
        return;
    }
  }
  void vertex_group(Vertex& v) {
    const int c = g_.code;
    if (c == 10 || c == 20 || c == 30) v.point[static_cast<Eigen::Index>(c / 10 - 1)] = number();
    if (c == 42) v.bulge = number();
    if (c == 70) v.flags = small();
  }

  // The point a group of a point's later coordinates belongs to.
  Vec3& last_point(int first_code) {
    if (e_.points.empty()) {
      r_.fail(g_.line,
              fmt::format("{}: group {} comes before any point's group {}", name(), g_.code, first_code));
    }
    return e_.points.back();
  }

  void check_counts() const {
    auto agree = [&](const std::optional<long long>& said, std::size_t found, int code, const char* what) {
      if (said && static_cast<std::size_t>(*said) != found) {
        r_.fail(e_.line,
                fmt::format("{}: group {} gives {} {}, but {} follow (the entity is cut or inconsistent)",
                            name(), code, *said, what, found));
      }
    };
    agree(announced_.vertices, e_.points.size(), 90, "vertices");
    agree(announced_.knots, e_.knots.size(), 72, "knots");
    agree(announced_.control, e_.points.size(), 73, "control points");
    agree(announced_.fit, e_.fit_points, 74, "fit points");
    if (kind_of(e_.type) == Kind::Spline && !e_.weights.empty() && e_.weights.size() != e_.points.size()) {
      r_.fail(e_.line, fmt::format("{}: {} weights (group 41) for {} control points", name(),
                                   e_.weights.size(), e_.points.size()));
    }
  }

  // A count no larger than the file could hold.
  long long announced_count() const {
    const long long n = integer();
    if (n < 0 || static_cast<unsigned long long>(n) > r_.lines()) {
      r_.fail(g_.line + 1, fmt::format("{} group {} announces {} entries; the file has {} lines", e_.type,
                                       g_.code, n, r_.lines()));
    }
    return n;
  }
  void count() {
    if (++items_ > kMaxDxfItems) {
      r_.fail(g_.line,
              fmt::format("more than {} entities and polyline vertices: not a template fabmesh reads",
                          kMaxDxfItems));
    }
  }
  // The group's value as an int; `what` names it in messages (null: the entity).
  int small(const char* what = nullptr) const {
    const std::optional<long long> v = dxf_integer(g_.value);
    if (!v) r_.bad_value(g_, what != nullptr ? std::string(what) : name(), "a whole number");
    if (*v < INT_MIN || *v > INT_MAX) {
      r_.fail(g_.line + 1, fmt::format("{}: group {}: {} is out of range",
                                       what != nullptr ? std::string(what) : name(), g_.code, *v));
    }
    return static_cast<int>(*v);
  }
  // The group's value; the entity is named only when it is not one (the name costs a format).
  double number() const {
    const std::optional<double> v = dxf_number(g_.value);
    if (!v) r_.bad_value(g_, name(), "a finite number");
    return *v;
  }
  long long integer() const {
    const std::optional<long long> v = dxf_integer(g_.value);
    if (!v) r_.bad_value(g_, name(), "a whole number");
    return *v;
  }
  std::string name() const { return dxf_entity_name(e_); }

  DxfGroupReader& r_;
  const DxfEntitySink& sink_;
  DxfGroup g_;
  bool have_ = false;
  DxfHeader header_;
  DxfEntity e_;
  Announced announced_;
  std::size_t items_ = 0;
};

}  // namespace

std::string dxf_entity_name(const DxfEntity& entity) {
  return entity.handle.empty() ? fmt::format("{} (line {})", entity.type, entity.line)
                               : fmt::format("{} #{}", entity.type, entity.handle);
}

DxfHeader read_dxf(std::string_view bytes, const std::string& path, const DxfEntitySink& sink) {
  if (bytes.empty())
    throw FileError(path, 0, 0, fmt::format("{}: the file is empty, not a DXF drawing", path));
  if (bytes.substr(0, 18) == "AutoCAD Binary DXF") {
    throw FileError(
        path, 0, 0,
        fmt::format("{}: a binary DXF; fabmesh reads ASCII DXF (save the drawing as ASCII DXF)", path));
  }
  DxfGroupReader reader(bytes, path);
  return DrawingParser(reader, sink).run();
}

std::vector<DxfEntity> read_dxf_entities(std::string_view bytes, const std::string& path) {
  std::vector<DxfEntity> out;
  read_dxf(bytes, path, [&](const DxfEntity& e) { out.push_back(e); });
  return out;
}

}  // namespace fabmesh
