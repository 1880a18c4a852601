#pragma once
// Reports shared by every command: the one serializer of a job's Result
// (to_json: `run --json`, the studio, the library and Python print what it
// makes), the validation facts under one set of JSON keys (`run` and `check`
// print the same), and the one model of an item's facts (ItemFacts,
// MeshFacts) that every table of items is made from (batch rows, the HTML
// report).

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "geometry/fairing/build_curve.h"
#include "geometry/validation/validate.h"
#include "pipeline/facts.h"
#include "pipeline/failure.h"
#include "pipeline/result.h"

namespace fabmesh {

/// The facts of a built mesh (or drawing) that every report of it shows:
/// `run --json`, a batch's summary rows, the HTML reports, `check`. In model
/// units.
struct MeshFacts {
  std::string kind;   ///< vessel | countertop | surface | curve; empty for a mesh file
  std::string units;  ///< of the facts below; empty for a mesh file that states none
  /// A mesh was validated, so the counts, volume and area are its own; false
  /// for a drawing (a curve design). Not kept in a summary row: read back
  /// from its kind (a curve's is a drawing).
  bool measured = true;
  std::size_t vertices = 0, triangles = 0;
  double volume = 0.0, area = 0.0;
  bool valid = false;  ///< valid for fabrication (a `purpose: view` surface may be written and not be)
  Vec3 bbox_min = Vec3::Zero(), bbox_max = Vec3::Zero();
  double max_deviation = 0.0, tolerance = 0.0;  ///< proven bound and the design's tolerance
};

/// One item of a report: a design that ran (or failed), a batch variant, a
/// mesh file checked. Every report's row or item is made from one.
struct ItemFacts {
  std::string name;  ///< the design's or variant's name, or the mesh file
  ItemStatus status = ItemStatus::Ok;
  std::string message;             ///< the verdict in words, or why it failed
  std::optional<MeshFacts> mesh;   ///< when built (or read)
  std::vector<std::string> files;  ///< written (paths as the job names them)
  StageTimings timings_ms;
  /// Lines under the verdict: the print checks' summary (a vessel), the warnings.
  std::vector<std::string> remarks;
};

/// The words of an item that is valid for fabrication.
inline constexpr const char* kValidForFabrication = "valid for fabrication";

/// The facts a validation gives: counts, volume, area and validity, in `units`.
MeshFacts mesh_facts(const ValidationReport& validation, const std::string& units);

/// A result's mesh facts: its product's validation (mesh_facts above), its
/// kind, box, proven deviation and tolerance; not `measured` for a drawing.
MeshFacts mesh_facts(const Result& result);

/// The status and words of a job that wrote `mesh`: "valid for fabrication",
/// "drawing written" (a curve design), or invalid and "written for viewing
/// only" (an open `purpose: view` surface). Every report says it this way.
void set_written_verdict(ItemFacts& item, const MeshFacts& mesh);

/// A job that ran: Ok when its mesh is valid for fabrication (or it is a
/// drawing), Invalid when written for viewing only, said in words; its mesh
/// facts, the files it wrote and its stage timings.
ItemFacts item_facts(const Result& result);

/// An item that failed with `exit_code` (describe_failure's) and `message`;
/// no facts beyond.
ItemFacts failed_facts(const std::string& name, int exit_code, const std::string& message);

/// A mesh file `check` read: Ok when each of its objects is valid, else
/// Invalid; the facts of its one object (none for several).
ItemFacts check_facts(const std::string& file, const std::vector<MeshFacts>& objects);

/// The validation facts of a mesh: counts, topology, orientation, volume,
/// area, genus, how self-intersection was settled, the defects and the verdict.
nlohmann::ordered_json validation_json(const ValidationReport& report);

/// Stage timings as a JSON object (stage -> ms); `prefix` is put before each name.
nlohmann::ordered_json timings_json(const StageTimings& timings, const std::string& prefix = "");

/// A mesh's bounding box as every report writes it: `min`, `max`, `size`
/// (each [x, y, z]) and `units`.
nlohmann::ordered_json bounding_box_json(const MeshFacts& mesh);

/// A builder's facts as JSON (the report's `build`): each group an object
/// with its keys in order of name, as the report has always printed them.
nlohmann::ordered_json facts_json(const Facts& facts);

/// The facts of facts_json's JSON, read back (a batch's summary row keeps
/// them). \throw InputError for a value no fact has (not an object at the top)
Facts facts_from_json(const nlohmann::ordered_json& json);

/// A part as the report lists it: name, role, counts, volume, area, genus, validity.
nlohmann::ordered_json part_json(const Part& part);

/// A job's result as JSON (docs/reports.md): name, kind, units, tolerance,
/// max_deviation, outputs, the product's validation facts, the parts,
/// builder facts and timings. The one serializer of a Result.
nlohmann::ordered_json to_json(const Result& result);

/// A parameter's value as reports give it: a number, a choice's text, or true / false.
nlohmann::ordered_json parameter_json(const DesignParameter& p);

/// A design's `run --json` item: the design file it was read from, then its result (to_json).
nlohmann::ordered_json design_item(const std::string& design_file, const Result& result);

/// The item of a `--json` array for an input that failed (docs/reports.md,
/// "JSON"): {KEY: input, "error": the message, "exit_code": its code}.
nlohmann::ordered_json error_item(const std::string& key, const std::string& input, const Failure& failure);

/// Prints a command's `--json` document: `items`, an array of objects, one per
/// input (design, mesh file, curve, manifest), failed ones as error_item. A
/// string that is not UTF-8 (a file name from the command line) is printed with
/// U+FFFD in place of each bad byte. \throw std::logic_error when `items` is
/// not an array of objects (a bug)
void print_json_items(const nlohmann::ordered_json& items, std::ostream& out);

/// One JSON object per joint of a built curve: segments, declared and
/// achieved continuity, whether fairing lost it, gap, angle and curvature jump.
nlohmann::ordered_json joints_json(const BuiltCurve& built);

/// One line per joint: "joint 1 -> 2 (closing): declared G1, measured G2 (gap ..., angle ... rad,
/// curvature jump ...)".
std::string joint_line(const BuiltCurve& built, std::size_t joint);

}  // namespace fabmesh
