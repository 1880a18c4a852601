#pragma once
// Reports shared by every command: the validation facts under one set of
// JSON keys (`run` and `check` print the same), job reports, joint reports.

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "geometry/fairing/build_curve.h"
#include "geometry/validation/validate.h"
#include "pipeline/failure.h"
#include "pipeline/job.h"

namespace fabmesh {

/// The validation facts of a mesh: counts, topology, orientation, volume,
/// area, genus, how self-intersection was settled, the defects and the verdict.
nlohmann::ordered_json validation_json(const ValidationReport& report);

/// Stage timings as a JSON object (stage -> ms); `prefix` is put before each name.
nlohmann::ordered_json timings_json(const StageTimings& timings, const std::string& prefix = "");

/// A bounding box as every report writes it: `min`, `max`, `size` (each
/// [x, y, z]) and `units`.
nlohmann::ordered_json bounding_box_json(const Vec3& lo, const Vec3& hi, const std::string& units);

/// A job's JSON report (docs/reports.md): name, kind, units, tolerance,
/// max_deviation, outputs, the validation facts, builder facts and timings.
nlohmann::ordered_json to_json(const JobReport& report);

/// A design's `run --json` item: the design file it was read from, then its report (to_json).
nlohmann::ordered_json design_item(const std::string& design_file, const JobReport& report);

/// The item of a `--json` array for an input that failed (docs/reports.md,
/// "JSON"): {KEY: input, "error": the message, "exit_code": its code}.
nlohmann::ordered_json error_item(const std::string& key, const std::string& input, const Failure& failure);

/// Prints a command's `--json` document: `items`, an array of objects, one per
/// input (design, mesh file, curve, manifest), failed ones as error_item. A
/// string that is not UTF-8 (a file name from the command line) is printed with
/// U+FFFD in place of each bad byte. \throw std::logic_error when `items` is
/// not an array of objects (a bug)
void print_json_items(const nlohmann::ordered_json& items, std::ostream& out);

/// A job's human summary (a few lines).
void print_summary(const JobReport& report, std::ostream& out);

/// One JSON object per joint of a built curve: segments, declared and
/// achieved continuity, whether fairing lost it, gap, angle and curvature jump.
nlohmann::ordered_json joints_json(const BuiltCurve& built);

/// One line per joint: "joint 1 -> 2 (closing): declared G1, measured G2 (gap ..., angle ... rad,
/// curvature jump ...)".
std::string joint_line(const BuiltCurve& built, std::size_t joint);

}  // namespace fabmesh
