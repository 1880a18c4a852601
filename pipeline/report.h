#pragma once
// Reports shared by every command: the validation facts under one set of
// JSON keys (`run` and `check` print the same), job reports, joint reports.

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "geometry/fairing/build_curve.h"
#include "geometry/validation/validate.h"
#include "pipeline/job.h"

namespace fabmesh {

/// The validation facts of a mesh: counts, topology, orientation, volume,
/// area, genus, how self-intersection was settled, the defects and the verdict.
nlohmann::ordered_json validation_json(const ValidationReport& report);

/// Stage timings as a JSON object (stage -> ms); `prefix` is put before each name.
nlohmann::ordered_json timings_json(const StageTimings& timings, const std::string& prefix = "");

/// A job's JSON report (docs/reports.md): name, kind, units, tolerance,
/// max_deviation, outputs, the validation facts, builder facts and timings.
nlohmann::ordered_json to_json(const JobReport& report);

/// A job's human summary (a few lines).
void print_summary(const JobReport& report, std::ostream& out);

/// One JSON object per joint of a built curve: segments, declared and
/// achieved continuity, whether fairing lost it, gap, angle and curvature jump.
nlohmann::ordered_json joints_json(const BuiltCurve& built);

/// One line per joint: "joint 1 -> 2 (closing): declared G1, measured G2 (gap ..., angle ... rad,
/// curvature jump ...)".
std::string joint_line(const BuiltCurve& built, std::size_t joint);

}  // namespace fabmesh
