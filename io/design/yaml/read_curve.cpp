#include "io/design/yaml/read_curve.h"

#include <fmt/format.h>

#include <filesystem>

#include "geometry/core/error_checks.h"
#include "geometry/curves/quasi_bspline_through.h"
#include "io/design/points_csv.h"

namespace fabmesh {
namespace {

Continuity read_continuity(const yaml::Fields& f, const YAML::Node& node, const std::string& field) {
  const std::string c = f.choice(node, field, {"G0", "G1", "G2"});
  return c == "G0" ? Continuity::G0 : c == "G1" ? Continuity::G1 : Continuity::G2;
}

FairMode read_fair(const yaml::Fields& f, const YAML::Node& curve, const std::string& field) {
  const YAML::Node n = curve["fair"];
  if (!n.IsDefined()) return FairMode::None;
  const std::string v = f.choice(n, field + ".fair", {"none", "strain", "curvature_variation"});
  return v == "none" ? FairMode::None : v == "strain" ? FairMode::Strain : FairMode::CurvatureVariation;
}

JoinSpec read_join(const yaml::Fields& f, const YAML::Node& node, const std::string& field,
                   SegmentKind kind) {
  JoinSpec j;
  if (kind == SegmentKind::HBezier) {
    f.require_map(node, field, key_group("segment.join.hbezier"));
    j.k = f.number_or(node, "k", field + ".k", 1.0);
    j.m = f.number_or(node, "m", field + ".m", 0.0);
    if (j.k <= 0.0) f.fail(node["k"], field + ".k", fmt::format("k = {} must be > 0", j.k));
  } else {
    f.require_map(node, field, key_group("segment.join.tbezier"));
    j.alpha = f.number_or(node, "alpha", field + ".alpha", 1.0);
    j.beta = f.number_or(node, "beta", field + ".beta", 0.0);
    if (j.alpha <= 0.0)
      f.fail(node["alpha"], field + ".alpha", fmt::format("alpha = {} must be > 0", j.alpha));
  }
  j.continuity = read_continuity(f, f.required(node, "continuity", field), field + ".continuity");
  return j;
}

SegmentSpec read_ellipse_arc(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                             bool circle) {
  SegmentSpec s;
  s.kind = SegmentKind::EllipseArc;
  if (circle) {
    f.require_map(n, field, key_group("segment.circle_arc.circle_arc"));
    s.ellipse.a = s.ellipse.b = f.number(f.required(n, "radius", field), field + ".radius");
  } else {
    f.require_map(n, field, key_group("segment.ellipse_arc.ellipse_arc"));
    s.ellipse.a = f.number(f.required(n, "a", field), field + ".a");
    s.ellipse.b = f.number(f.required(n, "b", field), field + ".b");
    s.ellipse.rotation_deg = f.number_or(n, "rotation_deg", field + ".rotation_deg", 0.0);
  }
  s.ellipse.center = f.point2(f.required(n, "center", field), field + ".center");
  s.ellipse.from_deg = f.number_or(n, "from_deg", field + ".from_deg", 0.0);
  s.ellipse.to_deg = f.number_or(n, "to_deg", field + ".to_deg", 360.0);
  f.checked(n, field, [&] { Segment::ellipse_arc(s.ellipse); });
  return s;
}

// `edge: wall | exposed` of a countertop outline's segment.
bool read_edge(const yaml::Fields& f, const YAML::Node& n, const std::string& field) {
  if (!n["edge"].IsDefined()) return false;
  if (field.rfind("outline.", 0) != 0) {
    f.fail(n["edge"], field + ".edge",
           "edge (wall or exposed) belongs to the segments of a countertop's outline");
  }
  return f.choice(n["edge"], field + ".edge", {"wall", "exposed"}) == "wall";
}

SegmentSpec read_segment_shape(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                               CurveFamily family, bool first);

SegmentSpec read_segment(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                         CurveFamily family, bool first) {
  SegmentSpec s = read_segment_shape(f, n, field, family, first);
  s.wall = read_edge(f, n, field);
  return s;
}

SegmentSpec read_segment_shape(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                               CurveFamily family, bool first) {
  if (!n.IsMap()) f.fail(n, field, "expected a map describing a segment");
  SegmentSpec s;
  s.key = field;
  if (n["line"].IsDefined()) {
    f.require_map(n, field, key_group("segment.line"));
    const YAML::Node l = n["line"];
    f.require_map(l, field + ".line", key_group("segment.line.line"));
    s.kind = SegmentKind::Line;
    if (l["from"].IsDefined()) s.points.push_back(f.point2(l["from"], field + ".line.from"));
    s.points.push_back(f.point2(f.required(l, "to", field + ".line"), field + ".line.to"));
    if (first && s.points.size() != 2)
      f.fail(l, field + ".line", "the first segment's line needs 'from' and 'to'");
    if (!first && s.points.size() != 1) {
      f.fail(l["from"], field + ".line.from",
             "a line continues from the previous segment's end: give only 'to'");
    }
    if (n["continuity"].IsDefined()) s.declared = read_continuity(f, n["continuity"], field + ".continuity");
    return s;
  }
  for (const char* key : {"ellipse_arc", "circle_arc"}) {
    if (!n[key].IsDefined()) continue;
    f.require_map(n, field, key_group(std::string("segment.") + key));
    SegmentSpec e = read_ellipse_arc(f, n[key], field + "." + key, std::string(key) == "circle_arc");
    e.key = s.key;
    if (n["continuity"].IsDefined()) e.declared = read_continuity(f, n["continuity"], field + ".continuity");
    return e;
  }
  // A cubic of the curve's family (or of the family the segment names).
  f.require_map(n, field, key_group("segment.cubic"));
  s.kind = family == CurveFamily::HBezier ? SegmentKind::HBezier : SegmentKind::TBezier;
  if (n["family"].IsDefined()) {
    s.kind = f.choice(n["family"], field + ".family", {"tbezier", "hbezier"}) == "hbezier"
                 ? SegmentKind::HBezier
                 : SegmentKind::TBezier;
  }
  s.lambda = f.number_or(n, "lambda", field + ".lambda", 0.0);
  s.mu = f.number_or(n, "mu", field + ".mu", 0.0);
  if (s.kind == SegmentKind::HBezier) {
    s.alpha = f.number_or(n, "alpha", field + ".alpha", 1.0);
  } else if (n["alpha"].IsDefined()) {
    f.fail(n["alpha"], field + ".alpha",
           "a tbezier segment has no alpha (the join's alpha goes under 'join')");
  }
  // Range checks of the shape parameters, reported at the segment.
  const std::array<Vec2, 4> probe{Vec2(0, 0), Vec2(1, 0), Vec2(2, 0), Vec2(3, 0)};
  f.checked(n, field, [&] {
    if (s.kind == SegmentKind::HBezier) {
      Segment::hbezier(probe, s.alpha, s.lambda, s.mu);
    } else {
      Segment::tbezier(probe, s.lambda, s.mu);
    }
  });
  if (n["join"].IsDefined()) s.join = read_join(f, n["join"], field + ".join", s.kind);
  if (n["continuity"].IsDefined()) {
    if (s.join) f.fail(n["continuity"], field + ".continuity", "give the continuity under 'join'");
    s.declared = read_continuity(f, n["continuity"], field + ".continuity");
  }
  const std::size_t needed = s.join ? static_cast<std::size_t>(3 - static_cast<int>(s.join->continuity)) : 4;
  s.points = f.points2(f.required(n, "points", field), field + ".points");
  if (s.points.size() != needed) {
    f.fail(n["points"], field + ".points",
           s.join
               ? fmt::format("a {} join computes {} point(s); give the {} free point(s), got {}",
                             to_string(s.join->continuity), 4 - needed, needed, s.points.size())
               : fmt::format("an explicit segment needs 4 control points P0..P3, got {}", s.points.size()));
  }
  return s;
}

// `polyline: [p0, p1, ...]`: straight lines through the points, one segment
// each (a compact form for long digitised outlines). As the first segment it
// starts at p0; later it continues from the previous segment's end.
void read_polyline(const yaml::Fields& f, const YAML::Node& n, const std::string& field,
                   std::vector<SegmentSpec>& out) {
  f.require_map(n, field, key_group("segment.polyline"));
  const bool first = out.empty();
  const YAML::Node list = n["polyline"];
  const std::size_t needed = first ? 2 : 1;
  std::vector<Vec2> pts;
  if (list.IsMap()) {
    // polyline: {file: points.csv}, relative to the design file's folder.
    f.require_map(list, field + ".polyline", key_group("segment.polyline.file"));
    const YAML::Node file = f.required(list, "file", field + ".polyline");
    const std::filesystem::path name = f.text(file, field + ".polyline.file");
    const std::filesystem::path path =
        name.is_absolute() ? name : std::filesystem::path(f.path()).parent_path() / name;
    int header_line = 0;
    f.input(path.string());
    f.checked(file, field + ".polyline.file", [&] { pts = read_points_csv(path.string(), &header_line); });
    if (header_line > 0) {
      f.note(fmt::format("{}:{}: a header row (not numbers) was skipped, for {}", path.string(), header_line,
                         f.label(file, field + ".polyline.file")));
    }
    if (pts.size() < needed) {
      f.fail(file, field + ".polyline.file",
             fmt::format("{} holds {} point(s); this polyline needs at least {}", path.string(), pts.size(),
                         needed));
    }
  } else {
    pts = f.points2(list, field + ".polyline", needed);
  }
  for (std::size_t k = first ? 1 : 0; k < pts.size(); ++k) {
    SegmentSpec s;
    s.kind = SegmentKind::Line;
    s.key = field;
    s.name = fmt::format("{} (point {})", field, k);
    s.points = (first && k == 1) ? std::vector<Vec2>{pts[0], pts[1]} : std::vector<Vec2>{pts[k]};
    out.push_back(std::move(s));
  }
  if (n["continuity"].IsDefined())
    out[out.size() - pts.size() + (first ? 1 : 0)].declared =
        read_continuity(f, n["continuity"], field + ".continuity");
  const bool wall = read_edge(f, n, field);
  for (std::size_t k = out.size() - pts.size() + (first ? 1 : 0); k < out.size(); ++k) out[k].wall = wall;
}

}  // namespace

CurveSpec read_curve(const yaml::Fields& f, const YAML::Node& node, const std::string& field) {
  CurveSpec spec;
  spec.key = field;
  if (!node.IsMap()) f.fail(node, field, "expected a map describing a curve");
  const std::string family =
      f.choice(f.required(node, "family", field), field + ".family", {"tbezier", "hbezier", "quasi_bspline"});
  spec.fair = read_fair(f, node, field);
  if (family == "quasi_bspline") {
    f.require_map(node, field, key_group("curve.quasi_bspline"));
    spec.family = CurveFamily::QuasiBSpline;
    // Either the control points, or the points the curve passes through.
    const bool through = node["through"].IsDefined();
    if (through && node["points"].IsDefined()) {
      f.fail(node["through"], field + ".through",
             "give either points (the control points) or through (points on the curve), not both");
    }
    const std::string points_key = through ? "through" : "points";
    const YAML::Node pts = through ? node["through"] : f.required(node, "points", field);
    spec.bspline_points = f.points2(pts, field + "." + points_key);
    if (spec.bspline_points.size() < 3) {
      f.fail(pts, field + "." + points_key,
             fmt::format("a quasi-cubic B-spline needs at least 3 points {} (n >= 2), got {}",
                         through ? "q0..qn" : "p0..pn", spec.bspline_points.size()));
    }
    if (through && spec.fair != FairMode::None) {
      f.fail(node["fair"], field + ".fair",
             "fair keeps the control points and changes the lambdas, which moves the curve off its through "
             "points; fair a curve given by its control points (points:)");
    }
    const std::size_t n = spec.bspline_points.size() - 1;
    if (node["lambdas"].IsDefined()) {
      const YAML::Node l = node["lambdas"];
      f.require_list(l, field + ".lambdas");
      if (l.size() != n - 1) {
        f.fail(l, field + ".lambdas",
               fmt::format("expected n - 1 = {} values lambda_1..lambda_{} for {} points, got {}", n - 1,
                           n - 1, n + 1, l.size()));
      }
      for (std::size_t i = 0; i < l.size(); ++i) {
        const std::string name = fmt::format("{}.lambdas[{}]", field, i);
        const double v = f.number(l[i], name);
        f.checked(l[i], name, [&] { require_in_range(fmt::format("lambda_{}", i + 1), v, -8.0, 1.0); });
        spec.bspline_lambdas.push_back(v);
      }
    }
    if (through) {
      spec.bspline_through = spec.bspline_points;
      f.checked(pts, field + ".through", [&] {
        QuasiBSplineThrough solved = quasi_bspline_through(spec.bspline_through, spec.bspline_lambdas);
        spec.bspline_points = std::move(solved.points);
        spec.bspline_through_deviation = solved.deviation;
      });
    }
    return spec;
  }
  f.require_map(node, field, key_group("curve.composite"));
  spec.family = family == "hbezier" ? CurveFamily::HBezier : CurveFamily::TBezier;
  spec.closed = f.boolean_or(node, "closed", field + ".closed", false);
  if (node["closing"].IsDefined()) {
    const YAML::Node c = node["closing"];
    f.require_map(c, field + ".closing", key_group("curve.closing"));
    if (!spec.closed) f.fail(c, field + ".closing", "only a closed curve has a closing joint");
    spec.closing_declared =
        read_continuity(f, f.required(c, "continuity", field + ".closing"), field + ".closing.continuity");
  }
  const YAML::Node segs = f.required(node, "segments", field);
  f.require_list(segs, field + ".segments", 1);
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const std::string name = fmt::format("{}.segments[{}]", field, i);
    if (segs[i].IsMap() && segs[i]["polyline"].IsDefined()) {
      read_polyline(f, segs[i], name, spec.segments);
      continue;
    }
    spec.segments.push_back(read_segment(f, segs[i], name, spec.family, spec.segments.empty()));
  }
  if (spec.fair == FairMode::Strain) {
    f.fail(node["fair"], field + ".fair",
           "strain fairing applies to quasi_bspline curves; use curvature_variation");
  }
  if (spec.fair != FairMode::None && spec.family == CurveFamily::HBezier) {
    f.fail(node["fair"], field + ".fair", "fairing is defined for tbezier and quasi_bspline curves");
  }
  if (node["fair_keeps"].IsDefined()) {
    if (spec.fair == FairMode::None) {
      f.fail(node["fair_keeps"], field + ".fair_keeps",
             "fair_keeps says what continuity fairing may leave; it needs fair: curvature_variation");
    }
    spec.fair_keeps = read_continuity(f, node["fair_keeps"], field + ".fair_keeps");
  }
  return spec;
}

}  // namespace fabmesh
