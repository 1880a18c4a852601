// The drawings (at true size, in the design's unit), the router program and
// the pictures of a design.

#include <fmt/format.h>

#include <stdexcept>
#include <type_traits>
#include <variant>

#include "geometry/core/errors.h"
#include "io/cutting/dxf.h"
#include "io/cutting/gcode.h"
#include "io/cutting/layout.h"
#include "io/cutting/shop_drawing.h"
#include "io/cutting/svg.h"
#include "io/cutting/toolpath_svg.h"
#include "pipeline/encoders/encoding.h"
#include "pipeline/pictures.h"

namespace fabmesh {
namespace {

// The drawing of a design at true size: a curve's curve, a vessel's profile
// template, a countertop's cutting outline. A surface has none (the output
// table gives drawings to the other kinds only).
const std::vector<CutLoop>& drawing_of(const Result& result) {
  return std::visit(
      [](const auto& products) -> const std::vector<CutLoop>& {
        using Products = std::decay_t<decltype(products)>;
        if constexpr (std::is_same_v<Products, CurveProducts>) {
          return products.drawing;
        } else if constexpr (std::is_same_v<Products, VesselProducts>) {
          return products.profile_template;
        } else if constexpr (std::is_same_v<Products, CountertopProducts>) {
          return products.cutting;
        } else {
          static_assert(std::is_same_v<Products, SurfaceProducts>, "a kind without a drawing rule");
          throw std::logic_error("a surface has no drawing");
        }
      },
      result.products);
}

}  // namespace

std::vector<RouterProgram> router_programs(const CountertopProducts& countertop) {
  if (!countertop.kitchen) return {{&*countertop.toolpath, countertop.cutting, "", {}}};
  const KitchenProducts& k = *countertop.kitchen;
  std::vector<RouterProgram> out;
  for (std::size_t s = 0; s < k.slab_toolpaths.size(); ++s) {
    RouterProgram p{&k.slab_toolpaths[s], {}, fmt::format(".slab-{}", s + 1), {}};
    for (const Placement& at : k.nesting.placements) {
      if (at.slab != s) continue;
      const KitchenPiece& piece = k.split.pieces[at.piece];
      p.parts.push_back(piece.name);
      for (const auto& hole : piece.holes) {
        p.part.push_back(polygon_loop(place_loop(hole, at), piece.name + " cut-out", false));
      }
      p.part.push_back(polygon_loop(at.outer, piece.name, true));
    }
    out.push_back(std::move(p));
  }
  return out;
}

namespace {

const KitchenProducts& kitchen_of(const EncodeContext& c) {
  const auto& countertop = std::get<CountertopProducts>(c.result.products);
  if (!countertop.kitchen) throw std::logic_error("a kitchen output of a countertop without a slab");
  return *countertop.kitchen;
}

LayoutOptions layout_options(const EncodeContext& c) {
  LayoutOptions options;
  options.units = c.common.units;
  options.title = c.common.name;
  return options;
}

// Each piece's exact drawing, or none where its outline has none (the sheets draw its polygons).
std::vector<std::vector<CutLoop>> exact_drawings(const KitchenProducts& k) {
  std::vector<std::vector<CutLoop>> out;
  out.reserve(k.exact.size());
  for (const KitchenProducts::Exact& e : k.exact) out.push_back(e.solid ? e.drawing : std::vector<CutLoop>{});
  return out;
}

Encoded drawn(std::string bytes, const EncodeContext& c) {
  Encoded e;
  e.bytes = std::move(bytes);
  e.units = c.common.units;
  return e;
}

// The design's drawing written by `encode`, or a kitchen's: one file per
// piece (NAME.piece-1.dxf), its exact outline and cut-outs.
template <class Encode>
EncodedFiles each_drawing(const EncodeContext& c, const std::string& format, Encode encode) {
  const auto* countertop = std::get_if<CountertopProducts>(&c.result.products);
  if (countertop == nullptr || !countertop->kitchen) return {drawn(encode(drawing_of(c.result)), c)};
  const KitchenProducts& k = *countertop->kitchen;
  EncodedFiles files;
  for (std::size_t i = 0; i < k.exact.size(); ++i) {
    if (!k.exact[i].solid) throw OutputError(format, format + ": " + k.exact[i].why_not);
    const std::string& piece = k.split.pieces[i].name;
    Encoded e = drawn(encode(k.exact[i].drawing), c);
    e.suffix = fmt::format(".{}.{}", piece, format);
    e.parts = {piece};
    files.push_back(std::move(e));
  }
  return files;
}

}  // namespace

EncodedFiles encode_dxf_output(const EncodeContext& c) {
  DxfOptions options;
  options.units = c.common.units;
  return each_drawing(c, "dxf",
                      [&](const std::vector<CutLoop>& loops) { return encode_dxf(loops, options); });
}

EncodedFiles encode_svg_output(const EncodeContext& c) {
  SvgOptions options;
  options.units = c.common.units;
  return each_drawing(c, "svg",
                      [&](const std::vector<CutLoop>& loops) { return encode_svg(loops, options); });
}

EncodedFiles encode_nc_output(const EncodeContext& c) {
  const auto& countertop = std::get<CountertopProducts>(c.result.products);
  const GcodeOptions& options = *countertop.gcode;
  EncodedFiles files;
  for (const RouterProgram& p : router_programs(countertop)) {
    Encoded e = drawn(encode_gcode(*p.path, options), c);
    e.units = options.units;
    e.added_error = p.path->deviation;
    e.suffix = p.suffix.empty() ? "" : p.suffix + ".nc";
    e.parts = p.parts;
    files.push_back(std::move(e));
  }
  return files;
}

EncodedFiles encode_toolpath_svg_output(const EncodeContext& c) {
  const auto& countertop = std::get<CountertopProducts>(c.result.products);
  ToolpathSvgOptions options;
  options.units = c.common.units;
  EncodedFiles files;
  for (const RouterProgram& p : router_programs(countertop)) {
    Encoded e = drawn(encode_toolpath_svg(p.part, *p.path, options), c);
    e.suffix = p.suffix.empty() ? "" : p.suffix + ".toolpath.svg";
    e.parts = p.parts;
    files.push_back(std::move(e));
  }
  return files;
}

EncodedFiles encode_layout_svg_output(const EncodeContext& c) {
  const KitchenProducts& k = kitchen_of(c);
  return {drawn(encode_layout_svg(k.split.pieces, k.stock, k.nesting, layout_options(c)), c)};
}

EncodedFiles encode_layout_dxf_output(const EncodeContext& c) {
  const KitchenProducts& k = kitchen_of(c);
  DxfOptions options;
  options.units = c.common.units;
  return {drawn(
      encode_dxf_sheet(layout_sheet(k.split.pieces, exact_drawings(k), k.stock, k.nesting, layout_options(c)),
                       options),
      c)};
}

EncodedFiles encode_shop_dxf_output(const EncodeContext& c) {
  const KitchenProducts& k = kitchen_of(c);
  DxfOptions options;
  options.units = c.common.units;
  return {
      drawn(encode_dxf_sheet(shop_sheet(k.split.pieces, exact_drawings(k), layout_options(c)), options), c)};
}

EncodedFiles encode_shop_svg_output(const EncodeContext& c) {
  const KitchenProducts& k = kitchen_of(c);
  return {drawn(encode_sheet_svg(shop_sheet(k.split.pieces, exact_drawings(k), layout_options(c)),
                                 c.common.units, c.common.name + " shop drawing"),
                c)};
}

EncodedFiles encode_cutlist_output(const EncodeContext& c) {
  const KitchenProducts& k = kitchen_of(c);
  return {drawn(encode_cutlist(k.split.pieces, k.nesting, layout_options(c)), c)};
}

EncodedFiles encode_plot_output(const EncodeContext& c) {
  return {drawn(plot_curves_svg(shape_plot(c.common, c.result)), c)};
}

EncodedFiles encode_png_output(const EncodeContext& c) {
  PreviewOptions options;
  options.supersample = 2;
  return {drawn(design_preview_png(c.common, c.result, options), c)};
}

}  // namespace fabmesh
