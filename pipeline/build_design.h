#pragma once
// The builders of the design kinds: design in, validated mesh out, no I/O.
// Each mesh builder validates its mesh with validate_built (validate_built.h)
// as soon as it is made, with the proofs of its construction.
// One overload of `build` per DesignBody alternative (build_vessel.cpp,
// build_countertop.cpp, build_surface.cpp, build_curve_design.cpp);
// build_design dispatches with std::visit and no fallback, so a kind
// without a builder does not compile.

#include "pipeline/built_mesh.h"
#include "pipeline/validate_built.h"

namespace fabmesh {

BuiltMesh build(const CurveDesign& design, const BuildContext& context);
BuiltMesh build(const VesselDesign& design, const BuildContext& context);
BuiltMesh build(const CountertopDesign& design, const BuildContext& context);
BuiltMesh build(const SurfaceDesign& design, const BuildContext& context);

/// Builds and validates `design` with the builder of its kind.
/// \throw InputError (bad design), anything the builder throws
BuiltMesh build_design(const Design& design, const BuildContext& context);

}  // namespace fabmesh
