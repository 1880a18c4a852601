#include "io/design/dxf_loops.h"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "geometry/curves/segment.h"
#include "io/design/number_limits.h"
#include "io/file.h"

namespace fabmesh {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = 180.0 / kPi;
constexpr std::size_t kMaxDxfBytes = 64u << 20;

// The $INSUNITS codes a drawing may carry: metres per unit.
struct DxfUnit {
  int code;
  const char* name;
  double metres;
};
constexpr DxfUnit kDxfUnits[] = {
    {1, "in", 0.0254}, {2, "ft", 0.3048}, {4, "mm", 1e-3}, {5, "cm", 1e-2}, {6, "m", 1.0},
};

// One span of a spline as a cubic Bézier curve: polynomial, or rational with
// the points' (positive) weights.
struct BezierSpan {
  std::array<Vec2, 4> points{};
  std::array<double, 4> weights{1.0, 1.0, 1.0, 1.0};
  bool rational = false;
};

// One piece of a loop: a line, an exact arc or an exact spline (as cubic
// Bézier pieces), in the drawing's direction, in drawing units.
struct Piece {
  bool arc = false;
  bool spline = false;
  Vec2 start{0.0, 0.0}, end{0.0, 0.0};
  EllipseArcParams ellipse;         // arcs
  std::vector<BezierSpan> beziers;  // splines: cubic Bézier spans, in order
  std::string entity;               // "LINE #2F", "LWPOLYLINE #30 vertex 4"
  bool closed = false;              // a whole circle or ellipse: a loop by itself
  std::size_t order = 0;            // its entity's place in the file
};

// A polyline as read: vertices (x, y) with the bulge of the span after each.
struct Polyline {
  std::string entity;
  std::size_t order = 0;
  bool closed = false;
  bool mirrored = false;
  std::vector<std::array<double, 3>> vertices;
};

// A SPLINE as read: degree, knots, control points (x, y, z) and weights.
struct SplineData {
  std::string entity;
  std::size_t order = 0;
  int degree = 0;
  bool closed = false;
  std::vector<double> knots;
  std::vector<std::array<double, 4>> control;  // x, y, z, w
  std::size_t fit_points = 0;
};

std::string fmt_point(const Vec2& p) { return fmt::format("({:.10g}, {:.10g})", p.x(), p.y()); }

// The point at u of the B-spline of degree p on its span k (knots[k] <= u <=
// knots[k + 1]), by de Boor's algorithm on the span's p + 1 control points.
Vec2 de_boor(const std::vector<double>& knots, const std::vector<Vec2>& points, int p, std::size_t k,
             double u) {
  const std::size_t q = static_cast<std::size_t>(p);
  std::array<Vec2, 4> d;
  for (std::size_t j = 0; j <= q; ++j) d[j] = points[k - q + j];
  for (std::size_t r = 1; r <= q; ++r) {
    for (std::size_t j = q; j >= r; --j) {
      const std::size_t i = k - q + j;
      const double den = knots[i + q + 1 - r] - knots[i];
      const double a = den > 0.0 ? (u - knots[i]) / den : 0.0;
      d[j] = (1.0 - a) * d[j - 1] + a * d[j];
    }
  }
  return d[q];
}

// The cubic Bézier control points of span k of a non-rational B-spline of
// degree 1..3: the span is a polynomial of degree <= 3, so its cubic Bézier
// is fixed by its points at t = 0, 1/3, 2/3, 1 (de Boor on the span's own
// control points: the degree raised exactly).
std::array<Vec2, 4> span_bezier(const std::vector<double>& knots, const std::vector<Vec2>& points, int p,
                                std::size_t k) {
  const double a = knots[k], b = knots[k + 1];
  const Vec2 p0 = de_boor(knots, points, p, k, a), p3 = de_boor(knots, points, p, k, b);
  const Vec2 s1 = de_boor(knots, points, p, k, a + (b - a) / 3.0);
  const Vec2 s2 = de_boor(knots, points, p, k, a + 2.0 * (b - a) / 3.0);
  // B(1/3) = (8 P0 + 12 P1 + 6 P2 + P3) / 27 and B(2/3) = (P0 + 6 P1 + 12 P2 + 8 P3) / 27.
  const Vec2 u = 27.0 * s1 - 8.0 * p0 - p3, v = 27.0 * s2 - p0 - 8.0 * p3;
  return {p0, (2.0 * u - v) / 18.0, (2.0 * v - u) / 18.0, p3};
}

// The blossom f(u_1, ..., u_p) of span k of a B-spline of degree p: de Boor's
// algorithm with u_r at level r. With every u_r in the span each step is a
// convex combination, so the weights of homogeneous points stay positive
// and keep their relative precision however far apart they are.
Eigen::Vector3d blossom(const std::vector<double>& knots, const std::vector<Eigen::Vector3d>& points, int p,
                        std::size_t k, const std::array<double, 3>& u) {
  const std::size_t q = static_cast<std::size_t>(p);
  std::array<Eigen::Vector3d, 4> d;
  for (std::size_t j = 0; j <= q; ++j) d[j] = points[k - q + j];
  for (std::size_t r = 1; r <= q; ++r) {
    for (std::size_t j = q; j >= r; --j) {
      const std::size_t i = k - q + j;
      const double den = knots[i + q + 1 - r] - knots[i];
      const double a = den > 0.0 ? (u[r - 1] - knots[i]) / den : 0.0;
      d[j] = (1.0 - a) * d[j - 1] + a * d[j];
    }
  }
  return d[q];
}

// The cubic Bézier control points (homogeneous) of span k = [a, b] of a NURBS
// of degree 1..3: F(a, a, a), F(a, a, b), F(a, b, b), F(b, b, b) of the cubic
// blossom F(x, y, z), the mean of f over the p-element subsets of (x, y, z)
// (the degree raised exactly), each a convex combination of control points.
std::array<Eigen::Vector3d, 4> rational_span_bezier(const std::vector<double>& knots,
                                                    const std::vector<Eigen::Vector3d>& points, int p,
                                                    std::size_t k) {
  const double a = knots[k], b = knots[k + 1];
  std::array<Eigen::Vector3d, 4> out;
  for (std::size_t i = 0; i < 4; ++i) {
    const std::array<double, 3> args{i > 2 ? b : a, i > 1 ? b : a, i > 0 ? b : a};  // 3 - i a's, i b's
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (unsigned mask = 0; mask < 8; ++mask) {
      std::array<double, 3> u{};
      int size = 0;
      for (std::size_t m = 0; m < 3; ++m) {
        if ((mask >> m) & 1u) u[static_cast<std::size_t>(size++)] = args[m];
      }
      if (size != p) continue;
      sum += blossom(knots, points, p, k, u);
      ++count;
    }
    out[i] = sum / count;
  }
  return out;
}

// The cubic Bézier spans of a B-spline of degree 1..3 over its domain
// [knots[p], knots[n]], one per span of positive length (linear time in the
// number of spans whatever their count). A span whose p + 1 control points
// weigh the same is a polynomial: its Bézier comes from the plane points. A
// rational span's comes from the homogeneous points (w x, w y, w), exactly,
// by blossoming: its poles are the homogeneous Bézier points divided by their
// w, its weights the w.
std::vector<BezierSpan> bezier_pieces(const std::vector<double>& knots, const std::vector<Vec2>& points,
                                      const std::vector<double>& weights, int p) {
  std::vector<BezierSpan> out;
  const std::size_t n = points.size(), q = static_cast<std::size_t>(p);
  std::vector<Eigen::Vector3d> homogeneous;
  for (std::size_t k = q; k < n; ++k) {
    if (!(knots[k + 1] > knots[k])) continue;
    BezierSpan span;
    const auto first = weights.begin() + static_cast<std::ptrdiff_t>(k - q);
    const auto last = weights.begin() + static_cast<std::ptrdiff_t>(k + 1);
    if (std::all_of(first, last, [&](double w) { return w == *first; })) {
      span.points = span_bezier(knots, points, p, k);
      out.push_back(span);
      continue;
    }
    if (homogeneous.empty()) {
      for (std::size_t i = 0; i < n; ++i)
        homogeneous.emplace_back(weights[i] * points[i].x(), weights[i] * points[i].y(), weights[i]);
    }
    const std::array<Eigen::Vector3d, 4> h = rational_span_bezier(knots, homogeneous, p, k);
    span.rational = true;
    for (std::size_t i = 0; i < 4; ++i) {
      span.weights[i] = h[i].z();
      span.points[i] = h[i].head<2>() / h[i].z();
    }
    out.push_back(span);
  }
  return out;
}

// The control points of the uniform cubic B-spline span (a quasi-cubic span
// with both local parameters 0) that is the cubic Bézier curve z exactly.
std::array<Vec2, 4> bspline_span_of(const std::array<Vec2, 4>& z) {
  return {6.0 * z[0] - 7.0 * z[1] + 2.0 * z[2], 2.0 * z[1] - z[2], -z[1] + 2.0 * z[2],
          2.0 * z[1] - 7.0 * z[2] + 6.0 * z[3]};
}

// Start and end of an exact arc, as the segment evaluates them.
void arc_ends(Piece& piece) {
  const Segment s = Segment::ellipse_arc(piece.ellipse);
  piece.start = s.point(0.0);
  piece.end = s.point(1.0);
}

// Collects the entities of the wanted layer in model space. A problem found
// while dxflib reads is kept and thrown once it has returned.
class Collector : public DL_CreationAdapter {
 public:
  explicit Collector(std::string layer) : layer_(std::move(layer)) {}

  std::vector<Piece> pieces;
  std::vector<Polyline> polylines;
  std::vector<SplineData> splines;
  std::optional<int> insunits;
  std::map<std::string, std::size_t> left_out;  // entity type -> count, on the wanted layer
  std::set<std::string> layers;                 // layers with loop entities in model space
  std::size_t paper_space = 0;                  // loop entities on the wanted layer in paper space
  std::string problem;

  using DL_CreationAdapter::setVariableInt;
  void setVariableInt(const std::string& key, int value, int /*code*/) override {
    if (key == "$INSUNITS") insunits = value;
  }
  void addBlock(const DL_BlockData& /*data*/) override { ++in_block_; }
  void endBlock() override { in_block_ = std::max(0, in_block_ - 1); }

  void addLine(const DL_LineData& d) override {
    if (!wanted()) return;
    Piece p;
    p.start = Vec2(d.x1, d.y1);  // LINE is in world coordinates
    p.end = Vec2(d.x2, d.y2);
    p.entity = name("LINE");
    add(std::move(p));
  }
  void addArc(const DL_ArcData& d) override {
    if (!wanted() || !in_plane("ARC")) return;
    double sweep = d.angle2 - d.angle1;
    sweep = std::fmod(sweep, 360.0);
    if (sweep <= 0.0) sweep += 360.0;
    const double from = std::fmod(d.angle1, 360.0);
    add_circle_arc("ARC", Vec2(d.cx, d.cy), d.radius, from, sweep, false);
  }
  void addCircle(const DL_CircleData& d) override {
    if (!wanted() || !in_plane("CIRCLE")) return;
    add_circle_arc("CIRCLE", Vec2(d.cx, d.cy), d.radius, 0.0, 360.0, true);
  }
  void addEllipse(const DL_EllipseData& d) override {
    if (!wanted() || !in_plane("ELLIPSE")) return;
    // Centre and major axis are in world coordinates; a mirrored extrusion
    // turns the minor axis, so the parameter runs clockwise.
    const double a = std::hypot(d.mx, d.my);
    double sweep = std::fmod(d.angle2 - d.angle1, 2.0 * kPi);
    if (sweep <= 0.0) sweep += 2.0 * kPi;
    const bool whole = std::abs(d.angle2 - d.angle1 - 2.0 * kPi) < 1e-12 || sweep >= 2.0 * kPi;
    if (whole) sweep = 2.0 * kPi;
    const double from = std::fmod(d.angle1, 2.0 * kPi) * kDegree;
    const double sign = mirrored() ? -1.0 : 1.0;
    Piece p;
    p.arc = true;
    p.entity = name("ELLIPSE");
    p.closed = whole;
    p.ellipse.center = Vec2(d.cx, d.cy);
    p.ellipse.a = a;
    p.ellipse.b = a * d.ratio;
    p.ellipse.rotation_deg = std::atan2(d.my, d.mx) * kDegree;
    p.ellipse.from_deg = sign * from;
    p.ellipse.to_deg = sign * (from + sweep * kDegree);
    if (!finite_arc(p) || !(a > 0.0) || !(d.ratio > 0.0)) return fail_at(p.entity, "a degenerate ellipse");
    add(std::move(p));
  }
  void addPolyline(const DL_PolylineData& d) override {
    polyline_ = std::nullopt;
    if (!wanted() || !in_plane("LWPOLYLINE")) return;
    if ((d.flags & (16 | 64)) != 0)
      return fail_at(name("POLYLINE"), "a polygon mesh or polyface, not a curve");
    Polyline pl;
    pl.entity = name("LWPOLYLINE");
    pl.closed = (d.flags & 1) != 0;
    pl.mirrored = mirrored();
    pl.order = index_;
    polylines.push_back(std::move(pl));
    polyline_ = polylines.size() - 1;
  }
  void addVertex(const DL_VertexData& d) override {
    if (!polyline_) return;
    if (++count_ > kMaxDxfEntities) return too_many();
    polylines[*polyline_].vertices.push_back({d.x, d.y, d.bulge});
  }
  void endSequence() override { polyline_ = std::nullopt; }

  // A SPLINE: its knots and control points follow at once (addKnot, addControlPoint).
  void addSpline(const DL_SplineData& d) override {
    spline_ = false;
    if (!wanted()) return;
    SplineData sp;
    sp.entity = name("SPLINE");
    sp.order = index_;
    sp.degree = static_cast<int>(d.degree);
    sp.closed = (d.flags & 1) != 0;
    sp.fit_points = d.nFit;
    splines.push_back(std::move(sp));
    spline_ = true;
  }
  void addKnot(const DL_KnotData& d) override {
    if (!spline_) return;
    if (++count_ > kMaxDxfEntities) return too_many();
    splines.back().knots.push_back(d.k);
  }
  void addControlPoint(const DL_ControlPointData& d) override {
    if (!spline_) return;
    if (++count_ > kMaxDxfEntities) return too_many();
    splines.back().control.push_back({d.x, d.y, d.z, d.w});
  }
  void addFitPoint(const DL_FitPointData& /*d*/) override {}

  // Entities a loop cannot be made of: refused on the wanted layer.
  void addInsert(const DL_InsertData& /*data*/) override {
    if (wanted())
      fail_at(name("INSERT"),
              "a block reference on the layer: explode it so its lines and arcs are in the layer");
  }
  // Entities that carry no outline: left out, and said so.
  void addPoint(const DL_PointData& /*data*/) override { leave_out("POINT"); }
  void addText(const DL_TextData& /*data*/) override { leave_out("TEXT"); }
  void addMText(const DL_MTextData& /*data*/) override { leave_out("MTEXT"); }
  void addHatch(const DL_HatchData& /*data*/) override { leave_out("HATCH"); }
  void addSolid(const DL_SolidData& /*data*/) override { leave_out("SOLID"); }
  void addXLine(const DL_XLineData& /*data*/) override { leave_out("XLINE"); }
  void addRay(const DL_RayData& /*data*/) override { leave_out("RAY"); }
  void addLeader(const DL_LeaderData& /*data*/) override { leave_out("LEADER"); }
  void addDimLinear(const DL_DimensionData& /*d*/, const DL_DimLinearData& /*l*/) override {
    leave_out("DIMENSION");
  }
  void addDimAlign(const DL_DimensionData& /*d*/, const DL_DimAlignedData& /*a*/) override {
    leave_out("DIMENSION");
  }
  void addDimRadial(const DL_DimensionData& /*d*/, const DL_DimRadialData& /*r*/) override {
    leave_out("DIMENSION");
  }
  void addDimDiametric(const DL_DimensionData& /*d*/, const DL_DimDiametricData& /*r*/) override {
    leave_out("DIMENSION");
  }

 private:
  // An entity of a loop kind: on the wanted layer, in model space, outside block definitions.
  bool wanted() {
    if (!problem.empty() || in_block_ > 0) return false;
    const DL_Attributes& at = getAttributes();
    const bool on_layer = layer_.empty() || at.getLayer() == layer_;
    if (at.isInPaperSpace()) {
      if (on_layer) ++paper_space;
      return false;
    }
    if (layers.size() < 64) layers.insert(at.getLayer());
    if (!on_layer) return false;
    if (++count_ > kMaxDxfEntities) {
      too_many();
      return false;
    }
    return true;
  }
  void leave_out(const char* type) {
    if (problem.empty() && in_block_ == 0 && !getAttributes().isInPaperSpace() &&
        (layer_.empty() || getAttributes().getLayer() == layer_))
      ++left_out[type];
  }
  std::string name(const char* type) {
    spline_ = false;
    const int handle = getAttributes().getHandle();
    ++index_;
    return handle >= 0 ? fmt::format("{} #{:X}", type, handle) : fmt::format("{} (entity {})", type, index_);
  }
  bool mirrored() { return getExtrusion()->getDirection()[2] < 0.0; }
  // Arcs, circles and polylines are in the entity's own coordinates: only
  // those of the drawing's plane (extrusion +-Z) are read.
  bool in_plane(const char* type) {
    const double* dir = getExtrusion()->getDirection();
    if (std::abs(dir[0]) > 1e-9 || std::abs(dir[1]) > 1e-9 || !(std::abs(dir[2]) > 0.0)) {
      fail_at(name(type), fmt::format("its plane (extrusion ({}, {}, {})) is not the drawing's XY plane",
                                      dir[0], dir[1], dir[2]));
      return false;
    }
    return true;
  }
  static bool finite_arc(const Piece& p) {
    const EllipseArcParams& e = p.ellipse;
    return std::isfinite(e.center.x()) && std::isfinite(e.center.y()) && std::isfinite(e.a) &&
           std::isfinite(e.b) && std::isfinite(e.from_deg) && std::isfinite(e.to_deg);
  }
  void add_circle_arc(const char* type, Vec2 center, double radius, double from_deg, double sweep_deg,
                      bool whole) {
    Piece p;
    p.arc = true;
    p.entity = name(type);
    p.closed = whole;
    if (mirrored()) {
      // x -> -x: the arc runs clockwise from the mirrored start angle.
      center.x() = -center.x();
      from_deg = 180.0 - from_deg;
      sweep_deg = -sweep_deg;
    }
    p.ellipse.center = center;
    p.ellipse.a = p.ellipse.b = radius;
    p.ellipse.from_deg = from_deg;
    p.ellipse.to_deg = from_deg + sweep_deg;
    if (!finite_arc(p) || !(radius > 0.0))
      return fail_at(p.entity, fmt::format("radius {} is not > 0", radius));
    add(std::move(p));
  }
  void add(Piece p) {
    p.order = index_;
    pieces.push_back(std::move(p));
  }
  void fail_at(const std::string& entity, const std::string& why) {
    if (problem.empty()) problem = fmt::format("{}: {}", entity, why);
  }
  void too_many() {
    if (problem.empty())
      problem = fmt::format("more than {} entities and polyline vertices: not a template fabmesh reads",
                            kMaxDxfEntities);
  }

  std::string layer_;
  int in_block_ = 0;
  std::size_t count_ = 0;
  std::size_t index_ = 0;
  std::optional<std::size_t> polyline_;
  bool spline_ = false;  // knots and control points go to splines.back()
};

// A spline as a loop piece: exact cubic pieces (rational where the SPLINE
// is a NURBS) of a SPLINE of degree 1 to 3 in the XY plane with positive
// weights. Sets `problem` for any other.
std::optional<Piece> spline_piece(const SplineData& sp, std::string& problem) {
  auto fail = [&](const std::string& why) -> std::optional<Piece> {
    if (problem.empty()) problem = fmt::format("{}: {}", sp.entity, why);
    return std::nullopt;
  };
  if (sp.control.empty()) {
    return fail(sp.fit_points > 0 ? "a SPLINE given by fit points only; save it with its control points"
                                  : "a SPLINE without control points");
  }
  if (sp.degree < 1 || sp.degree > 3)
    return fail(fmt::format("degree {}; fabmesh reads splines of degree 1, 2 or 3", sp.degree));
  const std::size_t n = sp.control.size(), p = static_cast<std::size_t>(sp.degree);
  if (n < p + 1) return fail(fmt::format("{} control points for degree {}", n, p));
  if (sp.knots.size() != n + p + 1)
    return fail(
        fmt::format("{} knots; {} control points of degree {} take {}", sp.knots.size(), n, p, n + p + 1));
  for (std::size_t i = 0; i < sp.knots.size(); ++i) {
    if (!std::isfinite(sp.knots[i]) || (i > 0 && sp.knots[i] < sp.knots[i - 1]))
      return fail(fmt::format("knot {} ({}) is not finite and non-decreasing", i + 1, sp.knots[i]));
  }
  std::vector<Vec2> points;
  std::vector<double> weights;
  const double z0 = sp.control.front()[2];
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = sp.control[i];
    if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
      return fail(fmt::format("control point {} is not finite", i + 1));
    if (!(std::isfinite(c[3]) && c[3] > 0.0)) {
      return fail(
          fmt::format("control point {} has weight {}: a NURBS weight must be finite and > 0", i + 1, c[3]));
    }
    if (std::abs(c[2] - z0) > 1e-9 * (1.0 + std::abs(z0)))
      return fail(fmt::format("control point {} is at z = {}, off the drawing's XY plane", i + 1, c[2]));
    points.emplace_back(c[0], c[1]);
    weights.push_back(c[3]);
  }
  if (!(sp.knots[n] > sp.knots[p])) return fail("its knots leave no domain to draw");
  Piece piece;
  piece.spline = true;
  piece.entity = sp.entity;
  piece.order = sp.order;
  piece.beziers = bezier_pieces(sp.knots, points, weights, sp.degree);
  if (piece.beziers.empty()) return fail("its knots leave no domain to draw");
  piece.start = piece.beziers.front().points[0];
  piece.end = piece.beziers.back().points[3];
  return piece;
}

// The text as group code / value pairs: that it is a DXF at all, and that no
// count in it (vertices, knots) announces more than the file could hold,
// which would make dxflib allocate for it.
void check_dxf_text(const std::string& bytes, const std::string& path) {
  if (bytes.empty())
    throw FileError(path, 0, 0, fmt::format("{}: the file is empty, not a DXF drawing", path));
  if (bytes.rfind("AutoCAD Binary DXF", 0) == 0) {
    throw FileError(
        path, 0, 0,
        fmt::format("{}: a binary DXF; fabmesh reads ASCII DXF (save the drawing as ASCII DXF)", path));
  }
  std::size_t lines = static_cast<std::size_t>(std::count(bytes.begin(), bytes.end(), '\n')) + 1;
  std::size_t pos = 0, line = 0;
  auto next_line = [&]() -> std::string_view {
    const std::size_t nl = bytes.find('\n', pos);
    std::string_view s(bytes.data() + pos, (nl == std::string::npos ? bytes.size() : nl) - pos);
    pos = nl == std::string::npos ? bytes.size() : nl + 1;
    ++line;
    while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    return s;
  };
  bool first = true;
  std::string_view entity;  // the entity (or table entry) the pairs belong to
  while (pos < bytes.size()) {
    const std::size_t code_line = line + 1;
    const std::string_view code_text = next_line();
    if (code_text.empty() && pos >= bytes.size()) break;
    int code = 0;
    const auto [end, ec] = std::from_chars(code_text.data(), code_text.data() + code_text.size(), code);
    if (ec != std::errc() || end != code_text.data() + code_text.size()) {
      throw FileError(
          path, static_cast<int>(code_line), 1,
          fmt::format("{}:{}: '{}' is not a DXF group code{}", path, code_line,
                      std::string(code_text.substr(0, 40)), first ? ": the file is not a DXF drawing" : ""));
    }
    const std::string_view value = next_line();
    if (first && code != 999 && !(code == 0 && value == "SECTION")) {
      throw FileError(path, static_cast<int>(code_line), 1,
                      fmt::format("{}: the file does not start with a DXF SECTION: not a DXF drawing", path));
    }
    first = false;
    // The counts dxflib allocates for before it reads the entries: an
    // LWPOLYLINE's vertices, a SPLINE's knots, control and fit points.
    if (code == 0) entity = value;
    if ((entity == "LWPOLYLINE" && code == 90) ||
        (entity == "SPLINE" && (code == 72 || code == 73 || code == 74))) {
      long long count = 0;
      const auto [vend, vec] = std::from_chars(value.data(), value.data() + value.size(), count);
      if (vec == std::errc() && vend == value.data() + value.size() &&
          count > static_cast<long long>(lines)) {
        throw FileError(path, static_cast<int>(line), 1,
                        fmt::format("{}:{}: {} group {} announces {} entries; the file has {} lines", path,
                                    line, std::string(entity), code, count, lines));
      }
    }
  }
}

// Ends of the open pieces, matched within `join`: each must meet exactly one other.
struct End {
  std::size_t piece = 0;
  bool at_end = false;  // false: the piece's start
  Vec2 p{0.0, 0.0};
};

std::string end_name(const End& e, const std::vector<Piece>& pieces) {
  return fmt::format("{}'s {}", pieces[e.piece].entity, e.at_end ? "end" : "start");
}

// The partner of every end (index into `ends`).
std::vector<std::size_t> match_ends(const std::vector<End>& ends, const std::vector<Piece>& pieces,
                                    double join, double cell, const std::string& where, double max_gap) {
  auto key = [cell](const Vec2& p) {
    return std::pair<std::int64_t, std::int64_t>(static_cast<std::int64_t>(std::floor(p.x() / cell)),
                                                 static_cast<std::int64_t>(std::floor(p.y() / cell)));
  };
  struct PairHash {
    std::size_t operator()(const std::pair<std::int64_t, std::int64_t>& k) const {
      const auto a = static_cast<std::uint64_t>(k.first);
      const auto b = static_cast<std::uint64_t>(k.second);
      return std::hash<std::uint64_t>()(a * 0x9E3779B97F4A7C15ULL ^ b);
    }
  };
  std::unordered_map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>, PairHash> grid;
  for (std::size_t i = 0; i < ends.size(); ++i) grid[key(ends[i].p)].push_back(i);
  std::vector<std::size_t> partner(ends.size());
  for (std::size_t i = 0; i < ends.size(); ++i) {
    const auto [kx, ky] = key(ends[i].p);
    std::vector<std::size_t> near;
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = grid.find({kx + dx, ky + dy});
        if (it == grid.end()) continue;
        for (const std::size_t j : it->second) {
          if (j != i && (ends[j].p - ends[i].p).norm() <= join) near.push_back(j);
        }
      }
    }
    if (near.empty()) {
      // The nearest end, to say how far the gap is.
      std::optional<std::size_t> nearest;
      for (std::size_t j = 0; j < ends.size(); ++j) {
        if (j != i && (!nearest || (ends[j].p - ends[i].p).norm() < (ends[*nearest].p - ends[i].p).norm()))
          nearest = j;
      }
      throw InputError(fmt::format(
          "{}: open chain: {} at {} meets no other end within max_gap {:.6g}{}", where,
          end_name(ends[i], pieces), fmt_point(ends[i].p), max_gap,
          nearest ? fmt::format(" (the nearest, {}, is {:.6g} away)", end_name(ends[*nearest], pieces),
                                (ends[*nearest].p - ends[i].p).norm())
                  : std::string()));
    }
    if (near.size() > 1) {
      std::string names = end_name(ends[i], pieces);
      for (const std::size_t j : near) names += ", " + end_name(ends[j], pieces);
      throw InputError(fmt::format(
          "{}: {} ends meet at {}: {}; entities overlap or branch there (a loop passes a point once)", where,
          near.size() + 1, fmt_point(ends[i].p), names));
    }
    partner[i] = near.front();
  }
  return partner;
}

// A piece as a loop runs through it.
Piece oriented(const Piece& p, bool forward) {
  if (forward) return p;
  Piece r = p;
  std::swap(r.start, r.end);
  std::swap(r.ellipse.from_deg, r.ellipse.to_deg);
  std::reverse(r.beziers.begin(), r.beziers.end());
  for (BezierSpan& z : r.beziers) {
    std::reverse(z.points.begin(), z.points.end());
    std::reverse(z.weights.begin(), z.weights.end());
  }
  return r;
}

// Arcs and splines end exactly where they end; lines follow them.
bool exact(const Piece& p) { return p.arc || p.spline; }

SegmentSpec line_to(const std::vector<Vec2>& points, const std::string& name) {
  SegmentSpec s;
  s.kind = SegmentKind::Line;
  s.points = points;
  s.declared = Continuity::G0;
  s.name = name;
  return s;
}

// The closed curve spec of a chain of oriented pieces: lines end exactly
// where the exact arcs they meet end; two arcs whose ends differ by more than
// the joints' check allows get a short line between them.
CurveSpec loop_spec(const std::vector<Piece>& q, double bridge, std::size_t& bridges) {
  const std::size_t n = q.size();
  auto joint = [&](std::size_t k) -> Vec2 {  // where q[k] meets q[k + 1]
    const Piece& a = q[k];
    const Piece& b = q[(k + 1) % n];
    if (exact(a)) return a.end;
    if (exact(b)) return b.start;
    return a.end;
  };
  CurveSpec spec;
  spec.closed = true;
  spec.closing_declared = Continuity::G0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 from = joint((k + n - 1) % n);
    const Piece& p = q[k];
    if (!exact(p)) {
      spec.segments.push_back(line_to(
          spec.segments.empty() ? std::vector<Vec2>{from, joint(k)} : std::vector<Vec2>{joint(k)}, p.entity));
      continue;
    }
    if (k > 0 && exact(q[k - 1]) && (q[k - 1].end - p.start).norm() > bridge) {
      spec.segments.push_back(
          line_to({p.start}, fmt::format("gap between {} and {}", q[k - 1].entity, p.entity)));
      ++bridges;
    }
    if (p.spline) {
      // Each polynomial cubic piece as the uniform B-spline span that is the
      // same curve; each rational one as the rational cubic Bézier it is.
      for (std::size_t i = 0; i < p.beziers.size(); ++i) {
        const BezierSpan& z = p.beziers[i];
        SegmentSpec s;
        if (z.rational) {
          s.kind = SegmentKind::RationalBezier;
          s.points.assign(z.points.begin(), z.points.end());
          s.weights = z.weights;
        } else {
          s.kind = SegmentKind::QuasiBSpline;
          const std::array<Vec2, 4> b = bspline_span_of(z.points);
          s.points.assign(b.begin(), b.end());
        }
        s.declared = Continuity::G0;
        s.name = p.beziers.size() == 1 ? p.entity : fmt::format("{} piece {}", p.entity, i + 1);
        spec.segments.push_back(std::move(s));
      }
      continue;
    }
    SegmentSpec s;
    s.kind = SegmentKind::EllipseArc;
    s.ellipse = p.ellipse;
    s.declared = Continuity::G0;
    s.name = p.entity;
    spec.segments.push_back(s);
  }
  if ((n > 1 || q.front().spline) && exact(q.back()) && exact(q.front()) &&
      (q.back().end - q.front().start).norm() > bridge) {
    spec.segments.push_back(
        line_to({q.front().start}, fmt::format("gap between {} and {}", q.back().entity, q.front().entity)));
    ++bridges;
  }
  return spec;
}

// Angles into the ranges an ellipse arc takes ([-720, 720] degrees).
void normalise_angles(EllipseArcParams& e) {
  const double shift = 360.0 * std::floor(std::min(e.from_deg, e.to_deg) / 360.0);
  e.from_deg -= shift;
  e.to_deg -= shift;
  e.rotation_deg = std::fmod(e.rotation_deg, 360.0);
}

}  // namespace

DxfLoops parse_dxf_loops(const std::string& bytes, const std::string& path, const DxfLoopQuery& query) {
  check_dxf_text(bytes, path);
  const std::string where = query.layer.empty() ? path : fmt::format("{} layer {}", path, query.layer);
  Collector c(query.layer);
  {
    DL_Dxf dxf;
    std::istringstream in(bytes);
    if (!dxf.in(in, &c)) throw FileError(path, 0, 0, fmt::format("{}: dxflib cannot read the drawing", path));
  }
  if (!c.problem.empty()) throw FileError(path, 0, 0, fmt::format("{}: {}", where, c.problem));

  DxfLoops out;
  // Units: the drawing's, scaled into the design's.
  const double design_metres = metres_per_unit(query.units);
  double scale = 1.0;
  if (!c.insunits || *c.insunits == 0) {
    out.notes.push_back(fmt::format("{} gives no units ($INSUNITS {}): read in the design's units ({})", path,
                                    c.insunits ? "0, unitless" : "missing", query.units));
  } else {
    const DxfUnit* unit = nullptr;
    for (const DxfUnit& u : kDxfUnits) {
      if (u.code == *c.insunits) unit = &u;
    }
    if (unit == nullptr) {
      throw FileError(
          path, 0, 0,
          fmt::format("{}: $INSUNITS {} is not a unit fabmesh reads (1 in, 2 ft, 4 mm, 5 cm, 6 m)", path,
                      *c.insunits));
    }
    scale = unit->metres / design_metres;
    out.notes.push_back(scale == 1.0 ? fmt::format("{}: $INSUNITS {} ({})", path, unit->code, unit->name)
                                     : fmt::format("{}: $INSUNITS {} ({}), scaled by {:.12g} into {}", path,
                                                   unit->code, unit->name, scale, query.units));
  }
  if (!c.left_out.empty()) {
    std::string kinds;
    for (const auto& [type, count] : c.left_out)
      kinds += fmt::format("{}{} {}", kinds.empty() ? "" : ", ", count, type);
    out.notes.push_back(fmt::format("{}: left out {} (no outline in them)", where, kinds));
  }

  // Splines into pieces of exact cubic spans.
  std::vector<Piece>& pieces = c.pieces;
  for (const SplineData& sp : c.splines) {
    std::string problem;
    std::optional<Piece> piece = spline_piece(sp, problem);
    if (!piece) throw FileError(path, 0, 0, fmt::format("{}: {}", where, problem));
    pieces.push_back(std::move(*piece));
  }
  // Polylines into pieces: straight spans and exact bulge arcs.
  for (const Polyline& pl : c.polylines) {
    const std::size_t n = pl.vertices.size();
    const std::size_t spans = pl.closed ? n : (n == 0 ? 0 : n - 1);
    for (std::size_t i = 0; i < spans; ++i) {
      const auto& v = pl.vertices[i];
      const auto& w = pl.vertices[(i + 1) % n];
      const double sx = pl.mirrored ? -1.0 : 1.0;
      const Vec2 a(sx * v[0], v[1]), b(sx * w[0], w[1]);
      const double bulge = pl.mirrored ? -v[2] : v[2];
      Piece p;
      p.entity = fmt::format("{} vertex {}", pl.entity, i + 1);
      p.order = pl.order;
      p.start = a;
      p.end = b;
      const double chord = (b - a).norm();
      if (bulge != 0.0 && std::isfinite(bulge) && chord > 0.0) {
        const double theta = 4.0 * std::atan(bulge);
        const Vec2 left(-(b - a).y() / chord, (b - a).x() / chord);
        const Vec2 centre = 0.5 * (a + b) + left * (0.5 * chord / std::tan(0.5 * theta));
        p.arc = true;
        p.ellipse.center = centre;
        p.ellipse.a = p.ellipse.b = 0.5 * chord / std::sin(0.5 * std::abs(theta));
        p.ellipse.from_deg = std::atan2(a.y() - centre.y(), a.x() - centre.x()) * kDegree;
        p.ellipse.to_deg = p.ellipse.from_deg + theta * kDegree;
      } else if (!std::isfinite(bulge)) {
        throw FileError(path, 0, 0, fmt::format("{}: {}: bulge {} is not a number", where, p.entity, bulge));
      }
      pieces.push_back(std::move(p));
    }
  }
  if (pieces.empty()) {
    std::string layers;
    for (const std::string& l : c.layers) layers += (layers.empty() ? "" : ", ") + l;
    if (c.paper_space > 0) {
      throw FileError(
          path, 0, 0,
          fmt::format("{}: the layer's {} entities are all in paper space; the outline must be in "
                      "model space",
                      where, c.paper_space));
    }
    throw FileError(
        path, 0, 0,
        fmt::format("{}: no LINE, ARC, CIRCLE, ELLIPSE, polyline or SPLINE in model space{}", where,
                    layers.empty() ? std::string(" (the drawing has none on any layer)")
                                   : fmt::format(" (layers that have them: {})", layers)));
  }

  // Into the design's units; every number within the design's limits.
  double extent = 0.0;
  for (Piece& p : pieces) {
    p.start *= scale;
    p.end *= scale;
    if (p.arc) {
      p.ellipse.center *= scale;
      p.ellipse.a *= scale;
      p.ellipse.b *= scale;
      normalise_angles(p.ellipse);
    }
    for (BezierSpan& z : p.beziers) {
      for (Vec2& v : z.points) {
        v *= scale;
        if (!v.allFinite() || std::abs(v.x()) > kMaxDesignNumber || std::abs(v.y()) > kMaxDesignNumber) {
          throw FileError(path, 0, 0,
                          fmt::format("{}: {}: a control point {} is beyond the design limit {:g}", where,
                                      p.entity, fmt_point(v), kMaxDesignNumber));
        }
        extent = std::max({extent, std::abs(v.x()), std::abs(v.y())});
      }
    }
    for (const double v : {p.start.x(), p.start.y(), p.end.x(), p.end.y(), p.ellipse.center.x(),
                           p.ellipse.center.y(), p.ellipse.a, p.ellipse.b}) {
      if (!std::isfinite(v) || std::abs(v) > kMaxDesignNumber) {
        throw FileError(path, 0, 0,
                        fmt::format("{}: {}: the value {} is beyond the design limit {:g}", where, p.entity,
                                    v, kMaxDesignNumber));
      }
    }
    try {
      if (p.arc) arc_ends(p);
    } catch (const InputError& e) {
      throw FileError(path, 0, 0, fmt::format("{}: {}: {}", where, p.entity, e.what()));
    }
    extent = std::max({extent, std::abs(p.start.x()), std::abs(p.start.y()), std::abs(p.end.x()),
                       std::abs(p.end.y()), p.arc ? p.ellipse.a + p.ellipse.center.norm() : 0.0});
  }
  if (extent == 0.0) extent = 1.0;
  const double join = std::max(query.max_gap, 1e-12 * extent);
  const double bridge = 1e-10 * extent;  // below the joints' own check (1e-9 of the curve's extent)
  for (Piece& p : pieces) {
    if (p.spline && (p.end - p.start).norm() <= join) p.closed = true;  // a closed spline: a loop by itself
  }

  // Whole circles and ellipses are loops by themselves; the rest is chained.
  std::vector<std::vector<Piece>> chains;
  std::vector<std::size_t> chain_first;  // file order of each chain's first piece
  std::vector<std::size_t> open;
  std::size_t skipped = 0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (pieces[i].closed) {
      chains.push_back({pieces[i]});
      chain_first.push_back(i);
    } else if (!pieces[i].arc && (pieces[i].end - pieces[i].start).norm() <= join) {
      ++skipped;  // a line no longer than the gap joined across: a point
    } else {
      open.push_back(i);
    }
  }
  if (skipped > 0)
    out.notes.push_back(fmt::format("{}: left out {} line(s) no longer than max_gap", where, skipped));
  std::vector<End> ends;
  ends.reserve(2 * open.size());
  for (const std::size_t i : open) {
    ends.push_back({i, false, pieces[i].start});
    ends.push_back({i, true, pieces[i].end});
  }
  const double cell = std::max(join, 1e-9 * extent);
  std::vector<std::size_t> partner;
  try {
    partner = match_ends(ends, pieces, join, cell, where, query.max_gap);
  } catch (const InputError& e) {
    throw FileError(path, 0, 0, e.what());
  }
  // Walk: ends 2k and 2k + 1 are open[k]'s start and end.
  std::vector<bool> used(open.size(), false);
  for (std::size_t k = 0; k < open.size(); ++k) {
    if (used[k]) continue;
    std::vector<Piece> chain;
    std::size_t cur = k;
    bool forward = true;
    for (std::size_t steps = 0; steps <= open.size(); ++steps) {
      used[cur] = true;
      chain.push_back(oriented(pieces[open[cur]], forward));
      const std::size_t exit_end = 2 * cur + (forward ? 1 : 0);
      const std::size_t next_end = partner[exit_end];
      const std::size_t next = next_end / 2;
      const bool next_forward = next_end % 2 == 0;  // entered at its start
      if (next == k && next_forward) break;         // back where the loop began
      if (used[next]) {
        throw FileError(path, 0, 0,
                        fmt::format("{}: {} meets {} twice; the entities do not make a loop", where,
                                    pieces[open[cur]].entity, pieces[open[next]].entity));
      }
      cur = next;
      forward = next_forward;
    }
    chains.push_back(std::move(chain));
    chain_first.push_back(open[k]);
  }

  std::vector<std::size_t> order(chains.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return pieces[chain_first[a]].order < pieces[chain_first[b]].order;
  });
  std::size_t bridges = 0;
  for (const std::size_t i : order) {
    DxfLoop loop;
    loop.curve = loop_spec(chains[i], bridge, bridges);
    loop.first_entity = pieces[chain_first[i]].entity;
    out.loops.push_back(std::move(loop));
  }
  if (bridges > 0) {
    out.notes.push_back(
        fmt::format("{}: {} gap(s) between arcs, up to max_gap, joined by short lines", where, bridges));
  }
  return out;
}

DxfLoops read_dxf_loops(const std::string& path, const DxfLoopQuery& query) {
  return parse_dxf_loops(read_file(path, kMaxDxfBytes, "DXF drawing"), path, query);
}

}  // namespace fabmesh
