#pragma once
// Building a design into its mesh (and curves), and writing its outputs,
// with the same proofs and the same bytes as `fabmesh run`.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
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

/// What a part of a result is.
enum class PartRole {
  Product,    ///< the design's own mesh: the vessel, the countertop, the surface
  MouldSide,  ///< a side part of a vessel's slip-casting mould
  MouldBase,  ///< the base part of a vessel's mould
  Piece,      ///< a piece of a kitchen's top, cut at its seams
  Master,     ///< a vessel's casting master (outputs master_stl, master_3mf, master_step)
  Case,       ///< the casting case of a mould part (outputs case_stl, case_3mf)
};

/// The role as the JSON reports name it: "product", "mould_side", "mould_base", "piece", "master", "case".
const char* to_string(PartRole role);

/// One mesh of a result: the design's own (its product) or a mould part.
struct Part {
  std::string name;  ///< the design's name for its product; "side-1", "base" for mould parts
  PartRole role = PartRole::Product;
  Mesh mesh;                    ///< model units (Result::units), outward, counter-clockwise
  ValidationReport validation;  ///< the verdict, with the builder's proofs
};

/// One file `fabmesh run` writes for the design (under "out/").
struct OutputFile {
  std::filesystem::path path;
  std::string format;                    ///< "stl", "3mf", "step", ...
  Unit units = Unit::mm;                 ///< the unit of its coordinates
  double max_added_error = 0.0;          ///< how far writing moves any vertex at most, model units
  std::optional<bool> valid_as_written;  ///< mesh outputs: the mesh as stored is proven valid
  std::vector<std::string> parts;        ///< the parts it holds (empty: the design as a whole)
};

/// A design built as `fabmesh run` builds it, validated, and its outputs
/// encoded in memory (so an output that cannot hold the tolerance is known).
struct Result {
  /// Every part is valid for what the design is for (fabrication, or
  /// viewing for a `purpose: view` surface). When false, `error` says why
  /// and the parts' validations have the defects; nothing should be written.
  bool valid = false;
  std::string error;                  ///< why it is not valid; empty when valid
  std::string name;                   ///< the design's name
  std::string kind;                   ///< "vessel", "countertop", "surface" or "curve"
  Unit units = Unit::mm;              ///< the design's model unit
  double tolerance = 0.0;             ///< the design's tolerance, model units
  double max_deviation = 0.0;         ///< proven bound of the meshes against the exact shape
  std::vector<Part> parts;            ///< the product first; none for a curve design
  std::vector<BuiltCurve> curves;     ///< the design's curves, in the design's order
  std::vector<OutputFile> files;      ///< what `run` writes (valid results only)
  std::vector<std::string> skipped;   ///< outputs that cannot be made, each with why
  std::vector<std::string> warnings;  ///< what deserves a look (a block no output uses, ...)
  /// The product's mesh and verdict (parts[0]), as 0.3 had them.
  std::vector<Point> vertices;
  std::vector<Triangle> triangles;
  ValidationReport validation;
  /// The design's item of `fabmesh run --json` (docs/reports.md), as JSON
  /// text: the one serializer of every report, so each fact of the report
  /// is here. An invalid result's item is the failure's.
  std::string to_json() const { return json_; }

  /// For the library's own implementation: the JSON to_json returns.
  void set_json(std::string json) { json_ = std::move(json); }

 private:
  std::string json_;
};

/// Result under its name before 0.4.
using BuildResult = Result;

/// Builds and validates `design` as `fabmesh run` does (the same tolerance
/// budget, the same proofs), encoding its outputs without writing them.
/// Distinct calls may run in parallel threads.
/// \throw InputError when the design cannot be built as designed (at its key)
Result build(const Design& design);

/// Writes the one output `file` names by its extension, as
/// `fabmesh run DESIGN -o FILE`: the same bytes, all or nothing.
/// \throw InputError (an extension the design's kind has no output for, a
///        design that cannot be built), ValidationFailed (an invalid mesh),
///        MachineError (the file cannot be written)
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
