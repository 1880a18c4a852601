// The drawings (at true size, in the design's unit), the router program and
// the pictures of a design.

#include <stdexcept>
#include <type_traits>
#include <variant>

#include "io/cutting/dxf.h"
#include "io/cutting/gcode.h"
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

Encoded drawn(std::string bytes, const EncodeContext& c) {
  Encoded e;
  e.bytes = std::move(bytes);
  e.units = c.common.units;
  return e;
}

}  // namespace

EncodedFiles encode_dxf_output(const EncodeContext& c) {
  DxfOptions options;
  options.units = c.common.units;
  return {drawn(encode_dxf(drawing_of(c.result), options), c)};
}

EncodedFiles encode_svg_output(const EncodeContext& c) {
  SvgOptions options;
  options.units = c.common.units;
  return {drawn(encode_svg(drawing_of(c.result), options), c)};
}

EncodedFiles encode_nc_output(const EncodeContext& c) {
  const auto& countertop = std::get<CountertopProducts>(c.result.products);
  const GcodeOptions& options = *countertop.gcode;
  Encoded e = drawn(encode_gcode(*countertop.toolpath, options), c);
  e.units = options.units;
  e.added_error = countertop.toolpath->deviation;
  return {std::move(e)};
}

EncodedFiles encode_toolpath_svg_output(const EncodeContext& c) {
  const auto& countertop = std::get<CountertopProducts>(c.result.products);
  ToolpathSvgOptions options;
  options.units = c.common.units;
  return {drawn(encode_toolpath_svg(countertop.cutting, *countertop.toolpath, options), c)};
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
