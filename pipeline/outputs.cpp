#include "pipeline/outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"
#include "io/cutting/dxf.h"
#include "io/cutting/svg.h"
#include "io/mesh/draco.h"
#include "io/mesh/gltf.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/stl.h"
#include "io/mesh/threemf.h"

namespace fabmesh {
namespace {

double max_abs_coordinate(const TriangleSoup& soup) {
  double m = 0.0;
  for (const Vec3& p : soup.vertices) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

// Rounding each coordinate to float32 moves a vertex by at most sqrt(3) 2^-24 max|x|
// (export units); scaling by a double adds at most 2^-52 of it. In model units.
double float32_error(const EncodeContext& c) {
  return std::sqrt(3.0) * (std::ldexp(1.0, -24) + std::ldexp(1.0, -52)) * max_abs_coordinate(c.exported) /
         c.export_scale;
}

// Shortest round-trip decimals are exact; only the scaling to the export unit rounds.
double double_error(const EncodeContext& c) {
  return c.export_scale == 1.0
             ? 0.0
             : std::sqrt(3.0) * std::ldexp(1.0, -52) * max_abs_coordinate(c.exported) / c.export_scale;
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

Encoded encode_stl_output(const EncodeContext& c) {
  return within_tolerance({encode_stl(c.exported), c.common.export_units, float32_error(c)}, c, "stl");
}
Encoded encode_obj_output(const EncodeContext& c) {
  return within_tolerance({encode_obj(c.exported), c.common.export_units, double_error(c)}, c, "obj");
}
Encoded encode_ply_output(const EncodeContext& c) {
  return within_tolerance({encode_ply(c.exported), c.common.export_units, float32_error(c)}, c, "ply");
}
Encoded encode_off_output(const EncodeContext& c) {
  return within_tolerance({encode_off(c.exported), c.common.export_units, double_error(c)}, c, "off");
}

Encoded encode_3mf_output(const EncodeContext& c) {
  ThreeMfOptions options;
  options.units = c.common.export_units;
  options.title = c.common.name;
  const double error = threemf_max_error(max_abs_coordinate(c.exported)) / c.export_scale + double_error(c);
  return within_tolerance({encode_3mf({{c.common.name, c.exported}}, options), c.common.export_units, error},
                          c, "3mf");
}

// Quantization may collapse or fold faces: each candidate's decoded mesh is validated.
std::function<bool(const TriangleSoup&)> still_fit(const EncodeContext& c) {
  const MeshPurpose purpose = c.built.purpose;
  return [purpose](const TriangleSoup& decoded) { return fit_for(validate(decoded), purpose); };
}

Encoded encode_drc_output(const EncodeContext& c) {
  const double tolerance = c.output_tolerance * c.export_scale;  // export units
  const DracoFit fit = fit_draco(c.exported, tolerance, still_fit(c), "drc");
  Encoded out{encode_draco_bits(c.exported, fit.bits), c.common.export_units,
              fit.max_displacement / c.export_scale};
  require_draco_matches(out.bytes, fit);
  return out;
}

GlbOptions glb_options(const EncodeContext& c) {
  GlbOptions options;
  options.name = c.common.name;
  options.scale_to_metres = metres_per_unit(c.common.units);
  return options;
}

Encoded encode_glb_output(const EncodeContext& c) {
  const GlbOptions options = glb_options(c);
  // float32 metres: relative rounding as for STL, of the model's own coordinates.
  const double error =
      std::sqrt(3.0) * (std::ldexp(1.0, -24) + std::ldexp(1.0, -52)) * max_abs_coordinate(c.built.soup);
  return within_tolerance({encode_glb(c.built.soup, options), "m", error}, c, "glb");
}

Encoded encode_glb_draco_output(const EncodeContext& c) {
  GlbOptions options = glb_options(c);
  const TriangleSoup metres = to_gltf_frame(c.built.soup, options.scale_to_metres);
  const DracoFit fit =
      fit_draco(metres, c.output_tolerance * options.scale_to_metres, still_fit(c), "glb_draco");
  options.draco = true;
  options.draco_position_bits = fit.bits;
  return {encode_glb(c.built.soup, options), "m", fit.max_displacement / options.scale_to_metres};
}

Encoded encode_dxf_output(const EncodeContext& c) {
  DxfOptions options;
  options.units = c.common.units;
  return {encode_dxf(c.built.cutting, options), c.common.units, 0.0};
}

Encoded encode_svg_output(const EncodeContext& c) {
  SvgOptions options;
  options.units = c.common.units;
  return {encode_svg(c.built.cutting, options), c.common.units, 0.0};
}

std::vector<OutputFormat> make_table() {
  const KindSet meshes = kinds<VesselDesign, CountertopDesign, SurfaceDesign>();
  const KindSet cutting = kinds<CountertopDesign>();
  const OutputContent mesh = OutputContent::Triangles, outline = OutputContent::CuttingOutline;
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
      {"dxf", "cutting outline for CNC with exact lines, arcs and ellipses, in the design's unit", outline,
       cutting, cutting, ".dxf", &encode_dxf_output},
      {"svg", "cutting outline drawing with exact arcs, true size", outline, cutting, cutting, ".svg",
       &encode_svg_output},
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
      if (f.default_for.test(kind)) out.push_back(&f);
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
    if (std::find(out.begin(), out.end(), format) != out.end()) {
      throw FileError(design.common.path, r.line, r.column,
                      fmt::format("{}: {} is listed twice", r.where, r.format));
    }
    out.push_back(format);
  }
  return out;
}

}  // namespace fabmesh
