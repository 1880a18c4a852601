// The mesh outputs: the product, and a vessel's mould parts, in the export
// unit, each proven valid as the file stores it (or refused).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <stdexcept>

#include "geometry/core/errors.h"
#include "geometry/core/float32.h"
#include "geometry/validation/validate.h"
#include "io/mesh/draco.h"
#include "io/mesh/gltf.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/stl.h"
#include "io/mesh/threemf.h"
#include "pipeline/encoders/encoding.h"

namespace fabmesh {
namespace {

double max_abs_coordinate(const TriangleSoup& soup) {
  double m = 0.0;
  for (const Vec3& p : soup.vertices) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

// The part written: the design's own mesh unless the job writes a kitchen's
// pieces one by one; the output table gives mesh outputs only to kinds that have one.
const Part& product_of(const EncodeContext& c) {
  const Part* part = c.part != nullptr ? c.part : product(c.result);
  if (part == nullptr) throw std::logic_error("a mesh output of a design without a mesh");
  return *part;
}

double float32_error(const EncodeContext& c) {
  return float32_bound(max_abs_coordinate(c.exported), c.export_scale);
}

double double_error(const EncodeContext& c) {
  return decimal_bound(max_abs_coordinate(c.exported), c.export_scale);
}

Encoded within_tolerance(Encoded e, const EncodeContext& c, std::string_view format) {
  if (e.added_error > c.output_tolerance) {
    throw OutputError(
        std::string(format),
        fmt::format("{}: writing moves vertices by up to {:.3g} {} (its number format at coordinates up "
                    "to {:.6g} {}), more than the {:.3g} left of the tolerance; raise the tolerance or "
                    "move the design nearer the origin",
                    format, e.added_error, c.common.units, max_abs_coordinate(c.exported),
                    c.common.export_units, c.output_tolerance));
  }
  return e;
}

// The validation of `stored`, a mesh as a file stores it: `input`'s triangles
// (the same indices, the same order) with its vertices as written. `input` is
// the built mesh (validated as `built`) times `scale` (and turned by quarter
// turns, which round nothing): its combinatorial facts carry over, and only
// its geometry is tested again (validate with moved_from: the same verdict
// as validating it from scratch). A proven embedding margin carries over
// times the scale, less what scaling rounded.
ValidationReport validate_stored(const ValidationReport& built, const TriangleSoup& input, double scale,
                                 const TriangleSoup& stored) {
  ValidationReport original = built;
  const double rounding =
      scale == 1.0 ? 0.0 : std::sqrt(3.0) * std::ldexp(1.0, -52) * max_abs_coordinate(input);
  original.embedding_margin = std::max(0.0, built.embedding_margin * scale * (1.0 - 1e-12) - rounding);
  ValidationOptions options;
  options.moved_from = MovedFrom{&input, &original};
  return validate(stored, options);
}

// Quantization may collapse or fold faces: each candidate's decoded mesh
// (whose faces are `input`'s: fit_draco checks that) is validated as stored.
// Moves within the built mesh's embedding margin (times the scale, as
// validate_stored carries it) keep it valid; a mesh that must be valid
// cannot have two vertices at one position.
DracoAccept still_fit(const EncodeContext& c, const TriangleSoup& input, double scale) {
  const ValidationReport& built = product_of(c).validation;
  const MeshPurpose purpose = c.result.purpose;
  DracoAccept a;
  a.accept = [&built, &input, scale, purpose](const TriangleSoup& decoded) {
    return fit_for(validate_stored(built, input, scale, decoded), purpose);
  };
  a.margin = built.valid() ? 0.5 * built.embedding_margin * scale : 0.0;
  a.distinct_positions = purpose != MeshPurpose::Drawing;
  return a;
}

// Every coordinate rounded to float32, as STL and PLY store them.
TriangleSoup soup_in_float32(const TriangleSoup& soup) {
  TriangleSoup out = soup;
  for (Vec3& p : out.vertices) {
    p = rounded_to_float32(p);
  }
  return out;
}

// Marks a mesh output's file valid as written once the mesh it stores is proven fit
// for the built mesh's purpose (valid; for viewing, open only at its border):
// stored exactly as built, or moved by less than the built mesh's embedding
// margin, or else `stored()` (the mesh as a reader of the file gets it, in
// the frame of `input`, the built mesh times `scale`) validated.
// \throw OutputError when the stored mesh is not fit: that file is not written.
struct StoredMesh {
  const ValidationReport& built;  ///< the built mesh's report
  const TriangleSoup& input;      ///< the built mesh in the file's frame, before rounding
  double scale = 1.0;             ///< input = built mesh x scale
  std::function<TriangleSoup()> stored;
  MeshPurpose purpose = MeshPurpose::Fabrication;  ///< what the mesh must be fit for
};

void prove_as_stored(Encoded& e, const EncodeContext& c, std::string_view format, const StoredMesh& mesh) {
  const MeshPurpose purpose = mesh.purpose;
  const bool moved = e.added_error != 0.0;
  if (fit_for(mesh.built, purpose) && (!moved || e.added_error < mesh.built.embedding_margin)) {
    e.valid_as_written = true;
    return;
  }
  const ValidationReport report = validate_stored(mesh.built, mesh.input, mesh.scale, mesh.stored());
  if (!fit_for(report, purpose)) {
    std::string defects;
    for (const std::string& line : describe_defects(report)) defects += "; " + line;
    throw OutputError(
        std::string(format),
        fmt::format("{}: as the file stores it (vertices moved by up to {:.3g} {}), the mesh is "
                    "no longer valid{}; nothing is written to it: the design has features "
                    "finer than that (points or edges nearly touching), or drop {}",
                    format, e.added_error, c.common.units, defects, format));
  }
  e.valid_as_written = true;
}

// The product as a mesh file stores it: exported (`input`, in the file's
// frame, `scale` times the built mesh), read back by `stored`.
StoredMesh product_file(const EncodeContext& c, const TriangleSoup& input, double scale,
                        std::function<TriangleSoup()> stored) {
  return {product_of(c).validation, input, scale, std::move(stored), c.result.purpose};
}

// The exported mesh as a float32 file (STL, PLY) stores it.
StoredMesh float32_file(const EncodeContext& c) {
  return product_file(c, c.exported, c.export_scale, [&c] { return soup_in_float32(c.exported); });
}

// The exported mesh as a file of exact decimals (OBJ, OFF) stores it.
StoredMesh decimal_file(const EncodeContext& c) {
  return product_file(c, c.exported, c.export_scale, [&c] { return c.exported; });
}

// The objects of a 3MF file as its reader gets them, in file order.
std::vector<TriangleSoup> stored_3mf_objects(const std::string& bytes) {
  std::vector<TriangleSoup> soups;
  for (ThreeMfObject& object : parse_3mf(bytes, "3mf output").objects)
    soups.push_back(std::move(object.soup));
  return soups;
}

Encoded unitless(std::string bytes, const EncodeContext& c, double error) {
  Encoded e;
  e.bytes = std::move(bytes);
  e.units = c.common.export_units;
  e.added_error = error;
  return e;
}

GlbOptions glb_options(const EncodeContext& c) {
  GlbOptions options;
  options.name = c.common.name;
  options.scale_to_metres = metres_per_unit(c.common.units);
  return options;
}

// The mould's parts, in the export unit, in the order built.
struct ExportedPart {
  const Part* part;
  TriangleSoup mesh;
};

std::vector<ExportedPart> exported_parts(const EncodeContext& c, std::initializer_list<PartRole> roles) {
  std::vector<ExportedPart> parts;
  for (const Part& p : c.result.parts) {
    if (std::find(roles.begin(), roles.end(), p.role) == roles.end()) continue;
    ExportedPart e{&p, p.mesh};
    for (Vec3& v : e.mesh.vertices) v *= c.export_scale;
    parts.push_back(std::move(e));
  }
  return parts;
}

// Parts as separate objects of one 3MF, named "NAME GROUP PART" ("NAME PART"
// without a group), each proven valid as the file stores it.
Encoded parts_3mf(const EncodeContext& c, const std::vector<ExportedPart>& parts, const std::string& group,
                  const char* format) {
  std::vector<ThreeMfObject> objects;
  double largest = 0.0;
  const std::string prefix = c.common.name + (group.empty() ? "" : " " + group);
  for (const ExportedPart& p : parts) {
    largest = std::max(largest, max_abs_coordinate(p.mesh));
    objects.push_back({prefix + " " + p.part->name, p.mesh});
  }
  ThreeMfOptions options;
  options.units = c.common.export_units;
  options.title = group.empty() ? c.common.name + " " + parts.front().part->name : prefix;
  Encoded e = unitless(encode_3mf(objects, options), c, threemf_max_error(largest) / c.export_scale);
  for (const ExportedPart& p : parts) e.parts.push_back(p.part->name);
  // Each part as the file stores it: its own object, read back (once, when a part needs it).
  std::optional<std::vector<TriangleSoup>> stored;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    prove_as_stored(e, c, format,
                    {parts[i].part->validation, objects[i].soup, c.export_scale,
                     [&, i] {
                       if (!stored) stored = stored_3mf_objects(e.bytes);
                       if (stored->size() != objects.size())
                         throw std::logic_error(std::string(format) + ": the file lost a part");
                       return (*stored)[i];
                     },
                     MeshPurpose::Fabrication});
  }
  return e;
}

// The casting master, the one part of its role, in the export unit (for `format`).
// The master, whole or in its sections (print.bed).
std::vector<ExportedPart> the_master(const EncodeContext& c, const char* format) {
  std::vector<ExportedPart> master = exported_parts(c, {PartRole::Master});
  if (master.empty()) throw std::logic_error(std::string(format) + ": the master was not built");
  return master;
}

// One part as STL, proven valid as stored.
Encoded part_stl(const EncodeContext& c, const ExportedPart& p, const char* format) {
  Encoded e = unitless(encode_stl(p.mesh), c, float32_bound(max_abs_coordinate(p.mesh), c.export_scale));
  e.parts = {p.part->name};
  prove_as_stored(e, c, format,
                  {p.part->validation, p.mesh, c.export_scale, [&p] { return soup_in_float32(p.mesh); },
                   MeshPurpose::Fabrication});
  return e;
}

}  // namespace

void require_cases(const EncodeContext& c, const char* format) {
  const VesselProducts& vessel = std::get<VesselProducts>(c.result.products);
  if (!vessel.cases.empty()) return;
  std::string why;
  for (const std::string& r : vessel.case_refusals) why += (why.empty() ? "" : "; ") + r;
  throw OutputError(format, fmt::format("{}: no mould part has a casting case: {}", format, why));
}

double float32_bound(double largest_exported, double export_scale) {
  // Rounding each coordinate to float32 moves a vertex by at most sqrt(3) 2^-24 max|x|
  // (export units); scaling by a double adds at most 2^-52 of it. In model units.
  return std::sqrt(3.0) * (std::ldexp(1.0, -24) + std::ldexp(1.0, -52)) * largest_exported / export_scale;
}

double decimal_bound(double largest_exported, double export_scale) {
  return export_scale == 1.0 ? 0.0 : std::sqrt(3.0) * std::ldexp(1.0, -52) * largest_exported / export_scale;
}

double threemf_bound(double largest_exported, double export_scale) {
  return threemf_max_error(largest_exported) / export_scale + decimal_bound(largest_exported, export_scale);
}

EncodedFiles encode_stl_output(const EncodeContext& c) {
  Encoded e = unitless({}, c, float32_error(c));
  const TriangleSoup& soup = c.exported;
  e.stream = [&soup](const std::function<void(std::string_view)>& sink) { encode_stl_pieces(soup, sink); };
  e = within_tolerance(std::move(e), c, "stl");
  prove_as_stored(e, c, "stl", float32_file(c));
  return {std::move(e)};
}

EncodedFiles encode_obj_output(const EncodeContext& c) {
  Encoded e = within_tolerance(unitless(encode_obj(c.exported), c, double_error(c)), c, "obj");
  prove_as_stored(e, c, "obj", decimal_file(c));
  return {std::move(e)};
}

EncodedFiles encode_ply_output(const EncodeContext& c) {
  Encoded e = within_tolerance(unitless(encode_ply(c.exported), c, float32_error(c)), c, "ply");
  prove_as_stored(e, c, "ply", float32_file(c));
  return {std::move(e)};
}

EncodedFiles encode_off_output(const EncodeContext& c) {
  Encoded e = within_tolerance(unitless(encode_off(c.exported), c, double_error(c)), c, "off");
  prove_as_stored(e, c, "off", decimal_file(c));
  return {std::move(e)};
}

EncodedFiles encode_3mf_output(const EncodeContext& c) {
  ThreeMfOptions options;
  options.units = c.common.export_units;
  options.title = c.common.name;
  const double error = threemf_bound(max_abs_coordinate(c.exported), c.export_scale);
  Encoded e =
      within_tolerance(unitless(encode_3mf({{c.common.name, c.exported}}, options), c, error), c, "3mf");
  prove_as_stored(e, c, "3mf", product_file(c, c.exported, c.export_scale, [&e] {
                    return stored_3mf_objects(e.bytes).front();
                  }));
  return {std::move(e)};
}

EncodedFiles encode_drc_output(const EncodeContext& c) {
  const double tolerance = c.output_tolerance * c.export_scale;  // export units
  DracoFit fit = fit_draco(c.exported, tolerance, still_fit(c, c.exported, c.export_scale), "drc");
  // fit.bytes are the file whose decoding was matched to the mesh and validated.
  Encoded e = unitless(std::move(fit.bytes), c, fit.max_displacement / c.export_scale);
  e.valid_as_written = true;  // its decoding was validated (still_fit)
  return {std::move(e)};
}

EncodedFiles encode_glb_output(const EncodeContext& c) {
  const GlbOptions options = glb_options(c);
  const TriangleSoup& mesh = product_of(c).mesh;
  // float32 metres: relative rounding as for STL, of the model's own coordinates.
  const double error = float32_bound(max_abs_coordinate(mesh), 1.0);
  Encoded e = unitless(encode_glb(mesh, options), c, error);
  e.units = "m";
  const TriangleSoup metres = to_gltf_frame(mesh, options.scale_to_metres);
  e = within_tolerance(std::move(e), c, "glb");
  prove_as_stored(e, c, "glb", product_file(c, metres, options.scale_to_metres, [&metres] {
                    return soup_in_float32(metres);
                  }));
  return {std::move(e)};
}

EncodedFiles encode_glb_draco_output(const EncodeContext& c) {
  GlbOptions options = glb_options(c);
  const TriangleSoup& mesh = product_of(c).mesh;
  const TriangleSoup metres = to_gltf_frame(mesh, options.scale_to_metres);
  const DracoFit fit = fit_draco(metres, c.output_tolerance * options.scale_to_metres,
                                 still_fit(c, metres, options.scale_to_metres), "glb_draco");
  options.draco = true;
  options.draco_position_bits = fit.bits;
  Encoded e = unitless(encode_glb(mesh, options), c, fit.max_displacement / options.scale_to_metres);
  e.units = "m";
  e.valid_as_written = true;  // its decoding was validated (still_fit)
  return {std::move(e)};
}

EncodedFiles encode_mould_stl_output(const EncodeContext& c) {
  EncodedFiles files;
  for (const ExportedPart& p : exported_parts(c, {PartRole::MouldSide, PartRole::MouldBase})) {
    Encoded e = part_stl(c, p, "mould_stl");
    e.suffix = ".mould-" + p.part->name + ".stl";
    files.push_back(std::move(e));
  }
  return files;
}

// NAME.master.stl, or one file per section: NAME.master.section-1.stl, ...
EncodedFiles encode_master_stl_output(const EncodeContext& c) {
  const std::vector<ExportedPart> master = the_master(c, "master_stl");
  if (master.size() == 1) return {part_stl(c, master.front(), "master_stl")};
  EncodedFiles files;
  for (const ExportedPart& p : master) {
    Encoded e = part_stl(c, p, "master_stl");
    e.suffix = ".master." + p.part->name + ".stl";
    files.push_back(std::move(e));
  }
  return files;
}

EncodedFiles encode_mould_3mf_output(const EncodeContext& c) {
  return {parts_3mf(c, exported_parts(c, {PartRole::MouldSide, PartRole::MouldBase}), "mould", "mould_3mf")};
}

// The casting cases that were built (require_cases: at least one).
std::vector<ExportedPart> the_cases(const EncodeContext& c, const char* format) {
  require_cases(c, format);
  return exported_parts(c, {PartRole::Case});
}

// NAME.case-side-1.stl, ...: one file per case.
EncodedFiles encode_case_stl_output(const EncodeContext& c) {
  EncodedFiles files;
  for (const ExportedPart& p : the_cases(c, "case_stl")) {
    Encoded e = part_stl(c, p, "case_stl");
    e.suffix = "." + p.part->name + ".stl";
    files.push_back(std::move(e));
  }
  return files;
}

EncodedFiles encode_case_3mf_output(const EncodeContext& c) {
  return {parts_3mf(c, the_cases(c, "case_3mf"), "", "case_3mf")};
}

EncodedFiles encode_master_3mf_output(const EncodeContext& c) {
  return {parts_3mf(c, the_master(c, "master_3mf"), "", "master_3mf")};
}

}  // namespace fabmesh
