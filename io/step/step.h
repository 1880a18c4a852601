#pragma once
// STEP files of exact geometry: fabmesh's curves as exact STEP curves (lines,
// conics, polynomial and rational B-splines; H-Bézier segments approximated
// within a proven bound), extruded or revolved into solids. OpenCASCADE does
// the B-rep and the file, in a module loaded only when it is needed.

#include <string>
#include <vector>

#include "geometry/curves/composite.h"
#include "geometry/sampling/offset_bezier.h"
#include "io/step/step_model.h"

namespace fabmesh {

/// A chain of exact pieces as STEP curves: lines, ellipse arcs as conics,
/// T-Bézier and quasi-B-spline segments as their exact Bézier forms, each
/// H-Bézier segment and each arc of an offset (a shell's inner wall) as one
/// C1 cubic B-spline within `tolerance`. Pieces may run backwards (s0 > s1).
struct StepLoopOf {
  StepLoop loop;
  double max_error = 0.0;  ///< the largest proven bound of an approximated segment; 0 when all exact
};
/// \throw GeometryError when a piece cannot be approximated within tolerance
StepLoopOf step_loop(const std::vector<ExactPiece>& pieces, double tolerance);
/// The same for a composite curve, each segment whole.
StepLoopOf step_loop(const CompositeCurve& curve, double tolerance);

/// Writes `model` (OpenCASCADE builds the B-rep: each body checked valid
/// and, for solids, closed, with its volume).
/// \throw OutputError("step", ...) when OpenCASCADE refuses the geometry;
///        MachineError when the module is missing; never an OpenCASCADE exception
StepWritten write_step(const StepModel& model);

/// Reads a STEP file with OpenCASCADE's reader and describes each root shape
/// (for tests and checks). \throw MachineError when the module is missing
StepRead read_step(const std::string& bytes);

/// The largest distance from `points` (in the file's unit) to the faces of
/// a STEP file's shapes (to its edges, for a wireframe), by OpenCASCADE.
/// \throw OutputError("step", ...) when the file is unreadable; MachineError when the module is missing
double max_distance_to_step(const std::string& bytes, const std::vector<Vec3>& points);

/// Where the STEP module was found, or why it was not (for `fabmesh --version`-like diagnostics).
std::string step_module_status();

}  // namespace fabmesh
