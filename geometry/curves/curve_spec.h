#pragma once
// The plain description of a curve as a designer gives it (control points,
// shape parameters, joins), and its construction into a CompositeCurve.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "geometry/curves/composite.h"

namespace fabmesh {

enum class CurveFamily { TBezier, HBezier, QuasiBSpline };
enum class FairMode { None, Strain, CurvatureVariation };

const char* to_string(CurveFamily f);
const char* to_string(FairMode f);

/// How a segment's leading control points are computed from the previous
/// segment. A T-Bézier segment uses (alpha, beta): r1'(1) = alpha r2'(0),
/// r1''(1) = alpha^2 r2''(0) + beta r2'(0) (docs/math/curves.md 1.1); an H-Bézier
/// segment uses (k, m): Q'(0) = k P'(end), Q''(0) = k^2 P''(end) + m P'(end)
/// (docs/math/h-bezier.md), derivatives in each segment's native parameter.
struct JoinSpec {
  Continuity continuity = Continuity::G1;
  double alpha = 1.0;  ///< > 0 (T-Bézier convention)
  double beta = 0.0;
  double k = 1.0;  ///< > 0 (H-Bézier convention)
  double m = 0.0;
};

struct SegmentSpec {
  SegmentKind kind = SegmentKind::TBezier;
  /// The designer's points: all control points of an explicit segment, or the
  /// free ones after a join (G0: 3, G1: 2, G2: 1 for a cubic); a line gives
  /// [to] (starting where the previous segment ends) or [from, to] when first.
  std::vector<Vec2> points;
  double lambda = 0.0, mu = 0.0, alpha = 1.0;
  std::optional<JoinSpec> join;
  /// Continuity an explicit segment declares with its predecessor: verified, not constructed.
  Continuity declared = Continuity::G0;
  EllipseArcParams ellipse;  ///< when kind == EllipseArc
  /// The points' weights when kind == RationalBezier (each finite and > 0).
  std::array<double, 4> weights{1.0, 1.0, 1.0, 1.0};
  /// Its design key path ("profile.segments[2]"), where errors about it are;
  /// empty: messages name it "segment i".
  std::string key;
  /// How messages name it when that says more than the key
  /// ("profile.segments[2] (point 3)" of a polyline); empty: the key.
  std::string name;
  /// A countertop outline's segment along a wall (`edge: wall`): a kitchen's
  /// pieces mark its edges `wall`, not exposed, and backsplash strips stand on them.
  bool wall = false;
};

struct CurveSpec {
  CurveFamily family = CurveFamily::TBezier;
  bool closed = false;
  std::vector<SegmentSpec> segments;  ///< T-/H-Bézier composites
  /// Declared continuity of the closing joint when the first segment has no join.
  Continuity closing_declared = Continuity::G0;
  std::vector<Vec2> bspline_points;     ///< quasi_bspline: p0..pn, n >= 2
  std::vector<double> bspline_lambdas;  ///< quasi_bspline: lambda_1..lambda_{n-1}; empty = all 0
  /// quasi_bspline given by `through:`: the points q0..qn the curve passes
  /// through at its joints (bspline_points then holds the control points
  /// solved from them, quasi_bspline_through); empty for `points:`.
  std::vector<Vec2> bspline_through;
  /// With bspline_through: the proven largest distance from a through point
  /// to its joint of the curve the control points make.
  double bspline_through_deviation = 0.0;
  FairMode fair = FairMode::None;
  /// The continuity every joint must keep after fairing (design key
  /// `fair_keeps`): a joint declared higher may drop to this, not below.
  /// Absent: every declared continuity must survive fairing.
  std::optional<Continuity> fair_keeps;
  /// Its design key path ("profile", "holes[1]"), where errors about it are
  /// (GeometryError::location); empty: none.
  std::string key;
};

/// Builds the segments, computing every join-determined control point (an
/// open chain, or a closed loop whose first segment joins the last: a linear
/// system solved exactly). No fairing, no continuity verification.
/// \throw RangeError, GeometryError
CompositeCurve construct_curve(const CurveSpec& spec);

/// The continuity each joint of `curve` was declared with (same order as
/// CompositeCurve::joints()).
std::vector<Continuity> declared_continuity(const CurveSpec& spec);

/// Throws GeometryError naming the first joint whose measured continuity
/// is below the declared one (at the curve's key).
void verify_declared_continuity(const CurveSpec& spec, const CompositeCurve& curve,
                                const JointTolerances& tol = {});

}  // namespace fabmesh
