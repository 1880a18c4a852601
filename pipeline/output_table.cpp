#include "pipeline/output_table.h"

#include <fmt/format.h>

#include <algorithm>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

// Each format's writing error (OutputFormat::writing_error).
double float32_error(double largest, double scale) { return float32_bound(largest * scale, scale); }
double float32_metres_error(double largest, double /*scale*/) { return float32_bound(largest, 1.0); }
double threemf_error(double largest, double scale) { return threemf_bound(largest * scale, scale); }
double decimal_error(double largest, double scale) { return decimal_bound(largest * scale, scale); }
double draco_share(double largest, double scale) { return 2.0 * float32_bound(largest * scale, scale); }
double draco_metres_share(double largest, double /*scale*/) { return 2.0 * float32_bound(largest, 1.0); }

std::vector<OutputFormat> make_table() {
  const KindSet meshes = kinds<VesselDesign, CountertopDesign, SurfaceDesign>();
  const KindSet drawn = kinds<CurveDesign, VesselDesign, CountertopDesign>();
  const KindSet vessels = kinds<VesselDesign>(), countertops = kinds<CountertopDesign>();
  const KindSet every = kinds<CurveDesign, VesselDesign, CountertopDesign, SurfaceDesign>();
  const OutputSource mesh = OutputSource::Meshes, drawing = OutputSource::Drawing;
  const DesignBlock none = DesignBlock::None, mould = DesignBlock::Mould, cnc = DesignBlock::Cnc,
                    slab = DesignBlock::Slab;
  return {
      {"stl", "binary STL mesh, in the export unit", mesh, none, meshes, meshes, ".stl", &float32_error,
       &encode_stl_output},
      {"drc", "Draco compressed mesh in the export unit, decoded and validated before writing", mesh, none,
       meshes, meshes, ".drc", &draco_share, &encode_drc_output},
      {"3mf",
       "3MF, the slicers' format: one object, the export unit recorded in the file",
       mesh,
       none,
       meshes,
       {},
       ".3mf",
       &threemf_error,
       &encode_3mf_output},
      {"glb",
       "binary glTF for viewers and the web: metres, Y up",
       mesh,
       none,
       meshes,
       {},
       ".glb",
       &float32_metres_error,
       &encode_glb_output},
      {"glb_draco",
       "binary glTF with Draco compression (KHR_draco_mesh_compression): metres, Y up",
       mesh,
       none,
       meshes,
       {},
       ".draco.glb",
       &draco_metres_share,
       &encode_glb_draco_output},
      {"obj",
       "Wavefront OBJ mesh in the export unit, exact decimals",
       mesh,
       none,
       meshes,
       {},
       ".obj",
       &decimal_error,
       &encode_obj_output},
      {"ply",
       "binary PLY mesh in the export unit, float32",
       mesh,
       none,
       meshes,
       {},
       ".ply",
       &float32_error,
       &encode_ply_output},
      {"off",
       "OFF mesh in the export unit, exact decimals",
       mesh,
       none,
       meshes,
       {},
       ".off",
       &decimal_error,
       &encode_off_output},
      {"dxf",
       "true-size drawing with exact lines, arcs and ellipses, in the design's unit: a countertop's cutting "
       "outline, a vessel's profile template, a curve",
       drawing, none, drawn, drawn, ".dxf", nullptr, &encode_dxf_output},
      {"svg", "the same drawing as SVG, exact arcs, true size", drawing, none, drawn, drawn, ".svg", nullptr,
       &encode_svg_output},
      {"mould_stl", "one STL per part of the vessel's slip-casting mould, in the export unit", mesh, mould,
       vessels, vessels, ".mould-PART.stl", &float32_error, &encode_mould_stl_output},
      {"mould_3mf", "the mould's parts as separate objects of one 3MF", mesh, mould, vessels, vessels,
       ".mould.3mf", &threemf_error, &encode_mould_3mf_output},
      {"mould_step",
       "STEP (AP214) of the mould's parts as exact solids with their keys, in the design's unit",
       OutputSource::Exact,
       mould,
       vessels,
       {},
       ".mould.step",
       nullptr,
       &encode_mould_step_output},
      {"master_stl",
       "STL of the vessel's casting master: its outer solid as written (scaled for shrinkage) with the "
       "mould's "
       "spare on its rim, in the export unit",
       mesh,
       none,
       vessels,
       {},
       ".master.stl",
       &float32_error,
       &encode_master_stl_output},
      {"master_3mf",
       "the casting master as one 3MF object, the export unit recorded",
       mesh,
       none,
       vessels,
       {},
       ".master.3mf",
       &threemf_error,
       &encode_master_3mf_output},
      {"master_step",
       "STEP (AP214) of the casting master as an exact solid of revolution, in the design's unit",
       OutputSource::Exact,
       none,
       vessels,
       {},
       ".master.step",
       nullptr,
       &encode_master_step_output},
      {"case_stl",
       "one STL per casting case of the mould's parts (key case): the open box plaster is poured into to "
       "cast that part, in the export unit",
       mesh,
       mould,
       vessels,
       {},
       ".case-PART.stl",
       &float32_error,
       &encode_case_stl_output},
      {"case_3mf",
       "the mould parts' casting cases as separate objects of one 3MF",
       mesh,
       mould,
       vessels,
       {},
       ".case.3mf",
       &threemf_error,
       &encode_case_3mf_output},
      {"case_step",
       "STEP (AP214) of each casting case as an exact solid, in the mould's frame and the design's unit",
       OutputSource::Exact,
       mould,
       vessels,
       {},
       ".case-PART.step",
       nullptr,
       &encode_case_step_output},
      {"nc", "RS-274 G-code of the countertop's router path (key cnc), G21/G20 as asked",
       OutputSource::Program, cnc, countertops, countertops, ".nc", nullptr, &encode_nc_output},
      {"toolpath_svg", "drawing of the router path over the outline", OutputSource::Program, cnc, countertops,
       countertops, ".toolpath.svg", nullptr, &encode_toolpath_svg_output},
      {"layout_svg",
       "a kitchen's slabs at true size with its pieces as nested, their labels and the free area", drawing,
       slab, countertops, countertops, ".layout.svg", nullptr, &encode_layout_svg_output},
      {"layout_dxf",
       "the same layout as DXF: slabs, usable areas, defects, the pieces' exact outlines as placed, seams "
       "and "
       "labels on layers of their own",
       drawing, slab, countertops, countertops, ".layout.dxf", nullptr, &encode_layout_dxf_output},
      {"shop_dxf",
       "a kitchen's shop drawing (DXF): every piece with its dimensions as DIMENSION entities (length, "
       "depth, "
       "cut-out positions and sizes, seam lengths), its label and its edges marked exposed, wall or seam",
       drawing, slab, countertops, countertops, ".shop.dxf", nullptr, &encode_shop_dxf_output},
      {"shop_svg", "the same shop drawing as SVG", drawing, slab, countertops, countertops, ".shop.svg",
       nullptr, &encode_shop_svg_output},
      {"cutlist",
       "a kitchen's cut list (CSV): each piece's slab, position, turn, size, area and edge lengths", drawing,
       slab, countertops, countertops, ".cutlist.csv", nullptr, &encode_cutlist_output},
      {"step",
       "STEP (AP214) of the exact geometry in the design's unit: a countertop's or a vessel's solid, a "
       "curve's wireframe, a surface's patches as B-spline faces sewn into one shell (closed: a thickened "
       "surface's solid)",
       OutputSource::Exact,
       none,
       every,
       {},
       ".step",
       nullptr,
       &encode_step_output},
      {"plot",
       "the design's curves with control polygons, joints, curvature combs and curvature plot (SVG)",
       OutputSource::Curves,
       none,
       every,
       {},
       ".plot.svg",
       nullptr,
       &encode_plot_output},
      {"png",
       "a shaded three-quarter preview of the mesh (PNG)",
       mesh,
       none,
       meshes,
       {},
       ".png",
       nullptr,
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

bool has_block(const Design& design, DesignBlock block) {
  switch (block) {
    case DesignBlock::None:
      return true;
    case DesignBlock::Mould: {
      const auto* v = std::get_if<VesselDesign>(&design.body);
      return v != nullptr && v->mould.has_value();
    }
    case DesignBlock::Cnc: {
      const auto* c = std::get_if<CountertopDesign>(&design.body);
      return c != nullptr && c->cnc.has_value();
    }
    case DesignBlock::Slab: {
      const auto* c = std::get_if<CountertopDesign>(&design.body);
      return c != nullptr && c->kitchen.has_value();
    }
  }
  return false;
}

bool applies_to(const OutputFormat& format, const Design& design) {
  return format.kinds.test(design.body.index()) && has_block(design, format.block);
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
      if (f.default_for.test(kind) && has_block(design, f.block)) out.push_back(&f);
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
    if (!has_block(design, format->block)) {
      const char* needs = format->block == DesignBlock::Mould ? "a `mould:` section"
                          : format->block == DesignBlock::Cnc ? "a `cnc:` section"
                                                              : "a `slab:` section (a kitchen)";
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
