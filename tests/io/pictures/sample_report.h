#pragma once
// Test helper: a sample report of real designs from configs/examples (two
// vessels and a countertop, built with the geometry library) plus a design
// that failed to read, with their STL files, previews and plots written
// beside the page.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>

#include "geometry/curves/curve_spec.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/slab.h"
#include "geometry/mesh/vessel.h"
#include "io/design/read_design.h"
#include "io/mesh/stl.h"
#include "io/pictures/curve_plot.h"
#include "io/pictures/html_report.h"
#include "io/pictures/png.h"
#include "io/pictures/preview.h"

namespace fabmesh::test {

/// Volume and area of a closed, outward-oriented soup (divergence theorem).
inline std::pair<double, double> volume_and_area(const TriangleSoup& soup) {
  double volume = 0.0, area = 0.0;
  for (const auto& t : soup.triangles) {
    const Vec3 &a = soup.vertices[t[0]], &b = soup.vertices[t[1]], &c = soup.vertices[t[2]];
    volume += a.dot(b.cross(c)) / 6.0;
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return {volume, area};
}

/// Writes the row's STL, preview PNG and plot SVG into `dir` and fills in its measures.
inline ReportRow sample_row(const std::string& dir, const Design& design, const TriangleSoup& soup,
                            const CurvePlot& plot, double seconds) {
  ReportRow row;
  row.name = design.common.name;
  row.kind = kind_name(design);
  row.units = design.common.units;
  row.status = ReportStatus::Ok;
  row.message = "valid: closed, oriented, no self-intersections";
  const auto [volume, area] = volume_and_area(soup);
  row.volume = volume;
  row.area = area;
  row.max_deviation = design.common.tolerance;
  Vec3 lo = soup.vertices.front(), hi = lo;
  for (const Vec3& v : soup.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  row.bbox = std::array<Vec3, 2>{lo, hi};
  row.triangles = soup.triangles.size();
  const auto t0 = std::chrono::steady_clock::now();
  write_stl(soup, dir + "/" + row.name + ".stl");
  PreviewOptions preview;
  preview.views = 2;
  preview.supersample = 2;
  std::ofstream(dir + "/" + row.name + ".png", std::ios::binary) << encode_png(render_preview(soup, preview));
  std::ofstream(dir + "/" + row.name + ".svg", std::ios::binary) << plot_curves_svg(plot);
  const double write = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  row.timings = {{"build", seconds}, {"pictures", write}};
  row.files = {row.name + ".stl", row.name + ".png", row.name + ".svg"};
  row.preview_png = row.name + ".png";
  row.plot_svg = row.name + ".svg";
  return row;
}

inline ReportRow vessel_row(const std::string& dir, const std::string& example) {
  const Design design = read_design(std::string(FABMESH_SOURCE_DIR) + "/configs/examples/" + example);
  const auto& vessel = std::get<VesselDesign>(design.body);
  const auto t0 = std::chrono::steady_clock::now();
  VesselOptions options;
  options.mode = vessel.mode;
  options.wall = vessel.wall;
  options.base = vessel.base;
  options.tolerance = design.common.tolerance;
  CurvePlot plot;
  plot.title = design.common.name + ": profile (radius, height)";
  plot.units = design.common.units;
  plot.curves.push_back(plot_curve(build_curve(vessel.profile), "profile"));
  const TriangleSoup soup = build_vessel(plot.curves[0].curve, options).soup;
  return sample_row(dir, design, soup, plot,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

inline ReportRow countertop_row(const std::string& dir, const std::string& example) {
  const Design design = read_design(std::string(FABMESH_SOURCE_DIR) + "/configs/examples/" + example);
  const auto& top = std::get<CountertopDesign>(design.body);
  const auto t0 = std::chrono::steady_clock::now();
  CurvePlot plot;
  plot.title = design.common.name + ": outline and cut-outs";
  plot.units = design.common.units;
  plot.curves.push_back(plot_curve(build_curve(top.outline), "outline"));
  std::vector<RegionHole> holes;
  for (std::size_t i = 0; i < top.holes.size(); ++i) {
    const std::string label = "holes[" + std::to_string(i) + "] (" + top.holes[i].shape + ")";
    plot.curves.push_back(plot_curve(build_curve(top.holes[i].curve), label));
    holes.push_back({plot.curves.back().curve, label});
  }
  RegionOptions region;
  region.tolerance = design.common.tolerance;
  SlabOptions slab;
  slab.thickness = top.thickness;
  const TriangleSoup soup = to_soup(build_slab(build_region(plot.curves[0].curve, holes, region), slab).mesh);
  return sample_row(dir, design, soup, plot,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

/// The sample report, its files written into `dir` (created if missing).
inline HtmlReport sample_report(const std::string& dir) {
  std::filesystem::create_directories(dir);
  HtmlReport report;
  report.title = "fabmesh sample report";
  report.generated_by = "fabmesh tests (io/pictures)";
  report.rows.push_back(vessel_row(dir, "vessel_golden_shell.yaml"));
  report.rows.push_back(countertop_row(dir, "countertop_g2_fair_cv.yaml"));
  report.rows.push_back(vessel_row(dir, "vessel_fair_strain_shell.yaml"));
  ReportRow bad;
  bad.name = "broken <design> & \"quotes\"";
  bad.kind = "vessel";
  bad.status = ReportStatus::BadInput;
  bad.message = "broken.yaml:6:7: profile.lambdas[1]: lambda = 1.7 is outside [-8, 1]";
  bad.units = "cm";
  report.rows.push_back(bad);
  return report;
}

}  // namespace fabmesh::test
