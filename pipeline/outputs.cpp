#include "pipeline/outputs.h"

#include <fmt/format.h>

#include <algorithm>

#include "geometry/core/errors.h"
#include "io/cutting/dxf.h"
#include "io/cutting/svg.h"
#include "io/mesh/draco.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/stl.h"

namespace fabmesh {
namespace {

std::string encode_stl_output(const EncodeContext& c) { return encode_stl(c.built.soup); }
std::string encode_obj_output(const EncodeContext& c) { return encode_obj(c.built.soup); }
std::string encode_ply_output(const EncodeContext& c) { return encode_ply(c.built.soup); }
std::string encode_off_output(const EncodeContext& c) { return encode_off(c.built.soup); }

// Quantization may collapse or fold faces: the decoded mesh is validated too.
std::string encode_drc_output(const EncodeContext& c) {
  DracoOptions options;
  options.tolerance = c.output_tolerance;
  const MeshPurpose purpose = c.built.purpose;
  return encode_draco_accepted(
      c.built.soup, options,
      [purpose](const TriangleSoup& decoded) { return fit_for(validate(decoded), purpose); }, c.path);
}

std::string encode_dxf_output(const EncodeContext& c) {
  DxfOptions options;
  options.units = c.common.units;
  return encode_dxf(c.built.cutting, options);
}

std::string encode_svg_output(const EncodeContext& c) {
  SvgOptions options;
  options.units = c.common.units;
  return encode_svg(c.built.cutting, options);
}

std::vector<OutputFormat> make_table() {
  const KindSet meshes = kinds<VesselDesign, CountertopDesign, SurfaceDesign>();
  const KindSet cutting = kinds<CountertopDesign>();
  const OutputContent mesh = OutputContent::Triangles, outline = OutputContent::CuttingOutline;
  return {
      {"stl", "binary STL triangle mesh", mesh, meshes, meshes, &encode_stl_output},
      {"drc", "Draco compressed mesh, decoded and validated before writing", mesh, meshes, meshes,
       &encode_drc_output},
      {"obj", "Wavefront OBJ mesh", mesh, meshes, {}, &encode_obj_output},
      {"ply", "binary PLY mesh", mesh, meshes, {}, &encode_ply_output},
      {"off", "OFF mesh", mesh, meshes, {}, &encode_off_output},
      {"dxf", "cutting outline for CNC with exact lines, arcs and ellipses", outline, cutting, cutting,
       &encode_dxf_output},
      {"svg", "cutting outline drawing with exact arcs", outline, cutting, cutting, &encode_svg_output},
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
    const auto& table = output_formats();
    const auto it =
        std::find_if(table.begin(), table.end(), [&](const OutputFormat& f) { return f.name == r.format; });
    if (it == table.end()) {
      std::string names;
      for (const OutputFormat& f : table) names += (names.empty() ? "" : ", ") + std::string(f.name);
      throw FileError(design.common.path, r.line, r.column,
                      fmt::format("{}: '{}' is not one of: {}", r.where, r.format, names));
    }
    if (!it->kinds.test(kind)) {
      throw FileError(design.common.path, r.line, r.column,
                      fmt::format("{}: {} ({}) is made for {} designs, not for a {} design", r.where,
                                  r.format, it->description, kind_list(it->kinds), kind_name(design)));
    }
    if (std::find(out.begin(), out.end(), &*it) != out.end()) {
      throw FileError(design.common.path, r.line, r.column,
                      fmt::format("{}: {} is listed twice", r.where, r.format));
    }
    out.push_back(&*it);
  }
  return out;
}

}  // namespace fabmesh
