#include "io/cutting/svg.h"

#include <fmt/format.h>

#include "io/cutting/svg_writing.h"

namespace fabmesh {

std::string encode_svg(const std::vector<CutLoop>& loops, const SvgOptions& options) {
  const auto [lo, hi] = cut_bounds(loops);
  std::string out = svg_start(lo, hi, options.margin, options.units);
  std::size_t holes = 0;
  for (const CutLoop& loop : loops) {
    std::string d;
    append_svg_loop(d, loop);
    if (loop.closed) d += " Z";
    const std::string id = loop.outer ? std::string("outline") : fmt::format("hole{}", holes++);
    out += fmt::format("  <path id=\"{}\" d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"0.5\"/>\n", id,
                       d, loop.outer ? "red" : "blue");
  }
  out += "</svg>\n";
  return out;
}

}  // namespace fabmesh
