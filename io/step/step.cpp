#include "io/step/step.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "geometry/core/errors.h"
#include "geometry/curves/bezier_form.h"
#include "io/module.h"

namespace fabmesh {
namespace {

// A missing module is an installation fault (MachineError, exit code 5),
// never a skipped output: the design asked for the file.
const StepModuleApi& api_or_throw() {
  return required_module<StepModuleApi>("fabmesh-step.so", "fabmesh_step_module", kStepModuleAbi, "step",
                                        "install fabmesh with its STEP module (OpenCASCADE)");
}

StepCurve conic_of(const EllipseArcParams& e) {
  StepCurve c;
  c.kind = StepCurve::Kind::Conic;
  const double rotation = e.rotation_deg * M_PI / 180.0;
  double from = e.from_deg * M_PI / 180.0, to = e.to_deg * M_PI / 180.0;
  c.conic.center = e.center;
  if (e.a >= e.b) {
    c.conic.major = e.a;
    c.conic.minor = e.b;
    c.conic.axis_angle = rotation;
  } else {
    // The major axis along the ellipse's y: its parameter is a quarter turn behind
    // (center + b cos(t - pi/2) Y - a sin(t - pi/2) X = center + a cos t X + b sin t Y).
    c.conic.major = e.b;
    c.conic.minor = e.a;
    c.conic.axis_angle = rotation + M_PI / 2.0;
    from -= M_PI / 2.0;
    to -= M_PI / 2.0;
  }
  c.conic.from = from;
  c.conic.to = to;
  return c;
}

StepCurve bezier_of(const BezierPiece& piece) {
  StepCurve c;
  c.kind = piece.poles.size() == 2 && piece.weights.empty() ? StepCurve::Kind::Line : StepCurve::Kind::Bezier;
  c.poles = piece.poles;
  c.weights = piece.weights;
  return c;
}

// Cubic Bézier pieces end to end as one B-spline: every interior knot of
// multiplicity 3, so each piece keeps its own poles (C1 by the Hermite construction).
StepCurve bspline_of(const std::vector<BezierPiece>& pieces) {
  StepCurve c;
  c.kind = StepCurve::Kind::BSpline;
  c.degree = 3;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& p = pieces[i].poles;
    c.poles.insert(c.poles.end(), p.begin() + (i == 0 ? 0 : 1), p.end());
    c.knots.push_back(static_cast<double>(i));
    c.multiplicities.push_back(i == 0 ? 4 : 3);
  }
  c.knots.push_back(static_cast<double>(pieces.size()));
  c.multiplicities.push_back(4);
  return c;
}

// The curve run the other way: poles (and weights) reversed, a conic's ends swapped.
StepCurve reversed(StepCurve c) {
  std::reverse(c.poles.begin(), c.poles.end());
  std::reverse(c.weights.begin(), c.weights.end());
  if (c.kind == StepCurve::Kind::BSpline) {
    const double end = c.knots.back();
    for (double& k : c.knots) k = end - k;
    std::reverse(c.knots.begin(), c.knots.end());
    std::reverse(c.multiplicities.begin(), c.multiplicities.end());
  }
  std::swap(c.conic.from, c.conic.to);
  return c;
}

}  // namespace

StepLoopOf step_loop(const std::vector<ExactPiece>& pieces, double tolerance) {
  StepLoopOf out;
  for (const ExactPiece& piece : pieces) {
    const Segment& s = piece.segment;
    StepCurve curve;
    if (piece.offset.distance > 0.0) {
      const BezierApproximation a = offset_approximation(piece, tolerance);
      out.max_error = std::max(out.max_error, a.bound);
      out.loop.curves.push_back(a.pieces.size() == 1 ? bezier_of(a.pieces[0]) : bspline_of(a.pieces));
      continue;  // offset_approximation runs from s0 to s1 already
    }
    if (std::min(piece.s0, piece.s1) != 0.0 || std::max(piece.s0, piece.s1) != 1.0) {
      throw GeometryError(to_string(s.kind()), "step: a part of a segment is written only as an offset");
    }
    if (s.kind() == SegmentKind::EllipseArc) {
      curve = conic_of(*s.ellipse());
    } else if (std::optional<BezierPiece> exact = exact_bezier(s)) {
      curve = bezier_of(*exact);
    } else {
      const BezierApproximation a = hermite_approximation(s, tolerance);
      out.max_error = std::max(out.max_error, a.bound);
      curve = a.pieces.size() == 1 ? bezier_of(a.pieces[0]) : bspline_of(a.pieces);
    }
    out.loop.curves.push_back(piece.s0 > piece.s1 ? reversed(std::move(curve)) : std::move(curve));
  }
  return out;
}

StepLoopOf step_loop(const CompositeCurve& curve, double tolerance) {
  return step_loop(exact_pieces(curve), tolerance);
}

StepWritten write_step(const StepModel& model) {
  StepWritten w = api_or_throw().write(model);
  if (!w.error.empty()) throw OutputError("step", "step: " + w.error);
  for (std::size_t i = 0; i < w.bodies.size() && i < model.bodies.size(); ++i) {
    const StepShapeFacts& f = w.bodies[i];
    const StepBody& body = model.bodies[i];
    if (body.form == StepForm::Sheet) {
      if (!f.valid || f.shells != 1 || f.solids != 0 || f.faces != static_cast<int>(body.surfaces.size())) {
        throw OutputError("step",
                          fmt::format("step: OpenCASCADE finds the sheet of '{}' {} ({} shells, {} faces "
                                      "of {}){}; nothing is written",
                                      body.name, !f.valid ? "invalid" : "not one shell", f.shells, f.faces,
                                      body.surfaces.size(), f.problems.empty() ? "" : "; " + f.problems));
      }
      continue;
    }
    const bool solid = body.form != StepForm::Wireframe;
    if (!f.valid || (solid && (f.solids != 1 || !f.closed || !(f.volume > 0.0)))) {
      throw OutputError("step", fmt::format("step: OpenCASCADE finds the {} of '{}' {} ({} solids, {} faces, "
                                            "volume {:.6g}{}); nothing is written",
                                            solid ? "solid" : "wireframe", body.name,
                                            !f.valid ? "invalid" : "not one closed solid", f.solids, f.faces,
                                            f.volume, f.problems.empty() ? "" : "; " + f.problems));
    }
  }
  return w;
}

StepRead read_step(const std::string& bytes) { return api_or_throw().read(bytes); }

double max_distance_to_step(const std::string& bytes, const std::vector<Vec3>& points) {
  const StepDistances d = api_or_throw().distances(bytes, points);
  if (!d.error.empty()) throw OutputError("step", "step: " + d.error);
  return d.max_distance;
}

std::string step_module_status() {
  return module_of<StepModuleApi>("fabmesh-step.so", "fabmesh_step_module", kStepModuleAbi).status;
}

}  // namespace fabmesh
