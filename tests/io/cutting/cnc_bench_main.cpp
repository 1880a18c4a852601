// fabmesh_cnc_bench: the fabmesh side of bench/gcode_vs_dxf2gcode.sh.
//
//   fabmesh_cnc_bench program DESIGN.yaml PREFIX [TABS]
//       writes PREFIX.nc (fabmesh's router program: 12 mm tool, the slab's
//       thickness in 10 mm passes, TABS tabs, default 0) and PREFIX.dxf (the
//       cutting outline as `fabmesh run` writes it)
//   fabmesh_cnc_bench measure DESIGN.yaml PROGRAM.nc
//       runs PROGRAM.nc through the CNCjs interpreter and prints one JSON
//       line: its line counts and, for the moves at the final depth, the
//       largest deviation of the tool centre from the exact offset of the
//       design's exact curves (a proven upper bound: samples every 5 um plus
//       half a step) and the least clearance (distance to the part - radius).

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "geometry/toolpath/toolpath.h"
#include "io/cutting/dxf.h"
#include "io/cutting/gcode.h"
#include "io/file.h"
#include "tests/io/cutting/gcode_checks.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

constexpr double kTool = 12.0;

ExampleRegion load(const std::string& path) { return load_countertop_example(path); }

int program(const std::string& design, const std::string& prefix, std::size_t tabs) {
  const ExampleRegion region = load(design);
  CncOptions o;
  o.tool_diameter = kTool;
  o.depth = region.thickness;
  o.tolerance = region.tolerance;
  o.tabs.count = tabs;
  const Toolpath tp = plan_toolpath(region.outline, region.holes, o);
  GcodeOptions g;
  g.name = region.name;
  write_gcode(prefix + ".nc", tp, g);
  // The cutting outline as the pipeline writes it: each loop in the region's orientation.
  RegionOptions ro;
  ro.tolerance = region.tolerance;
  const Region2 r = build_region(region.outline, region.holes, ro);
  CutLoopOptions co;
  co.tolerance = region.tolerance;
  co.reverse = r.reversed[0];
  std::vector<CutLoop> loops{cut_loop(region.outline, "outline", true, co)};
  for (std::size_t i = 0; i < region.holes.size(); ++i) {
    co.reverse = r.reversed[i + 1];
    loops.push_back(cut_loop(region.holes[i].curve, region.holes[i].label, false, co));
  }
  write_file_atomically(prefix + ".dxf", encode_dxf(loops));
  return 0;
}

int measure(const std::string& design, const std::string& file) {
  const ExampleRegion region = load(design);
  const double r = 0.5 * kTool, step = 0.005;
  std::vector<CurveDistance> exact{CurveDistance(region.outline, 0.5)};
  for (const RegionHole& h : region.holes) exact.emplace_back(h.curve, 0.5);

  std::ifstream in(file);
  std::size_t lines = 0, motion_lines = 0;
  for (std::string line; std::getline(in, line);) {
    ++lines;
    const std::string code = line.substr(0, line.find('('));
    if (code.find_first_of("XYZ") != std::string::npos) ++motion_lines;
  }
  const Trace trace = interpret_gcode_file(file);
  double deepest = 0.0;
  for (const TraceMotion& m : trace.motions) deepest = std::min(deepest, std::min(m.start.z(), m.end.z()));
  double worst = 0.0, least = INFINITY, length = 0.0;
  std::size_t arcs = 0, linears = 0;
  for (const TraceMotion& m : trace.motions) {
    const bool level = std::abs(m.start.z() - deepest) < 0.01 && std::abs(m.end.z() - deepest) < 0.01;
    if (!level || m.motion == "G0" || m.comment == "lead in" || m.comment == "lead out") continue;
    const double len = motion_length(m);
    if (len == 0.0) continue;
    (m.arc ? arcs : linears) += 1;
    length += len;
    // The loop this move cuts: the nearest at its middle.
    const Vec2 mid = motion_point(m, 0.5).head<2>();
    std::size_t loop = 0;
    double best = INFINITY;
    for (std::size_t l = 0; l < exact.size(); ++l) {
      const double d = exact[l].nearest(mid, 50.0).distance;
      if (d < best) best = d, loop = l;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int k = 0; k <= n; ++k) {
      const Vec2 p = motion_point(m, static_cast<double>(k) / n).head<2>();
      const double dev = std::abs(exact[loop].nearest(p, 2 * r).distance - r);
      if (dev > worst && std::getenv("FABMESH_CNC_BENCH_WHERE")) {
        std::cerr << fmt::format("deviation {} at ({}, {}) loop {} line {}\n", dev, p.x(), p.y(), loop,
                                 m.line);
      }
      worst = std::max(worst, dev);
      double d = INFINITY;
      for (const CurveDistance& e : exact) d = std::min(d, e.nearest(p, r + 1.0).distance);
      least = std::min(least, d - r);
    }
  }
  std::cout << fmt::format(
      "{{\"lines\": {}, \"motion_lines\": {}, \"depth\": {}, \"moves_at_depth\": {}, \"arcs_at_depth\": {}, "
      "\"length_at_depth\": {:.3f}, \"max_deviation\": {:.6f}, \"least_clearance\": {:.6f}, \"unknown\": "
      "{}}}\n",
      lines, motion_lines, -deepest, arcs + linears, arcs, length, worst + 0.5 * step, least - 0.5 * step,
      trace.unknown.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string command = argc > 1 ? argv[1] : "";
    if (command == "program" && (argc == 4 || argc == 5)) {
      return program(argv[2], argv[3], argc == 5 ? std::stoul(argv[4]) : 0);
    }
    if (command == "measure" && argc == 4) return measure(argv[2], argv[3]);
    std::cerr << "usage: fabmesh_cnc_bench program DESIGN.yaml PREFIX [TABS]\n"
                 "       fabmesh_cnc_bench measure DESIGN.yaml PROGRAM.nc\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fabmesh_cnc_bench: " << e.what() << "\n";
    return 1;
  }
}
