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

/// What the library throws: an error of fabmesh's one tree (E: InputError,
/// MissingFileError, ValidationFailed, MachineError, Error), marked as
/// already made public, so that rethrow_public leaves it as it is.
struct Published {};
template <class E>
class Public : public E, public Published {
 public:
  using E::E;
};

/// Rethrows the exception being handled as the public one of its kind (the
/// same class of geometry/core/errors.h), with the command line's whole
/// message: InputError (with its location), MissingFileError,
/// ValidationFailed, MachineError, or Error with exit code 3.
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
