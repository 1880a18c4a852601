#pragma once
// The builders of the design kinds: design in, validated mesh out, no I/O.
// One overload of `build` per DesignBody alternative (build_vessel.cpp,
// build_countertop.cpp, build_surface.cpp, build_curve_design.cpp);
// build_design dispatches with std::visit and no fallback, so a kind
// without a builder does not compile.

#include <optional>

#include "geometry/mesh/embedding_proof.h"
#include "pipeline/built_mesh.h"

namespace fabmesh {

BuiltMesh build(const CurveDesign& design, const BuildContext& context);
BuiltMesh build(const VesselDesign& design, const BuildContext& context);
BuiltMesh build(const CountertopDesign& design, const BuildContext& context);
BuiltMesh build(const SurfaceDesign& design, const BuildContext& context);

/// Builds and validates `design` with the builder of its kind.
/// \throw InputError (bad design), anything the builder throws
BuiltMesh build_design(const Design& design, const BuildContext& context);

/// Validates a built mesh: by its builder's proof of embedding when there is
/// one (no 3D self-intersection test), fully otherwise, and returns its soup
/// with the report. Times the stage as "validate".
BuiltMesh validated(const Mesh& mesh, const std::optional<EmbeddingProof>& proof,
                    const BuildContext& context);

}  // namespace fabmesh
