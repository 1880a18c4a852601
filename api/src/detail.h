#pragma once
// The library's private parts: what its handles hold, and the translation of
// the pipeline's exceptions into the public ones. Compiled with
// FABMESH_BUILDING_LIBRARY, so the public names stay in fabmesh::api and
// fabmesh::X is always the pipeline's X here.

#include <optional>
#include <utility>
#include <vector>

#include "fabmesh/curves.h"
#include "fabmesh/errors.h"
#include "geometry/curves/composite.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/fairing/build_curve.h"
#include "io/design/design.h"

namespace fabmesh::api::detail {

struct DesignData {
  fabmesh::Design design;
};

struct CurveData {
  fabmesh::CompositeCurve curve;
  /// What it was built from (fairing builds it again with other shape parameters).
  fabmesh::CurveSpec spec;
  /// The continuity each joint was declared with (CompositeCurve::joints() order).
  std::vector<fabmesh::Continuity> declared;
  std::optional<api::Fairing> fairing;  ///< set on a curve made by fair()
};

/// The public handle of a curve as built (its fairing, if any, kept) from `spec`.
Curve curve_handle(const fabmesh::BuiltCurve& built, fabmesh::CurveSpec spec);

/// Rethrows the exception being handled as the public one of its kind, with
/// the command line's message: InputError (with its key and place),
/// ValidationFailed, EnvironmentError, or Error with exit code 3.
[[noreturn]] void rethrow_public();

/// Runs `f`, with every exception it throws made public (rethrow_public).
template <class F>
auto translated(F&& f) -> decltype(f()) {
  try {
    return std::forward<F>(f)();
  } catch (...) {
    rethrow_public();
  }
}

/// An InputError at a library call's argument ("triangles", "t").
[[noreturn]] void bad_argument(const std::string& argument, const std::string& message);

}  // namespace fabmesh::api::detail
