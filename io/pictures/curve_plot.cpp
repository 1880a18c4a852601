#include "io/pictures/curve_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>

#include "geometry/core/error_checks.h"
#include "geometry/sampling/sample_curve.h"
#include "io/pictures/curvature_profile.h"
#include "io/pictures/markup.h"

namespace fabmesh {
namespace {

// Curve colours: the first is the papers' red; none is the control polygons' blue.
constexpr const char* kPalette[] = {"#d62728", "#2ca02c", "#8e44ad", "#8c564b",
                                    "#e377c2", "#ff7f0e", "#17a2b8", "#7f7f00"};
constexpr const char* kPolygonBlue = "#1f4fd0";
constexpr double kTitleBand = 34.0;  // pixels above the panels
constexpr double kLegendLine = 18.0;
constexpr const char* kFlagColour = "#ff2020";  // flags: red, drawn translucent and wide
constexpr double kScaleBand = 48.0;             // pixels under the model: the x coordinates, the scale bar
constexpr double kTickGutter = 48.0;            // pixels left of the model: the y coordinates
constexpr double kTickFont = 10.0;              // pixels
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kJointLabelRows = 3;  // rows of joint labels above the curvature plot

struct Box {
  Vec2 lo = Vec2::Constant(kInfinity), hi = Vec2::Constant(-kInfinity);
  void add(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool empty() const { return !(lo.x() <= hi.x()); }
};

// A curve with everything the picture derives from it.
struct Prepared {
  const PlotCurve* in = nullptr;
  std::vector<JointReport> joints;
  CurvatureProfile profile;
  std::string colour;
  std::vector<std::vector<std::pair<Vec2, Vec2>>> comb;  // per segment: (foot, tip) of each tooth
};

// Where the model panel sits (pixels) and what it shows (viewBox: model x, -model y).
struct ModelFrame {
  double px = 0, py = 0, pw = 0, ph = 0;
  double vx = 0, vy = 0, vw = 0, vh = 0;
  double unit = 1.0;  // model units per pixel
  double grid = 1.0;  // the grid's step, model units
  int decimals = 3;
  std::string num(double v) const { return fixed_number(v, decimals); }
  std::string pt(const Vec2& p) const { return num(p.x()) + "," + num(-p.y()); }
  std::string px_len(double pixels) const { return fixed_number(pixels * unit, decimals + 2); }
};

std::string px(double v) { return fixed_number(v, 2); }

// The largest 1, 2 or 5 times a power of ten that is at most `limit` (> 0).
double nice_step(double limit) {
  const double p = std::pow(10.0, std::floor(std::log10(limit)));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * p <= limit) return m * p;
  }
  return p;
}

void validate(const CurvePlot& plot, const CurvePlotOptions& o) {
  require_in_range("plot width", o.width, 200, 10000);
  require_in_range("plot height", o.height, 150, 10000);
  require_in_range("plot sample_fraction", o.sample_fraction, 1e-9, 0.01);
  require_in_range("plot comb_fraction", o.comb_fraction, 0.0, 1.0);
  require_in_range("plot comb_teeth", o.comb_teeth, 1, 1000);
  require_in_range("plot curvature_samples", o.curvature_samples, 2, 100000);
  if (plot.curves.empty() && plot.net_lines.empty()) throw InputError("curve plot: nothing to draw");
  for (const PlotCurve& c : plot.curves) {
    const std::size_t joints = c.curve.size() - (c.curve.closed() ? 0 : 1);
    if (!c.joints.empty() && c.joints.size() != joints) {
      throw InputError(fmt::format("curve plot: curve '{}' has {} joints but {} joint reports", c.name,
                                   joints, c.joints.size()));
    }
    if (!c.declared.empty() && c.declared.size() != joints) {
      throw InputError(fmt::format("curve plot: curve '{}' has {} joints but {} declared continuities",
                                   c.name, joints, c.declared.size()));
    }
    for (const auto& polygon : c.control_polygons) {
      for (const Vec2& p : polygon) {
        if (!p.allFinite())
          throw InputError(fmt::format("curve plot: curve '{}' has a non-finite control point", c.name));
      }
    }
  }
  for (const PlotOutline& outline : plot.outlines) {
    for (const Vec2& p : outline.points) {
      if (!p.allFinite())
        throw InputError(fmt::format("curve plot: outline '{}' is not finite", outline.name));
    }
  }
  for (const PlotFlag& flag : plot.flags) {
    for (const auto& stretch : flag.stretches) {
      for (const Vec2& p : stretch) {
        if (!p.allFinite()) throw InputError(fmt::format("curve plot: flag '{}' is not finite", flag.name));
      }
    }
  }
  for (const auto& line : plot.net_lines) {
    if (!line[0].allFinite() || !line[1].allFinite())
      throw InputError("curve plot: a net line is not finite");
  }
}

void add_curve(Box& box, const CompositeCurve& curve) {
  for (const Segment& seg : curve.segments()) {
    for (int i = 0; i <= 32; ++i) box.add(seg.point(i / 32.0));
  }
}

// A circular arc: its curvature is constant (the curvature panel gives it),
// and a small corner arc's comb would dwarf every free-form curve's.
bool circular_arc(const Segment& seg) {
  return seg.kind() == SegmentKind::EllipseArc && seg.ellipse() && seg.ellipse()->a == seg.ellipse()->b;
}

// The comb of every curve at one shared scale: the longest tooth of the
// free-form segments (all segments when there are none) is comb_fraction
// of the diagonal. A circular arc more curved than that scale allows gets
// no comb rather than teeth out of scale.
void build_combs(std::vector<Prepared>& curves, double diagonal, const CurvePlotOptions& o) {
  double k_free = 0.0, k_all = 0.0;
  for (const Prepared& c : curves) {
    for (const Segment& seg : c.in->curve.segments()) {
      for (int j = 0; j <= o.comb_teeth; ++j) {
        const double k = drawn_curvature(seg, static_cast<double>(j) / o.comb_teeth);
        if (!std::isfinite(k)) continue;
        k_all = std::max(k_all, std::abs(k));
        if (!circular_arc(seg)) k_free = std::max(k_free, std::abs(k));
      }
    }
  }
  const double k_max = k_free > 0.0 ? k_free : k_all;
  const double scale = k_max > 0.0 ? o.comb_fraction * diagonal / k_max : 0.0;
  for (Prepared& c : curves) {
    for (const Segment& seg : c.in->curve.segments()) {
      if (circular_arc(seg) && std::abs(drawn_curvature(seg, 0.0)) > k_max) {
        c.comb.emplace_back();  // no teeth
        continue;
      }
      std::vector<std::pair<Vec2, Vec2>> teeth;
      bool bent = false;
      for (int j = 0; j <= o.comb_teeth; ++j) {
        const double s = static_cast<double>(j) / o.comb_teeth;
        const CurveJet r = seg.jet(s);
        const double speed = r[1].norm();
        const double k = drawn_curvature(seg, s);
        if (!std::isfinite(k) || !(speed > 0.0)) continue;
        bent = bent || k != 0.0;
        const Vec2 normal(-r[1].y() / speed, r[1].x() / speed);  // left of the direction of travel
        teeth.emplace_back(r[0], r[0] - k * scale * normal);     // away from the centre of curvature
      }
      if (!bent) teeth.clear();  // straight (to rounding): no comb to draw
      c.comb.push_back(std::move(teeth));
    }
  }
}

// The model panel's viewBox: the content box plus a margin, widened to the
// panel's aspect, with a band under it for the x coordinates and the scale
// bar, and one left of it for the y coordinates.
ModelFrame model_frame(const Box& content, double px0, double py0, double pw, double ph) {
  ModelFrame f;
  f.px = px0;
  f.py = py0;
  f.pw = pw;
  f.ph = ph;
  Vec2 size = content.hi - content.lo;
  const double margin = 0.04 * std::max(size.norm(), 1e-9);
  size += Vec2::Constant(2.0 * margin);
  const double scale =
      std::min((pw - kTickGutter) / size.x(), (ph - kScaleBand) / size.y());  // pixels per unit
  f.unit = 1.0 / scale;
  f.vw = pw * f.unit;
  f.vh = ph * f.unit;
  const Vec2 mid = 0.5 * (content.lo + content.hi);
  // Centre the content right of the gutter and above the band (SVG y = -model y).
  f.vx = mid.x() - (kTickGutter + 0.5 * (pw - kTickGutter)) * f.unit;
  f.vy = -mid.y() - 0.5 * (ph - kScaleBand) * f.unit;
  f.grid = nice_step(0.25 * f.vw);
  // Coordinates to 1e-4 of a pixel at this scale, at least.
  f.decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(f.unit * 1e-4))), 0, 12);
  return f;
}

// The multiples of `step` in [lo, hi], as whole numbers of steps (so that
// each is exactly k * step, not a sum that drifts).
std::vector<double> grid_values(double lo, double hi, double step) {
  std::vector<double> values;
  for (double k = std::ceil(lo / step); k * step <= hi; k += 1.0) values.push_back(k * step);
  return values;
}

// A coordinate as its tick label writes it: -0 and rounding noise are 0.
std::string tick_text(double v, double step) { return short_number(std::abs(v) < 1e-9 * step ? 0.0 : v, 6); }

// The SVG path of a curve: exact arcs as A commands (pieces below 180
// degrees), lines as L, other segments as polylines within `tolerance`.
std::string curve_path(const CompositeCurve& curve, double tolerance, const ModelFrame& f) {
  std::string d;
  Vec2 pen = Vec2::Constant(kInfinity);
  SampleOptions sampling;
  sampling.tolerance = tolerance;
  for (const Segment& seg : curve.segments()) {
    const Vec2 start = seg.point(0.0);
    if (!((start - pen).norm() <= tolerance)) d += (d.empty() ? "M" : " M") + f.pt(start);
    if (seg.kind() == SegmentKind::EllipseArc) {
      const EllipseArcParams& a = *seg.ellipse();
      const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(a.to_deg - a.from_deg) / 120.0)));
      const int sweep = a.to_deg > a.from_deg ? 0 : 1;  // counter-clockwise stays so after the y flip
      for (int i = 1; i <= pieces; ++i) {
        d += fmt::format(" A{},{} {} 0 {} {}", f.num(a.a), f.num(a.b), fixed_number(-a.rotation_deg, 9),
                         sweep, f.pt(seg.point(static_cast<double>(i) / pieces)));
      }
    } else {
      const std::vector<double> s = sample_segment_parameters(seg, sampling);
      for (std::size_t i = 1; i < s.size(); ++i) d += " L" + f.pt(seg.point(s[i]));
    }
    pen = seg.point(1.0);
  }
  if (curve.closed() && (pen - curve.segments().front().point(0.0)).norm() <= tolerance) d += " Z";
  return d;
}

void write_grid_and_scale_bar(std::string& out, const ModelFrame& f, const std::string& units) {
  const double step = f.grid;
  std::string d;
  for (const double x : grid_values(f.vx, f.vx + f.vw, step)) {
    d += fmt::format("M{},{} V{} ", f.num(x), f.num(f.vy), f.num(f.vy + f.vh));
  }
  for (const double y : grid_values(f.vy, f.vy + f.vh, step)) {
    d += fmt::format("M{},{} H{} ", f.num(f.vx), f.num(y), f.num(f.vx + f.vw));
  }
  out += fmt::format("<path class=\"grid\" d=\"{}\" stroke=\"#e4e4e4\" stroke-width=\"{}\" fill=\"none\"/>\n",
                     d, f.px_len(1.0));
  const double x0 = f.vx + 14.0 * f.unit, y = f.vy + f.vh - 14.0 * f.unit;
  const std::string label = short_number(step, 6) + " " + units;
  out += fmt::format("<g class=\"scale-bar\" data-length=\"{}\" data-units=\"{}\">\n", short_number(step, 15),
                     escape_markup(units));
  out += fmt::format(
      "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#000\" stroke-width=\"{}\"/>\n"
      "<path d=\"M{},{} v{} M{},{} v{}\" stroke=\"#000\" stroke-width=\"{}\"/>\n",
      f.num(x0), f.num(y), f.num(x0 + step), f.num(y), f.px_len(2.0), f.num(x0), f.num(y - 4 * f.unit),
      f.px_len(8.0), f.num(x0 + step), f.num(y - 4 * f.unit), f.px_len(8.0), f.px_len(1.0));
  out +=
      fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"{}\">{}</text>\n</g>\n", f.num(x0 + step + 6 * f.unit),
                  f.num(y + 4 * f.unit), f.px_len(12.0), escape_markup(label));
}

// The grid's coordinates: x under the model (above the scale bar), y in the
// gutter left of it, each axis named with the units at its end.
void write_ticks(std::string& out, const ModelFrame& f, const CurvePlot& plot) {
  const std::string units = escape_markup(plot.units);
  out += fmt::format("<g class=\"ticks\" font-size=\"{}\" fill=\"#555\">\n", f.px_len(kTickFont));
  const double x_row = f.vy + f.vh - (kScaleBand - 16.0) * f.unit;  // the x labels' baseline
  const double x_name_left = f.vx + f.vw - 58.0 * f.unit;           // the x axis's name, right of the labels
  for (const double x : grid_values(f.vx + kTickGutter * f.unit, x_name_left - 12.0 * f.unit, f.grid)) {
    out += fmt::format(
        "<text class=\"tick\" data-axis=\"x\" data-value=\"{}\" x=\"{}\" y=\"{}\" "
        "text-anchor=\"middle\">{}</text>\n",
        short_number(x, 15), f.num(x), f.num(x_row), tick_text(x, f.grid));
  }
  const double y_top = f.vy + 28.0 * f.unit, y_bottom = f.vy + f.vh - kScaleBand * f.unit;
  for (const double y : grid_values(y_top, y_bottom, f.grid)) {  // SVG y: the model's -y
    out += fmt::format(
        "<text class=\"tick\" data-axis=\"y\" data-value=\"{}\" x=\"{}\" y=\"{}\" "
        "text-anchor=\"end\">{}</text>\n",
        short_number(-y, 15), f.num(f.vx + (kTickGutter - 6.0) * f.unit),
        f.num(y + 0.35 * kTickFont * f.unit), tick_text(-y, f.grid));
  }
  out += fmt::format(
      "<text class=\"axis-name\" data-axis=\"x\" x=\"{}\" y=\"{}\" text-anchor=\"end\">{} ({})</text>\n"
      "<text class=\"axis-name\" data-axis=\"y\" x=\"{}\" y=\"{}\">{} ({})</text>\n</g>\n",
      f.num(f.vx + f.vw - 6.0 * f.unit), f.num(x_row), escape_markup(plot.axis_names[0]), units,
      f.num(f.vx + 6.0 * f.unit), f.num(f.vy + 14.0 * f.unit), escape_markup(plot.axis_names[1]), units);
}

// A vessel's axis of revolution, x = 0, dash-dotted over the whole panel.
void write_axis(std::string& out, const ModelFrame& f) {
  out += fmt::format(
      "<g class=\"axis\"><line x1=\"0\" y1=\"{}\" x2=\"0\" y2=\"{}\" stroke=\"#333\" stroke-width=\"{}\" "
      "stroke-dasharray=\"{} {} {} {}\"/><text x=\"{}\" y=\"{}\" font-size=\"{}\" "
      "fill=\"#333\">axis</text></g>\n",
      f.num(f.vy), f.num(f.vy + f.vh), f.px_len(1.0), f.px_len(10.0), f.px_len(3.0), f.px_len(2.0),
      f.px_len(3.0), f.num(4.0 * f.unit), f.num(f.vy + 28.0 * f.unit), f.px_len(kTickFont));
}

void write_outlines(std::string& out, const CurvePlot& plot, const ModelFrame& f) {
  for (const PlotOutline& outline : plot.outlines) {
    std::string d;
    for (std::size_t i = 0; i < outline.points.size(); ++i)
      d += (i == 0 ? "M" : " L") + f.pt(outline.points[i]);
    if (!d.empty()) d += " Z";
    out += fmt::format(
        "<path class=\"outline\" data-name=\"{}\" d=\"{}\" fill=\"none\" stroke=\"#666\" "
        "stroke-width=\"{}\" stroke-linejoin=\"round\"/>\n",
        escape_markup(outline.name), d, f.px_len(1.2));
  }
}

void write_flags(std::string& out, const CurvePlot& plot, const ModelFrame& f) {
  for (const PlotFlag& flag : plot.flags) {
    std::string d;
    for (const auto& stretch : flag.stretches) {
      for (std::size_t i = 0; i < stretch.size(); ++i) d += (i == 0 ? " M" : " L") + f.pt(stretch[i]);
    }
    out += fmt::format(
        "<path class=\"flag\" data-name=\"{}\" d=\"{}\" fill=\"none\" stroke=\"{}\" "
        "stroke-opacity=\"0.45\" stroke-width=\"{}\" stroke-linecap=\"round\" stroke-linejoin=\"round\"/>\n",
        escape_markup(flag.name), d.empty() ? d : d.substr(1), kFlagColour, f.px_len(9.0));
  }
}

void write_dimensions(std::string& out, const CurvePlot& plot, const ModelFrame& f) {
  for (const PlotDimension& dim : plot.dimensions) {
    const Vec2 span = dim.to - dim.from;
    if (!(span.norm() > 0.0)) continue;
    const Vec2 d = span.normalized(), n(-d.y(), d.x());
    const Vec2 shift = n * (dim.offset_px * f.unit);
    const Vec2 a = dim.from + shift, b = dim.to + shift;
    std::string path = "M" + f.pt(a) + " L" + f.pt(b);
    if (dim.offset_px != 0.0) {  // extension lines, a little past the dimension line
      const Vec2 past = n * (std::copysign(3.0, dim.offset_px) * f.unit);
      path += " M" + f.pt(dim.from) + " L" + f.pt(a + past) + " M" + f.pt(dim.to) + " L" + f.pt(b + past);
    }
    // Arrowheads 7 pixels long, pointing out to the ends.
    const double len = 7.0 * f.unit, half = 2.5 * f.unit;
    const auto head = [&](const Vec2& tip, const Vec2& inward) {
      return "M" + f.pt(tip) + " L" + f.pt(tip + inward * len + n * half) + " L" +
             f.pt(tip + inward * len - n * half) + " Z";
    };
    const std::string heads = head(a, d) + " " + head(b, -d);
    // The text beside the middle: right of an upright dimension, above a level one.
    const Vec2 mid = 0.5 * (a + b);
    const bool upright = std::abs(d.y()) > std::abs(d.x());
    const Vec2 at = upright ? mid + Vec2(5.0 * f.unit, 0.0) : mid + Vec2(0.0, 5.0 * f.unit);
    out += fmt::format(
        "<g class=\"dimension\" data-name=\"{}\" data-value=\"{}\"><path d=\"{}\" fill=\"none\" "
        "stroke=\"#222\" stroke-width=\"{}\"/><path d=\"{}\" fill=\"#222\"/><text x=\"{}\" y=\"{}\" "
        "font-size=\"{}\" text-anchor=\"{}\" dominant-baseline=\"{}\" fill=\"#222\">{}</text></g>\n",
        escape_markup(dim.name), short_number(dim.value, 12), path, f.px_len(0.8), heads, f.num(at.x()),
        f.num(-at.y()), f.px_len(kTickFont), upright ? "start" : "middle", upright ? "middle" : "auto",
        escape_markup(dim.text));
  }
}

void write_comb(std::string& out, const Prepared& c, const ModelFrame& f, const std::string& name) {
  std::string teeth, envelope;
  for (const auto& segment : c.comb) {
    for (std::size_t j = 0; j < segment.size(); ++j) {
      teeth += "M" + f.pt(segment[j].first) + " L" + f.pt(segment[j].second) + " ";
      envelope += (j == 0 ? "M" : "L") + f.pt(segment[j].second) + " ";
    }
  }
  out += fmt::format(
      "<g class=\"comb\" data-name=\"{}\" fill=\"none\">\n<path class=\"comb-teeth\" d=\"{}\" stroke=\"{}\" "
      "stroke-opacity=\"0.45\" stroke-width=\"{}\"/>\n<path class=\"comb-envelope\" d=\"{}\" stroke=\"{}\" "
      "stroke-opacity=\"0.7\" stroke-width=\"{}\"/>\n</g>\n",
      name, teeth, c.colour, f.px_len(0.8), envelope, c.colour, f.px_len(1.0));
}

void write_control_polygon(std::string& out, const PlotCurve& c, const ModelFrame& f,
                           const std::string& name) {
  std::string d, dots;
  std::size_t points = 0;
  for (const auto& polygon : c.control_polygons) {
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      d += (i == 0 ? "M" : "L") + f.pt(polygon[i]) + " ";
      dots += fmt::format("<circle class=\"control-point\" cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
                          f.num(polygon[i].x()), f.num(-polygon[i].y()), f.px_len(2.5));
      ++points;
    }
  }
  out += fmt::format(
      "<g class=\"control-polygon\" data-name=\"{}\" data-points=\"{}\" fill=\"{}\">\n<path d=\"{}\" "
      "fill=\"none\" "
      "stroke=\"{}\" stroke-width=\"{}\" stroke-dasharray=\"{} {}\"/>\n{}\n</g>\n",
      name, points, kPolygonBlue, d, kPolygonBlue, f.px_len(1.0), f.px_len(2.0), f.px_len(3.0), dots);
}

// Points the curve is given to pass through: dots in its colour, drawn over
// the joint markers they sit on.
void write_through_points(std::string& out, const Prepared& c, const ModelFrame& f, const std::string& name) {
  if (c.in->through.empty()) return;
  std::string dots;
  for (const Vec2& p : c.in->through) {
    dots += fmt::format("<circle class=\"through-point\" cx=\"{}\" cy=\"{}\" r=\"{}\"/>", f.num(p.x()),
                        f.num(-p.y()), f.px_len(2.5));
  }
  out +=
      fmt::format("<g class=\"through-points\" data-name=\"{}\" data-points=\"{}\" fill=\"{}\">\n{}\n</g>\n",
                  name, c.in->through.size(), c.colour, dots);
}

const char* joint_label(Continuity c) { return c == Continuity::None ? "gap" : to_string(c); }

void write_joints(std::string& out, const Prepared& c, const ModelFrame& f, const std::string& name) {
  const PlotCurve& in = *c.in;
  for (std::size_t j = 0; j < c.joints.size(); ++j) {
    const JointReport& r = c.joints[j];
    const Continuity declared = in.declared.empty() ? Continuity::None : in.declared[j];
    const bool lost = static_cast<int>(r.achieved) < static_cast<int>(declared);
    const Vec2 p = in.curve.segments()[r.before].point(1.0);
    out += fmt::format(
        "<g class=\"joint{}\" data-name=\"{}\" data-joint=\"{}\" data-achieved=\"{}\" data-declared=\"{}\" "
        "data-gap=\"{}\" data-tangent-angle=\"{}\" data-curvature-jump=\"{}\">\n",
        lost ? " lost" : "", name, j, joint_label(r.achieved),
        declared == Continuity::None ? "" : to_string(declared), short_number(r.gap, 6),
        short_number(r.tangent_angle, 6), short_number(r.curvature_jump, 6));
    const double s = 4.5 * f.unit;
    if (lost) {  // an orange diamond
      out += fmt::format(
          "<path d=\"M{},{} l{},{} l{},{} l{},{} Z\" fill=\"#ff8c00\" stroke=\"#000\" "
          "stroke-width=\"{}\"/>\n",
          f.num(p.x() - 1.4 * s), f.num(-p.y()), f.num(1.4 * s), f.num(-1.4 * s), f.num(1.4 * s),
          f.num(1.4 * s), f.num(-1.4 * s), f.num(1.4 * s), f.px_len(0.8));
    } else {
      out += fmt::format(
          "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#fff\" stroke=\"#000\" stroke-width=\"{}\"/>\n",
          f.num(p.x()), f.num(-p.y()), f.num(s), f.px_len(1.2));
    }
    out += fmt::format("<text class=\"joint-label\" x=\"{}\" y=\"{}\" font-size=\"{}\">{}</text>\n",
                       f.num(p.x() + 7 * f.unit), f.num(-p.y() - 7 * f.unit), f.px_len(12.0),
                       joint_label(r.achieved));
    if (lost) {
      out += fmt::format(
          "<text class=\"joint-declared\" x=\"{}\" y=\"{}\" font-size=\"{}\" fill=\"#c05000\">{} "
          "declared</text>\n",
          f.num(p.x() + 7 * f.unit), f.num(-p.y() + 7 * f.unit), f.px_len(10.0), to_string(declared));
    }
    out += "</g>\n";
  }
}

void write_model_panel(std::string& out, const std::vector<Prepared>& curves, const CurvePlot& plot,
                       const ModelFrame& f, double tolerance) {
  out += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#fff\" stroke=\"#bbb\"/>\n"
      "<svg class=\"model-panel\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" viewBox=\"{} {} {} {}\" "
      "data-units=\"{}\" data-units-per-pixel=\"{}\" font-family=\"sans-serif\">\n",
      px(f.px), px(f.py), px(f.pw), px(f.ph), px(f.px), px(f.py), px(f.pw), px(f.ph), f.num(f.vx),
      f.num(f.vy), f.num(f.vw), f.num(f.vh), escape_markup(plot.units), short_number(f.unit, 9));
  write_grid_and_scale_bar(out, f, plot.units);
  write_ticks(out, f, plot);
  if (plot.revolution_axis) write_axis(out, f);
  write_outlines(out, plot, f);
  write_flags(out, plot, f);
  write_dimensions(out, plot, f);
  if (!plot.net_lines.empty()) {
    std::string d;
    for (const auto& line : plot.net_lines) d += "M" + f.pt(line[0]) + " L" + f.pt(line[1]) + " ";
    out += fmt::format(
        "<path class=\"net\" d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" "
        "stroke-dasharray=\"{} {}\"/>\n",
        d, kPolygonBlue, f.px_len(0.8), f.px_len(1.5), f.px_len(3.0));
  }
  for (const Prepared& c : curves) {
    const std::string name = escape_markup(c.in->name);
    if (c.in->before_fairing) {
      out += fmt::format(
          "<path class=\"curve-before\" data-name=\"{}\" d=\"{}\" fill=\"none\" stroke=\"#888\" "
          "stroke-width=\"{}\" stroke-dasharray=\"{} {}\"/>\n",
          name, curve_path(*c.in->before_fairing, tolerance, f), f.px_len(1.4), f.px_len(6.0), f.px_len(4.0));
    }
    write_comb(out, c, f, name);
    write_control_polygon(out, *c.in, f, name);
    out += fmt::format(
        "<path class=\"curve\" data-name=\"{}\" data-segments=\"{}\" d=\"{}\" fill=\"none\" stroke=\"{}\" "
        "stroke-width=\"{}\" stroke-linejoin=\"round\"/>\n",
        name, c.in->curve.size(), curve_path(c.in->curve, tolerance, f), c.colour, f.px_len(2.0));
  }
  for (const Prepared& c : curves) write_joints(out, c, f, escape_markup(c.in->name));
  for (const Prepared& c : curves) write_through_points(out, c, f, escape_markup(c.in->name));
  out += "</svg>\n";
}

// The curvature plot's axes: data ranges and the pixel box they map to.
struct Axes {
  double s_max = 1, k_min = -1, k_max = 1;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;  // pixels: x0 <-> s = 0, y0 <-> k_max (top)
  double x(double s) const { return x0 + (x1 - x0) * s / s_max; }
  double y(double k) const { return y0 + (y1 - y0) * (k_max - k) / (k_max - k_min); }
};

Axes curvature_axes(const std::vector<Prepared>& curves, double px0, double py0, double pw, double ph) {
  Axes a;
  double k_lo = 0.0, k_hi = 0.0, length = 0.0;
  for (const Prepared& c : curves) {
    length = std::max(length, c.profile.length);
    for (const auto& seg : c.profile.segments) {
      for (const CurvatureSample& s : seg) {
        k_lo = std::min(k_lo, s.curvature);
        k_hi = std::max(k_hi, s.curvature);
      }
    }
  }
  a.s_max = length > 0.0 ? length : 1.0;
  const double pad = k_hi > k_lo ? 0.06 * (k_hi - k_lo) : 1.0 / a.s_max;
  a.k_min = k_lo - pad;
  a.k_max = k_hi + pad;
  a.x0 = px0 + 62;
  a.x1 = px0 + pw - 14;
  a.y0 = py0 + 14 + 11 * kJointLabelRows;
  a.y1 = py0 + ph - 40;
  return a;
}

void write_axes(std::string& out, const Axes& a, const std::string& units) {
  std::string ticks, labels;
  const double s_step = nice_step(a.s_max / 4.0), k_step = nice_step((a.k_max - a.k_min) / 4.0);
  for (double s = 0.0; s <= a.s_max * (1 + 1e-12); s += s_step) {
    ticks += fmt::format("M{},{} v5 ", px(a.x(s)), px(a.y1));
    labels += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>", px(a.x(s)),
                          px(a.y1 + 17), short_number(s, 6));
  }
  for (double k = std::ceil(a.k_min / k_step) * k_step; k <= a.k_max; k += k_step) {
    ticks += fmt::format("M{},{} h-5 ", px(a.x0), px(a.y(k)));
    labels += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>", px(a.x0 - 7),
                          px(a.y(k) + 4), short_number(std::abs(k) < 1e-9 * k_step ? 0.0 : k, 6));
  }
  const std::string u = escape_markup(units);
  out += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>\n"
      "<line class=\"zero\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#999\" stroke-dasharray=\"2 "
      "2\"/>\n"
      "<path d=\"{}\" stroke=\"#444\"/>\n<g font-size=\"11\">{}</g>\n"
      "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"12\">arc length ({})</text>\n"
      "<text transform=\"translate({},{}) rotate(-90)\" text-anchor=\"middle\" font-size=\"12\">curvature "
      "(1/{})"
      "</text>\n",
      px(a.x0), px(a.y0), px(a.x1 - a.x0), px(a.y1 - a.y0), px(a.x0), px(a.y(0.0)), px(a.x1), px(a.y(0.0)),
      ticks, labels, px(0.5 * (a.x0 + a.x1)), px(a.y1 + 34), u, px(a.x0 - 48), px(0.5 * (a.y0 + a.y1)), u);
}

// Rows of joint labels above the curvature plot, so that close joints stay readable.
class LabelRows {
 public:
  /// The row (0 nearest the plot) for a label centred at pixel x.
  int place(double x) {
    int best = 0;
    for (int r = 0; r < kRows; ++r) {
      if (x - last_[r] >= 18.0) {
        best = r;
        break;
      }
      if (last_[r] < last_[best]) best = r;
    }
    last_[best] = x;
    return best;
  }
  static constexpr int kRows = kJointLabelRows;

 private:
  std::array<double, kRows> last_{-kInfinity, -kInfinity, -kInfinity};
};

void write_curvature_curve(std::string& out, const Prepared& c, const Axes& a, LabelRows& rows) {
  const std::string name = escape_markup(c.in->name);
  out +=
      fmt::format("<g class=\"curvature\" data-name=\"{}\" fill=\"none\" stroke=\"{}\">\n", name, c.colour);
  const CurvatureSample* previous = nullptr;
  for (std::size_t i = 0; i < c.profile.segments.size(); ++i) {
    const auto& samples = c.profile.segments[i];
    if (samples.empty()) continue;
    // A jump at the joint is drawn as a thin vertical step (zero length where the curvature is continuous).
    if (previous != nullptr && std::abs(a.y(previous->curvature) - a.y(samples.front().curvature)) >= 0.05) {
      out += fmt::format(
          "<line class=\"curvature-jump\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke-width=\"0.8\" "
          "stroke-opacity=\"0.7\"/>\n",
          px(a.x(previous->arc_length)), px(a.y(previous->curvature)), px(a.x(samples.front().arc_length)),
          px(a.y(samples.front().curvature)));
    }
    std::string points;
    for (const CurvatureSample& s : samples)
      points += px(a.x(s.arc_length)) + "," + px(a.y(s.curvature)) + " ";
    points.pop_back();
    out += fmt::format(
        "<polyline class=\"curvature-segment\" data-segment=\"{}\" data-s-start=\"{}\" data-s-end=\"{}\" "
        "data-k-start=\"{}\" data-k-end=\"{}\" points=\"{}\" stroke-width=\"1.6\"/>\n",
        i, short_number(samples.front().arc_length, 12), short_number(samples.back().arc_length, 12),
        short_number(samples.front().curvature, 12), short_number(samples.back().curvature, 12), points);
    previous = &samples.back();
  }
  for (std::size_t j = 0; j < c.joints.size(); ++j) {
    const JointReport& r = c.joints[j];
    const double s = c.profile.segment_ends[r.before];
    const int row = rows.place(a.x(s));
    out += fmt::format(
        "<g class=\"joint-marker\" data-name=\"{}\" data-joint=\"{}\" data-s=\"{}\" data-achieved=\"{}\">"
        "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke-width=\"0.8\" stroke-dasharray=\"4 3\"/>"
        "<text x=\"{}\" y=\"{}\" font-size=\"10\" text-anchor=\"middle\" fill=\"{}\" "
        "stroke=\"none\">{}</text></g>\n",
        name, j, short_number(s, 12), joint_label(r.achieved), px(a.x(s)), px(a.y0 - 11.0 * row), px(a.x(s)),
        px(a.y1), px(a.x(s)), px(a.y0 - 4.0 - 11.0 * row), c.colour, joint_label(r.achieved));
  }
  out += "</g>\n";
}

void write_curvature_panel(std::string& out, const std::vector<Prepared>& curves, const CurvePlot& plot,
                           double px0, double py0, double pw, double ph) {
  const Axes a = curvature_axes(curves, px0, py0, pw, ph);
  out += fmt::format(
      "<g class=\"curvature-plot\" data-s-max=\"{}\" data-k-min=\"{}\" data-k-max=\"{}\" data-x0=\"{}\" "
      "data-x1=\"{}\" data-y0=\"{}\" data-y1=\"{}\" font-family=\"sans-serif\">\n",
      short_number(a.s_max, 12), short_number(a.k_min, 12), short_number(a.k_max, 12), px(a.x0), px(a.x1),
      px(a.y0), px(a.y1));
  write_axes(out, a, plot.units);
  LabelRows rows;
  for (const Prepared& c : curves) write_curvature_curve(out, c, a, rows);
  out += "</g>\n";
}

bool any_through(const std::vector<Prepared>& curves) {
  return std::any_of(curves.begin(), curves.end(), [](const Prepared& c) { return !c.in->through.empty(); });
}

// The outlines' names, each once, in order: the legend's lines for them.
std::vector<std::string> outline_names(const CurvePlot& plot) {
  std::vector<std::string> names;
  for (const PlotOutline& outline : plot.outlines) {
    if (std::find(names.begin(), names.end(), outline.name) == names.end()) names.push_back(outline.name);
  }
  return names;
}

void write_legend(std::string& out, const std::vector<Prepared>& curves, const CurvePlot& plot, double y0) {
  double y = y0 + kLegendLine;
  out += "<g class=\"legend\" font-family=\"sans-serif\" font-size=\"12\">\n";
  for (const std::string& name : outline_names(plot)) {
    out += fmt::format(
        "<g class=\"legend-entry\" data-name=\"{}\"><line x1=\"12\" y1=\"{}\" x2=\"36\" y2=\"{}\" "
        "stroke=\"#666\" stroke-width=\"1.2\"/><text x=\"42\" y=\"{}\">{}</text></g>\n",
        escape_markup(name), px(y - 4), px(y - 4), px(y), escape_markup(name));
    y += kLegendLine;
  }
  for (const PlotFlag& flag : plot.flags) {
    out += fmt::format(
        "<g class=\"legend-entry\" data-name=\"{}\"><line x1=\"12\" y1=\"{}\" x2=\"36\" y2=\"{}\" "
        "stroke=\"{}\" stroke-opacity=\"0.45\" stroke-width=\"9\"/><text x=\"42\" y=\"{}\">{}</text></g>\n",
        escape_markup(flag.name), px(y - 4), px(y - 4), kFlagColour, px(y), escape_markup(flag.name));
    y += kLegendLine;
  }
  for (const Prepared& c : curves) {
    std::string text = escape_markup(c.in->name);
    if (c.in->energy_before && c.in->energy_after) {
      const std::string kind =
          c.in->energy_name.empty() ? "energy" : escape_markup(c.in->energy_name) + " energy";
      text += fmt::format(": {} {} before fairing (grey dashed), {} after", kind,
                          short_number(*c.in->energy_before, 6), short_number(*c.in->energy_after, 6));
    }
    out += fmt::format(
        "<g class=\"legend-entry\" data-name=\"{}\"><line x1=\"12\" y1=\"{}\" x2=\"36\" y2=\"{}\" "
        "stroke=\"{}\" "
        "stroke-width=\"2\"/><text x=\"42\" y=\"{}\">{}</text></g>\n",
        escape_markup(c.in->name), px(y - 4), px(y - 4), c.colour, px(y), text);
    y += kLegendLine;
  }
  out += fmt::format(
      "<text x=\"12\" y=\"{}\" fill=\"#555\">dotted blue: control polygon; light strokes: curvature comb "
      "(teeth \u2212k n, away from the centre of curvature); \u25cb joint with its measured continuity; "
      "\u25c6 declared continuity lost{}</text>\n",
      px(y), plot.revolution_axis ? "; dash-dotted: the axis of revolution" : "");
  if (any_through(curves)) {
    out += fmt::format(
        "<text x=\"12\" y=\"{}\" fill=\"#555\">\u25cf on a joint, in the curve's colour: a point the curve "
        "is "
        "given to pass through (through:)</text>\n",
        px(y + kLegendLine));
  }
  out += "</g>\n";
}

}  // namespace

std::string plot_curves_svg(const CurvePlot& plot, const CurvePlotOptions& options) {
  validate(plot, options);
  std::vector<Prepared> curves;
  Box box;
  for (std::size_t i = 0; i < plot.curves.size(); ++i) {
    const PlotCurve& in = plot.curves[i];
    Prepared c;
    c.in = &in;
    c.joints = in.joints.empty() ? in.curve.joints() : in.joints;
    c.profile = curvature_profile(in.curve, options.curvature_samples);
    c.colour = kPalette[i % std::size(kPalette)];
    add_curve(box, in.curve);
    if (in.before_fairing) add_curve(box, *in.before_fairing);
    for (const auto& polygon : in.control_polygons) {
      for (const Vec2& p : polygon) box.add(p);
    }
    curves.push_back(std::move(c));
  }
  for (const auto& line : plot.net_lines) {
    box.add(line[0]);
    box.add(line[1]);
  }
  for (const PlotOutline& outline : plot.outlines) {
    for (const Vec2& p : outline.points) box.add(p);
  }
  for (const PlotFlag& flag : plot.flags) {
    for (const auto& stretch : flag.stretches) {
      for (const Vec2& p : stretch) box.add(p);
    }
  }
  const double diagonal = std::max((box.hi - box.lo).norm(), 1e-9);
  build_combs(curves, diagonal, options);
  for (const Prepared& c : curves) {
    for (const auto& seg : c.comb) {
      for (const auto& tooth : seg) box.add(tooth.second);
    }
  }
  bool upright_dimension = false;
  for (const PlotDimension& dim : plot.dimensions) {
    box.add(dim.from);
    box.add(dim.to);
    upright_dimension =
        upright_dimension || std::abs(dim.to.y() - dim.from.y()) > std::abs(dim.to.x() - dim.from.x());
  }
  if (upright_dimension && !box.empty()) {  // room on the right for an upright dimension's line and text
    box.add(Vec2(box.hi.x() + 0.18 * (box.hi - box.lo).norm(), box.lo.y()));
  }
  if (plot.revolution_axis && !box.empty()) {  // the axis in view, beside the profile or across it
    box.add(Vec2(0.0, box.lo.y()));
    box.add(Vec2(0.0, box.hi.y()));
  }

  const double w = options.width, h = options.height;
  const double legend =
      kLegendLine * static_cast<double>(curves.size() + outline_names(plot).size() + plot.flags.size() + 1 +
                                        (any_through(curves) ? 1 : 0)) +
      10.0;
  const double panel_h = std::max(60.0, h - kTitleBand - legend);
  const ModelFrame frame = model_frame(box, 8.0, kTitleBand, 0.5 * w - 12.0, panel_h);
  std::string out = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\">\n"
      "<title>{}</title>\n<rect class=\"background\" width=\"{}\" height=\"{}\" fill=\"#f7f7f7\"/>\n"
      "<text class=\"title\" x=\"12\" y=\"22\" font-family=\"sans-serif\" font-size=\"16\" "
      "font-weight=\"bold\">"
      "{}</text>\n",
      options.width, options.height, options.width, options.height, escape_markup(plot.title), options.width,
      options.height, escape_markup(plot.title));
  write_model_panel(out, curves, plot, frame, options.sample_fraction * diagonal);
  write_curvature_panel(out, curves, plot, 0.5 * w + 4.0, kTitleBand, 0.5 * w - 12.0, panel_h);
  write_legend(out, curves, plot, kTitleBand + panel_h);
  out += "</svg>\n";
  return out;
}

}  // namespace fabmesh
