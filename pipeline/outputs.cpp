#include "pipeline/outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/core/float32.h"
#include "geometry/surfaces/bspline_patch.h"
#include "geometry/surfaces/bspline_shell.h"
#include "geometry/validation/validate.h"
#include "io/cutting/dxf.h"
#include "io/cutting/gcode.h"
#include "io/cutting/svg.h"
#include "io/cutting/toolpath_svg.h"
#include "io/mesh/draco.h"
#include "io/mesh/gltf.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/stl.h"
#include "io/mesh/threemf.h"
#include "io/step/step.h"
#include "pipeline/pictures.h"

namespace fabmesh {
namespace {

double max_abs_coordinate(const TriangleSoup& soup) {
  double m = 0.0;
  for (const Vec3& p : soup.vertices) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

// Rounding each coordinate to float32 moves a vertex by at most sqrt(3) 2^-24 max|x|
// (export units); scaling by a double adds at most 2^-52 of it. In model units.
double float32_bound(double largest_exported, double export_scale) {
  return std::sqrt(3.0) * (std::ldexp(1.0, -24) + std::ldexp(1.0, -52)) * largest_exported / export_scale;
}

// Shortest round-trip decimals are exact; only the scaling to the export unit rounds.
double decimal_bound(double largest_exported, double export_scale) {
  return export_scale == 1.0 ? 0.0 : std::sqrt(3.0) * std::ldexp(1.0, -52) * largest_exported / export_scale;
}

// 3MF's micro-unit decimals of float32 values, and the scaling.
double threemf_bound(double largest_exported, double export_scale) {
  return threemf_max_error(largest_exported) / export_scale + decimal_bound(largest_exported, export_scale);
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
  DracoAccept a;
  a.accept = [&c, &input, scale](const TriangleSoup& decoded) {
    return fit_for(validate_stored(c.built.validation, input, scale, decoded), c.built.purpose);
  };
  a.margin = c.built.validation.valid() ? 0.5 * c.built.validation.embedding_margin * scale : 0.0;
  a.distinct_positions = c.built.purpose != MeshPurpose::Drawing;
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
};

void prove_as_stored(Encoded& e, const EncodeContext& c, std::string_view format, const StoredMesh& mesh) {
  const MeshPurpose purpose = c.built.purpose;
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

// The exported mesh as a float32 file (STL, PLY) stores it.
StoredMesh float32_file(const EncodeContext& c) {
  return {c.built.validation, c.exported, c.export_scale, [&c] { return soup_in_float32(c.exported); }};
}

// The exported mesh as a file of exact decimals (OBJ, OFF) stores it.
StoredMesh decimal_file(const EncodeContext& c) {
  return {c.built.validation, c.exported, c.export_scale, [&c] { return c.exported; }};
}

// The objects of a 3MF file as its reader gets them, in file order.
std::vector<TriangleSoup> stored_3mf_objects(const std::string& bytes) {
  std::vector<TriangleSoup> soups;
  for (ThreeMfObject& object : parse_3mf(bytes, "3mf output").objects)
    soups.push_back(std::move(object.soup));
  return soups;
}

using Files = std::vector<Encoded>;

Encoded unitless(std::string bytes, const EncodeContext& c, double error) {
  Encoded e;
  e.bytes = std::move(bytes);
  e.units = c.common.export_units;
  e.added_error = error;
  return e;
}

Files encode_stl_output(const EncodeContext& c) {
  Encoded e = unitless({}, c, float32_error(c));
  const TriangleSoup& soup = c.exported;
  e.stream = [&soup](const std::function<void(std::string_view)>& sink) { encode_stl_pieces(soup, sink); };
  e = within_tolerance(std::move(e), c, "stl");
  prove_as_stored(e, c, "stl", float32_file(c));
  return {std::move(e)};
}
Files encode_obj_output(const EncodeContext& c) {
  Encoded e = within_tolerance(unitless(encode_obj(c.exported), c, double_error(c)), c, "obj");
  prove_as_stored(e, c, "obj", decimal_file(c));
  return {std::move(e)};
}
Files encode_ply_output(const EncodeContext& c) {
  Encoded e = within_tolerance(unitless(encode_ply(c.exported), c, float32_error(c)), c, "ply");
  prove_as_stored(e, c, "ply", float32_file(c));
  return {std::move(e)};
}
Files encode_off_output(const EncodeContext& c) {
  Encoded e = within_tolerance(unitless(encode_off(c.exported), c, double_error(c)), c, "off");
  prove_as_stored(e, c, "off", decimal_file(c));
  return {std::move(e)};
}

Files encode_3mf_output(const EncodeContext& c) {
  ThreeMfOptions options;
  options.units = c.common.export_units;
  options.title = c.common.name;
  const double error = threemf_bound(max_abs_coordinate(c.exported), c.export_scale);
  Encoded e =
      within_tolerance(unitless(encode_3mf({{c.common.name, c.exported}}, options), c, error), c, "3mf");
  prove_as_stored(e, c, "3mf", {c.built.validation, c.exported, c.export_scale, [&e] {
                                  return stored_3mf_objects(e.bytes).front();
                                }});
  return {std::move(e)};
}

Files encode_drc_output(const EncodeContext& c) {
  const double tolerance = c.output_tolerance * c.export_scale;  // export units
  DracoFit fit = fit_draco(c.exported, tolerance, still_fit(c, c.exported, c.export_scale), "drc");
  // fit.bytes are the file whose decoding was matched to the mesh and validated.
  Encoded e = unitless(std::move(fit.bytes), c, fit.max_displacement / c.export_scale);
  e.valid_as_written = true;  // its decoding was validated (still_fit)
  return {std::move(e)};
}

GlbOptions glb_options(const EncodeContext& c) {
  GlbOptions options;
  options.name = c.common.name;
  options.scale_to_metres = metres_per_unit(c.common.units);
  return options;
}

Files encode_glb_output(const EncodeContext& c) {
  const GlbOptions options = glb_options(c);
  // float32 metres: relative rounding as for STL, of the model's own coordinates.
  const double error = float32_bound(max_abs_coordinate(c.built.soup), 1.0);
  Encoded e{encode_glb(c.built.soup, options), "m", error, ""};
  const TriangleSoup metres = to_gltf_frame(c.built.soup, options.scale_to_metres);
  e = within_tolerance(std::move(e), c, "glb");
  prove_as_stored(e, c, "glb", {c.built.validation, metres, options.scale_to_metres, [&metres] {
                                  return soup_in_float32(metres);
                                }});
  return {std::move(e)};
}

Files encode_glb_draco_output(const EncodeContext& c) {
  GlbOptions options = glb_options(c);
  const TriangleSoup metres = to_gltf_frame(c.built.soup, options.scale_to_metres);
  const DracoFit fit = fit_draco(metres, c.output_tolerance * options.scale_to_metres,
                                 still_fit(c, metres, options.scale_to_metres), "glb_draco");
  options.draco = true;
  options.draco_position_bits = fit.bits;
  Encoded e{encode_glb(c.built.soup, options), "m", fit.max_displacement / options.scale_to_metres, ""};
  e.valid_as_written = true;  // its decoding was validated (still_fit)
  return {std::move(e)};
}

Files encode_dxf_output(const EncodeContext& c) {
  DxfOptions options;
  options.units = c.common.units;
  return {{encode_dxf(c.built.cutting, options), c.common.units, 0.0, ""}};
}

Files encode_svg_output(const EncodeContext& c) {
  SvgOptions options;
  options.units = c.common.units;
  return {{encode_svg(c.built.cutting, options), c.common.units, 0.0, ""}};
}

// The mould's parts in the export unit, as the vessel itself.
std::vector<NamedSoup> exported_parts(const EncodeContext& c) {
  std::vector<NamedSoup> parts = c.built.mould_parts;
  for (NamedSoup& p : parts) {
    for (Vec3& v : p.soup.vertices) v *= c.export_scale;
  }
  return parts;
}

Files encode_mould_stl_output(const EncodeContext& c) {
  Files files;
  const std::vector<NamedSoup> parts = exported_parts(c);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const NamedSoup& p = parts[i];
    Encoded e{encode_stl(p.soup),
              c.common.export_units,
              float32_bound(max_abs_coordinate(p.soup), c.export_scale),
              ".mould-" + p.name + ".stl",
              nullptr,
              std::nullopt};
    prove_as_stored(e, c, "mould_stl", {c.built.mould_parts[i].validation, p.soup, c.export_scale, [&p] {
                                          return soup_in_float32(p.soup);
                                        }});
    files.push_back(std::move(e));
  }
  return files;
}

Files encode_mould_3mf_output(const EncodeContext& c) {
  std::vector<ThreeMfObject> objects;
  double largest = 0.0;
  for (NamedSoup& p : exported_parts(c)) {
    for (const Vec3& v : p.soup.vertices) largest = std::max(largest, v.cwiseAbs().maxCoeff());
    objects.push_back({c.common.name + " mould " + p.name, std::move(p.soup)});
  }
  ThreeMfOptions options;
  options.units = c.common.export_units;
  options.title = c.common.name + " mould";
  Encoded e{encode_3mf(objects, options),
            c.common.export_units,
            threemf_max_error(largest) / c.export_scale,
            "",
            nullptr,
            std::nullopt};
  // Each part as the file stores it: its own object, read back (once, when a part needs it).
  std::optional<std::vector<TriangleSoup>> stored;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    prove_as_stored(e, c, "mould_3mf",
                    {c.built.mould_parts[i].validation, objects[i].soup, c.export_scale, [&, i] {
                       if (!stored) stored = stored_3mf_objects(e.bytes);
                       if (stored->size() != objects.size())
                         throw std::logic_error("mould_3mf: the file lost a part");
                       return (*stored)[i];
                     }});
  }
  return {std::move(e)};
}

Files encode_nc_output(const EncodeContext& c) {
  const GcodeOptions& options = *c.built.gcode;
  return {{encode_gcode(*c.built.toolpath, options), options.units, c.built.toolpath->deviation, ""}};
}

Files encode_toolpath_svg_output(const EncodeContext& c) {
  ToolpathSvgOptions options;
  options.units = c.common.units;
  return {{encode_toolpath_svg(c.built.cutting, *c.built.toolpath, options), c.common.units, 0.0, ""}};
}

Files encode_plot_output(const EncodeContext& c) {
  return {{plot_curves_svg(shape_plot(c.common, c.built.shape)), c.common.units, 0.0, ""}};
}

Files encode_png_output(const EncodeContext& c) {
  PreviewOptions options;
  options.supersample = 2;
  return {{design_preview_png(c.common, c.built, options), c.common.units, 0.0, ""}};
}

// Exact curves as STEP loops, keeping the largest proven bound of an
// approximated piece (0 while every piece is exact).
class StepLoops {
 public:
  explicit StepLoops(double tolerance) : tolerance_(tolerance) {}
  template <class Curve>
  StepLoop operator()(const Curve& curve) {
    try {
      StepLoopOf l = step_loop(curve, tolerance_);
      added_ = std::max(added_, l.max_error);
      return std::move(l.loop);
    } catch (const InputError& e) {
      throw OutputError("step", std::string("step: ") + e.what());
    }
  }
  double added() const { return added_; }

 private:
  double tolerance_;
  double added_ = 0.0;
};

Files step_file(const EncodeContext& c, const StepModel& model, double added) {
  Encoded e;
  e.bytes = write_step(model).bytes;
  e.units = c.common.units;
  e.added_error = added;
  return {std::move(e)};
}

// A surface's B-spline faces as one body: sewn into an open shell (Sheet) or
// a closed one (Closed). Border curves agree to the poles' rounding (about
// 1e-13 of the size).
Files step_faces(const EncodeContext& c, const PatchNetwork& network, std::vector<BSplineFace> faces,
                 StepForm form, double bound, StepModel model) {
  StepBody body;
  body.name = c.common.name;
  body.form = form;
  body.sewing_tolerance = 1e-7 * network.size;
  body.surfaces = std::move(faces);
  model.bodies.push_back(std::move(body));
  return step_file(c, model, bound);
}

// An open surface as one shell of B-spline faces, one per patch, sewn along
// the shared borders: each patch within what the build left of the
// tolerance (geometry/surfaces/bspline_patch.h), the largest bound the file's
// added error. A thickened one as the closed shell of its sheets and walls
// (geometry/surfaces/bspline_shell.h): a sheet on the surface as above, an
// offset sheet through the proven mesh's grid, within the mesh's bound.
Files step_surface_body(const EncodeContext& c, const PatchNetwork& network, StepModel model) {
  const std::optional<ShellGrid>& grid = c.built.shape.shell;
  if (!grid && c.built.purpose == MeshPurpose::Fabrication) {
    throw OutputError("step",
                      "step: the shell's grid was not kept by its build (it did not know a step "
                      "output was asked for)");
  }
  std::vector<BSplineFace> faces;
  double bound = 0.0;
  try {
    if (grid) {
      BSplineShell shell = bspline_shell(network, *grid, c.output_tolerance);
      faces = std::move(shell.faces);
      bound = shell.bound;
    } else {
      BSplineNetwork sheet = bspline_network(network, c.output_tolerance);
      for (std::size_t p = 0; p < sheet.patches.size(); ++p)
        faces.push_back(bspline_face(sheet.patches[p], network.names[p]));
      bound = sheet.max_bound;
    }
  } catch (const InputError& e) {
    throw OutputError("step", std::string("step: ") + e.what());
  }
  return step_faces(c, network, std::move(faces), grid ? StepForm::Closed : StepForm::Sheet, bound,
                    std::move(model));
}

// The exact solid (or, for a curve design, its curves; for an open surface
// its patches) in the design's unit. Exact segments stay exact; an H-Bézier
// segment becomes a cubic B-spline within what the build left of the
// tolerance, and that bound is the file's added error.
Files encode_step_output(const EncodeContext& c) {
  StepModel model;
  model.name = c.common.name;
  model.unit = c.common.units;
  if (const auto& network = c.built.shape.patches) return step_surface_body(c, *network, std::move(model));
  StepLoops loop_of(c.output_tolerance);
  StepBody body;
  body.name = c.common.name;
  if (const auto& solid = c.built.shape.solid) {
    body.height = solid->height;
    if (solid->form == ExactSolid::Form::Extrusion) {
      body.form = StepForm::Extrusion;
      for (const std::vector<ExactPiece>& loop : solid->loops) body.loops.push_back(loop_of(loop));
    } else {
      // A solid per loop: a profile that runs along the axis between parts makes one per part.
      body.form = StepForm::Revolution;
      for (std::size_t i = 0; i < solid->loops.size(); ++i) {
        StepBody part = body;
        if (solid->loops.size() > 1) part.name += fmt::format(" part {}", i + 1);
        part.loops.push_back(loop_of(solid->loops[i]));
        model.bodies.push_back(std::move(part));
      }
      return step_file(c, model, loop_of.added());
    }
  } else if (!c.built.soup.triangles.empty()) {
    throw OutputError("step", "step: a shell whose profile runs along the axis is not written as STEP yet");
  } else {
    body.form = StepForm::Wireframe;
    for (const NamedBuiltCurve& curve : c.built.shape.curves)
      body.loops.push_back(loop_of(curve.curve.curve));
  }
  model.bodies.push_back(std::move(body));
  return step_file(c, model, loop_of.added());
}

// The mould's parts as exact solids, one product each, in the design's unit:
// OpenCASCADE takes the revolved cavity and the sockets from each block and
// adds the bumps. When the cavity is exact, the parts' volumes together must
// be the exact plaster volume (block - cavity + bumps - sockets) within
// OpenCASCADE's integration: a boolean operation that lost the cavity or a
// key (a key is about 1e-4 of a mould) would show there.
Files encode_mould_step_output(const EncodeContext& c) {
  const ExactMould& mould = *c.built.shape.mould;
  StepModel model;
  model.name = c.common.name + " mould";
  model.unit = c.common.units;
  StepLoops loop_of(c.output_tolerance);
  const StepLoop cavity = loop_of(mould.cavity);
  for (const ExactMould::Part& part : mould.parts) {
    StepBody body;
    body.name = c.common.name + " mould " + part.name;
    body.form = StepForm::Carved;
    body.loops = {cavity};
    body.block = {mould.box, mould.block_radius, part.z_low, part.z_high, part.from_angle, part.to_angle};
    for (const ExactMould::Key& k : part.keys)
      body.hemispheres.push_back({k.centre, k.axis, k.radius, k.bump});
    model.bodies.push_back(std::move(body));
  }
  const StepWritten written = write_step(model);
  double volume = 0.0;
  for (const StepShapeFacts& f : written.bodies) volume += f.volume;
  if (loop_of.added() == 0.0 && !(std::abs(volume - mould.volume) <= 1e-6 * std::abs(mould.volume))) {
    throw OutputError("step",
                      fmt::format("step: the mould's parts as OpenCASCADE built them hold {:.9g} {}^3 "
                                  "of plaster, not the exact {:.9g}; nothing is written",
                                  volume, c.common.units, mould.volume));
  }
  Encoded e;
  e.bytes = written.bytes;
  e.units = c.common.units;
  e.added_error = loop_of.added();
  return {std::move(e)};
}

std::vector<OutputFormat> make_table() {
  const KindSet meshes = kinds<VesselDesign, CountertopDesign, SurfaceDesign>();
  const KindSet drawn = kinds<CurveDesign, VesselDesign, CountertopDesign>();
  const KindSet vessels = kinds<VesselDesign>(), countertops = kinds<CountertopDesign>();
  const KindSet every = kinds<CurveDesign, VesselDesign, CountertopDesign, SurfaceDesign>();
  const OutputContent mesh = OutputContent::Triangles, drawing = OutputContent::Drawing,
                      mould = OutputContent::MouldParts, toolpath = OutputContent::Toolpath;
  return {
      {"stl", "binary STL mesh, in the export unit", mesh, meshes, meshes, ".stl", &encode_stl_output},
      {"drc", "Draco compressed mesh in the export unit, decoded and validated before writing", mesh, meshes,
       meshes, ".drc", &encode_drc_output},
      {"3mf",
       "3MF, the slicers' format: one object, the export unit recorded in the file",
       mesh,
       meshes,
       {},
       ".3mf",
       &encode_3mf_output},
      {"glb",
       "binary glTF for viewers and the web: metres, Y up",
       mesh,
       meshes,
       {},
       ".glb",
       &encode_glb_output},
      {"glb_draco",
       "binary glTF with Draco compression (KHR_draco_mesh_compression): metres, Y up",
       mesh,
       meshes,
       {},
       ".draco.glb",
       &encode_glb_draco_output},
      {"obj",
       "Wavefront OBJ mesh in the export unit, exact decimals",
       mesh,
       meshes,
       {},
       ".obj",
       &encode_obj_output},
      {"ply", "binary PLY mesh in the export unit, float32", mesh, meshes, {}, ".ply", &encode_ply_output},
      {"off", "OFF mesh in the export unit, exact decimals", mesh, meshes, {}, ".off", &encode_off_output},
      {"dxf",
       "true-size drawing with exact lines, arcs and ellipses, in the design's unit: a countertop's cutting "
       "outline, a vessel's profile template, a curve",
       drawing, drawn, drawn, ".dxf", &encode_dxf_output},
      {"svg", "the same drawing as SVG, exact arcs, true size", drawing, drawn, drawn, ".svg",
       &encode_svg_output},
      {"mould_stl", "one STL per part of the vessel's slip-casting mould, in the export unit", mould, vessels,
       vessels, ".mould-PART.stl", &encode_mould_stl_output},
      {"mould_3mf", "the mould's parts as separate objects of one 3MF", mould, vessels, vessels, ".mould.3mf",
       &encode_mould_3mf_output},
      {"mould_step",
       "STEP (AP214) of the mould's parts as exact solids with their keys, in the design's unit",
       mould,
       vessels,
       {},
       ".mould.step",
       &encode_mould_step_output},
      {"nc", "RS-274 G-code of the countertop's router path (key cnc), G21/G20 as asked", toolpath,
       countertops, countertops, ".nc", &encode_nc_output},
      {"toolpath_svg", "drawing of the router path over the outline", toolpath, countertops, countertops,
       ".toolpath.svg", &encode_toolpath_svg_output},
      {"step",
       "STEP (AP214) of the exact geometry in the design's unit: a countertop's or a vessel's solid, a "
       "curve's wireframe, a surface's patches as B-spline faces sewn into one shell (closed: a thickened "
       "surface's solid)",
       OutputContent::Exact,
       every,
       {},
       ".step",
       &encode_step_output},
      {"plot",
       "the design's curves with control polygons, joints, curvature combs and curvature plot (SVG)",
       OutputContent::Design,
       every,
       {},
       ".plot.svg",
       &encode_plot_output},
      {"png",
       "a shaded three-quarter preview of the mesh (PNG)",
       mesh,
       meshes,
       {},
       ".png",
       &encode_png_output},
  };
}

std::string kind_list(const KindSet& set) {
  std::string out;
  const std::vector<std::string> names = kind_names();
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (set.test(i)) out += (out.empty() ? "" : ", ") + names[i];
  }
  return out;
}

}  // namespace

double writing_error_bound(std::string_view format, double largest, double export_scale) {
  const double exported = largest * export_scale;
  if (format == "stl" || format == "ply" || format == "mould_stl")
    return float32_bound(exported, export_scale);
  if (format == "glb") return float32_bound(largest, 1.0);
  if (format == "3mf" || format == "mould_3mf") return threemf_bound(exported, export_scale);
  if (format == "obj" || format == "off") return decimal_bound(exported, export_scale);
  // Draco measures its own; its decoded positions are float32, and the fewest
  // bits that fit round about as much again: a share to keep, not a bound.
  if (format == "drc") return 2.0 * float32_bound(exported, export_scale);
  if (format == "glb_draco") return 2.0 * float32_bound(largest, 1.0);
  return 0.0;
}

bool has_content(const Design& design, OutputContent content) {
  switch (content) {
    case OutputContent::Triangles:
      return !std::holds_alternative<CurveDesign>(design.body);
    case OutputContent::Drawing:
      return !std::holds_alternative<SurfaceDesign>(design.body);
    case OutputContent::MouldParts: {
      const auto* v = std::get_if<VesselDesign>(&design.body);
      return v != nullptr && v->mould.has_value();
    }
    case OutputContent::Design:
    case OutputContent::Exact:
      return true;
    case OutputContent::Toolpath: {
      const auto* c = std::get_if<CountertopDesign>(&design.body);
      return c != nullptr && c->cnc.has_value();
    }
  }
  return false;
}

const std::vector<OutputFormat>& output_formats() {
  static const std::vector<OutputFormat> table = make_table();
  return table;
}

const OutputFormat* find_output_format(std::string_view name) {
  const auto& table = output_formats();
  const auto it =
      std::find_if(table.begin(), table.end(), [&](const OutputFormat& f) { return f.name == name; });
  return it == table.end() ? nullptr : &*it;
}

std::vector<const OutputFormat*> resolve_outputs(const Design& design) {
  const std::size_t kind = design.body.index();
  std::vector<const OutputFormat*> out;
  if (design.common.outputs.empty()) {
    for (const OutputFormat& f : output_formats()) {
      if (f.default_for.test(kind) && has_content(design, f.content)) out.push_back(&f);
    }
    return out;
  }
  for (const OutputRequest& r : design.common.outputs) {
    const OutputFormat* format = find_output_format(r.format);
    if (format == nullptr) {
      std::string names;
      for (const OutputFormat& f : output_formats())
        names += (names.empty() ? "" : ", ") + std::string(f.name);
      throw FileError(design.common.path, r.line, r.column,
                      fmt::format("{}: '{}' is not one of: {}", r.where, r.format, names));
    }
    if (!format->kinds.test(kind)) {
      throw FileError(
          design.common.path, r.line, r.column,
          fmt::format("{}: {} ({}) is made for {} designs, not for a {} design", r.where, r.format,
                      format->description, kind_list(format->kinds), kind_name(design)));
    }
    if (!has_content(design, format->content)) {
      const char* needs = format->content == OutputContent::MouldParts ? "a `mould:` section"
                          : format->content == OutputContent::Toolpath ? "a `cnc:` section"
                                                                       : "a curve, a vessel or a countertop";
      throw FileError(design.common.path, r.line, r.column,
                      fmt::format("{}: {} needs {}", r.where, r.format, needs));
    }
    if (std::find(out.begin(), out.end(), format) != out.end()) {
      throw FileError(design.common.path, r.line, r.column,
                      fmt::format("{}: {} is listed twice", r.where, r.format));
    }
    out.push_back(format);
  }
  return out;
}

const OutputFormat* format_of_file(const std::string& name) {
  std::string path = name;
  std::transform(path.begin(), path.end(), path.begin(),
                 [](unsigned char c) { return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c); });
  const OutputFormat* best = nullptr;
  for (const OutputFormat& f : output_formats()) {
    const std::string_view suffix = f.file_suffix;
    if (path.size() > suffix.size() &&
        path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0 &&
        (best == nullptr || suffix.size() > best->file_suffix.size())) {
      best = &f;
    }
  }
  return best;
}

}  // namespace fabmesh
