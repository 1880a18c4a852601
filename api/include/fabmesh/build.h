#pragma once
// Building a design into its mesh (and curves), and writing its outputs,
// with the same proofs and the same bytes as `fabmesh run`.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "fabmesh/curves.h"
#include "fabmesh/design.h"
#include "fabmesh/mesh.h"

namespace fabmesh {
namespace api {

/// One of the design's curves as built, sampled within the proven bound.
struct BuiltCurve {
  std::string key;  ///< the design key it comes from: "curve", "profile", "outline", "holes[0]"
  std::vector<std::array<double, 2>> points;  ///< the sampled polyline, model units
  bool closed = false;                        ///< the last point joins the first
  double max_deviation = 0.0;                 ///< proven bound of the polyline against the exact curve
  Curve curve;                                ///< the exact curve, to evaluate
};

/// A design built as `fabmesh run` builds it, validated, and its outputs
/// encoded in memory (so an output that cannot hold the tolerance is known).
struct BuildResult {
  /// The mesh is valid for what the design is for (fabrication, or viewing
  /// for a `purpose: view` surface). When false, `error` says why and
  /// `validation` has the defects; nothing of it should be written.
  bool valid = false;
  std::vector<Point> vertices;      ///< model units; empty for a curve design
  std::vector<Triangle> triangles;  ///< outward, counter-clockwise
  std::string units;                ///< the design's model unit
  double tolerance = 0.0;           ///< the design's tolerance, model units
  double max_deviation = 0.0;       ///< proven bound of the mesh against the exact shape
  ValidationReport validation;      ///< the verdict, with the builder's proofs
  std::vector<BuiltCurve> curves;   ///< the design's curves, in the design's order
  std::string error;                ///< why it is not valid; empty when valid
  /// The design's item of `fabmesh run --json` (docs/reports.md), as JSON
  /// text: outputs as they would be written under "out/", skipped outputs,
  /// tolerance split, validation facts, timings.
  std::string report_json;
};

/// Builds and validates `design` as `fabmesh run` does (the same tolerance
/// budget, the same proofs), encoding its outputs without writing them.
/// Distinct calls may run in parallel threads.
/// \throw InputError when the design cannot be built as designed (at its key)
BuildResult build(const Design& design);

/// Writes the one output `file` names by its extension, as
/// `fabmesh run DESIGN -o FILE`: the same bytes, all or nothing.
/// \throw InputError (an extension the design's kind has no output for, a
///        design that cannot be built), ValidationFailed (an invalid mesh),
///        EnvironmentError (the file cannot be written)
void write_output(const Design& design, const std::filesystem::path& file);

/// Writes every output of `design` into `folder` (created when missing), as
/// `fabmesh run DESIGN -o FOLDER/`; returns the files written.
/// \throw as write_output
std::vector<std::filesystem::path> write_outputs(const Design& design, const std::filesystem::path& folder);

/// Optimizes the shape parameters of the design's curves as `fabmesh
/// optimize --json` does; returns its JSON document (an array, one item per curve).
/// \throw InputError (a design without curves to optimize, a bad design)
std::string optimize(const Design& design);

}  // namespace api
#ifndef FABMESH_BUILDING_LIBRARY
using namespace api;  // fabmesh::Design, fabmesh::build, ...
#endif
}  // namespace fabmesh
