#include "io/cutting/gcode.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"
#include "io/file.h"

namespace fabmesh {
namespace {

// Comments may not hold parentheses (RS-274) and stay printable ASCII.
std::string comment_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '(') {
      out += '[';
    } else if (c == ')') {
      out += ']';
    } else if (c >= 32 && c < 127) {
      out += c;
    }
  }
  return out;
}

class Writer {
 public:
  Writer(double scale, int decimals) : scale_(scale), decimals_(decimals) {}

  // A number in program units, fixed decimals, no trailing zeros, no "-0".
  std::string num(double model_value) const { return plain(model_value * scale_); }
  std::string plain(double v) const {
    std::string s = fmt::format("{:.{}f}", v, decimals_);
    if (s.find('.') != std::string::npos) {
      while (s.back() == '0') s.pop_back();
      if (s.back() == '.') s.pop_back();
    }
    if (s == "-0") s = "0";
    return s;
  }
  // The value the controller will read back, in model units.
  double rounded(double model_value) const { return std::stod(num(model_value)) / scale_; }
  double resolution() const { return std::pow(10.0, -decimals_) / scale_; }

  std::string text;
  void line(const std::string& s) {
    text += s;
    text += '\n';
  }

 private:
  double scale_;
  int decimals_;
};

struct State {
  Vec3 at{0.0, 0.0, 0.0};  // rounded position, model units
  bool known = false;
  std::string motion;  // G0, G1, G2, G3
  double feed = -1.0;
};

const char* note(const ToolMove& m) {
  switch (m.kind) {
    case MoveKind::LeadIn:
      return " (lead in)";
    case MoveKind::LeadOut:
      return " (lead out)";
    case MoveKind::Ramp:
      return " (ramp)";
    case MoveKind::Helix:
      return " (helix)";
    case MoveKind::TabUp:
    case MoveKind::TabDown:
      return " (tab)";
    default:
      return m.role == PieceRole::Dogbone ? " (dogbone)" : "";
  }
}

class Encoder {
 public:
  Encoder(const Toolpath& path, double scale, int decimals) : path_(path), w_(scale, decimals) {}

  std::string run(const GcodeOptions& o);

 private:
  // Each drill's tool change and cycle blocks, then the change back to the
  // router bit; ends with the bit in the spindle, running.
  void drilling(const std::string& u);
  void profile(const std::string& u);
  // Retract and stop the spindle if it runs, change to `tool`, start it again.
  void change_tool(int tool, double spindle);
  bool spindle_on_ = false;

  double feed_of(const ToolMove& m) const {
    switch (m.kind) {
      case MoveKind::Plunge:
      case MoveKind::TabUp:
      case MoveKind::TabDown:
        return path_.options.plunge;
      default:
        return path_.options.feed;
    }
  }

  // "G1 X.. Y.. Z.. F.." with the words that change; nothing when no word changes.
  void linear(const ToolMove& m, const Vec3& to) {
    const bool rapid = m.kind == MoveKind::Rapid || m.kind == MoveKind::Retract;
    const Vec3 r(w_.rounded(to.x()), w_.rounded(to.y()), w_.rounded(to.z()));
    std::string words;
    const char* axes = "XYZ";
    for (int k = 0; k < 3; ++k) {
      if (!s_.known || r[k] != s_.at[k]) words += fmt::format(" {}{}", axes[k], w_.num(to[k]));
    }
    if (words.empty()) return;
    emit(rapid ? "G0" : "G1", words, rapid ? -1.0 : feed_of(m), note(m));
    s_.at = r;
    s_.known = true;
  }

  // G2/G3 (split in arcs of at most a half turn); a ramp's arc descends
  // along its turn (a helix: Z on the same line).
  void arc(const ToolMove& m) {
    const Vec2 start(s_.at.x(), s_.at.y());
    const double radius = (start - m.center).norm();
    const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(m.sweep) / (M_PI + 1e-9))));
    const double a0 = std::atan2(start.y() - m.center.y(), start.x() - m.center.x());
    const double z0 = s_.at.z();
    for (int i = 1; i <= pieces; ++i) {
      const double sweep = m.sweep / pieces;
      const Vec2 end = i == pieces ? Vec2(m.to.x(), m.to.y())
                                   : m.center + radius * Vec2(std::cos(a0 + m.sweep * i / pieces),
                                                              std::sin(a0 + m.sweep * i / pieces));
      const double z = i == pieces ? m.to.z() : z0 + (m.to.z() - z0) * i / pieces;
      const Vec3 to(end.x(), end.y(), z);
      // Flatter than the resolution: a straight move is as exact.
      if (radius * (1.0 - std::cos(0.5 * sweep)) <= w_.resolution()) {
        linear(m, to);
        continue;
      }
      const Vec2 from(s_.at.x(), s_.at.y());
      const Vec2 r_end(w_.rounded(end.x()), w_.rounded(end.y()));
      if (r_end == from) continue;  // would read as a full circle
      const double r_z = w_.rounded(z);
      const std::string words = fmt::format(" X{} Y{}{} I{} J{}", w_.num(end.x()), w_.num(end.y()),
                                            r_z != s_.at.z() ? " Z" + w_.num(z) : std::string(),
                                            w_.num(m.center.x() - from.x()), w_.num(m.center.y() - from.y()));
      emit(sweep > 0.0 ? "G3" : "G2", words, feed_of(m), note(m));
      s_.at = Vec3(r_end.x(), r_end.y(), r_z);
    }
  }

  void emit(const std::string& motion, const std::string& words, double feed, const char* comment) {
    std::string line = motion + words;
    if (feed > 0.0 && feed != s_.feed) {
      line += " F" + w_.num(feed);
      s_.feed = feed;
    }
    s_.motion = motion;
    w_.line(line + comment);
  }

  const Toolpath& path_;
  Writer w_;
  State s_;
};

std::string Encoder::run(const GcodeOptions& o) {
  const CncOptions& c = path_.options;
  const std::string u = o.units;
  const std::string per_min = u + "/min";
  w_.line(fmt::format("(fabmesh toolpath: {})", comment_text(o.name).substr(0, 120)));
  w_.line(fmt::format("(tool: end mill, diameter {} {}; the tool-centre path, no G41/G42)",
                      w_.num(c.tool_diameter), u));
  w_.line(fmt::format("(units {}; z = 0 on the slab top; depth {} in {} passes)", u,
                      w_.num(c.depth + c.breakthrough), path_.pass_z.size()));
  w_.line(fmt::format("(feed {} {}, plunge {} {}, spindle {} rpm clockwise)", w_.num(c.feed), per_min,
                      w_.num(c.plunge), per_min, w_.plain(c.spindle)));
  w_.line(fmt::format("(cutting {}; tabs {} x {} wide, {} high; lead-in {})", to_string(c.direction),
                      c.tabs.count, w_.num(c.tabs.width), w_.num(c.tabs.height), w_.num(c.lead_in)));
  for (std::size_t i = 0; i < path_.loops.size(); ++i) {
    const LoopPath& loop = path_.loops[i];
    if (loop.outer || loop.tabs.empty()) continue;
    w_.line(fmt::format("({}: tabs {}, {} high)", comment_text(loop.label), loop.tabs.size(),
                        w_.num(loop.tab_height)));
  }
  if (c.finish > 0.0) {
    w_.line(fmt::format("(roughing leaves {} of stock; a finishing pass at full depth cuts each edge)",
                        w_.num(c.finish)));
  }
  if (c.entry == EntryKind::Ramp) {
    w_.line(fmt::format("(entry: zig-zag ramp at {} degrees along the path)", w_.plain(c.ramp_angle_deg)));
  }
  if (c.entry == EntryKind::Helix) {
    for (const std::vector<LoopPath>* paths : {&path_.roughing, &path_.loops}) {
      for (const LoopPath& loop : *paths) {
        if (!loop.helix) continue;
        w_.line(fmt::format("({}: entry: helix of radius {} about X{} Y{}, at most {} degrees)",
                            comment_text(loop.label), w_.num(piece_radius(*loop.helix)),
                            w_.num(loop.helix->center.x()), w_.num(loop.helix->center.y()),
                            w_.plain(c.ramp_angle_deg)));
      }
    }
  }
  if (c.arc_fit) {
    w_.line(
        fmt::format("(arc fitting: {} line and corner moves fitted as {} arcs and {} lines, within {} {})",
                    path_.fit_replaced, path_.fit_arcs, path_.fit_lines, w_.num(path_.fit_deviation), u));
  }
  w_.line(fmt::format("(path within {} {} of the exact offset of the exact curves)",
                      w_.num(path_.deviation + w_.resolution()), u));
  const ToolpathTotals totals = toolpath_totals(path_);
  const std::string drilled = path_.drills.empty()
                                  ? std::string()
                                  : fmt::format(", drilling {} {} at {} {}", w_.num(totals.drilling), u,
                                                w_.num(drill_feed(c)), per_min);
  w_.line(
      fmt::format("(estimated {:.1f} min without acceleration: cutting {} {}, plunging {} {}, rapids {} {} "
                  "at {} {}{})",
                  totals.minutes, w_.num(totals.cutting), u, w_.num(totals.plunging), u, w_.num(totals.rapid),
                  u, w_.num(c.rapid), per_min, drilled));
  const ProfilePasses& profiling = path_.profiling;
  const bool tool_changes = !path_.drills.empty() || !c.tools.empty() || !profiling.runs.empty();
  if (tool_changes) {
    std::string tools = fmt::format("T{} end mill {} {}", end_mill_number(c), w_.num(c.tool_diameter), u);
    for (std::size_t k = 0; k < path_.drills.size(); ++k) {
      if (k > 0 && path_.drills[k].tool == path_.drills[k - 1].tool) continue;
      tools += fmt::format(", T{} drill {} {}", path_.drills[k].tool, w_.num(path_.drills[k].diameter), u);
    }
    if (!profiling.runs.empty())
      tools += fmt::format(", T{} profile bit {} {}", profiling.tool, w_.num(profiling.diameter), u);
    w_.line(fmt::format("(tools: {})", tools));
  }
  if (!path_.drills.empty()) {
    w_.line(fmt::format("(drilling first: {} {}, {} from R {} to z {}{} at {} {}, spindle {} rpm)",
                        path_.drills.size(), path_.drills.size() == 1 ? "hole" : "holes",
                        c.drill.peck > 0.0 ? "G83" : "G81", w_.num(drill_retract(c)),
                        w_.num(-(c.depth + c.breakthrough)),
                        c.drill.peck > 0.0 ? fmt::format(" in pecks of {}", w_.num(c.drill.peck)) : "",
                        w_.num(drill_feed(c)), per_min, w_.plain(drill_spindle(c))));
  }
  w_.line(std::string(u == "in" ? "G20" : "G21") + " G90 G94 G17");
  w_.line(fmt::format("G0 Z{}", w_.num(c.safe_z)));  // up before the spindle starts
  if (tool_changes) {
    drilling(u);
  } else {
    w_.line(fmt::format("M3 S{}", w_.plain(c.spindle)));
  }
  s_.motion = "G0";
  std::size_t loop = static_cast<std::size_t>(-1);
  std::size_t pass = 0;
  for (const ToolMove& m : path_.moves) {
    if (m.loop != loop) loop = m.loop, pass = 0;
    if (m.kind == MoveKind::Plunge && m.finishing) {
      w_.line(fmt::format("({}: finishing pass at z {}, the last {} of stock)",
                          comment_text(path_.loops[m.loop].label), w_.num(m.to.z()), w_.num(c.finish)));
    } else if (m.kind == MoveKind::Plunge && pass < path_.pass_z.size()) {
      w_.line(fmt::format("({}: pass {} of {} at z {})", comment_text(path_.loops[m.loop].label), pass + 1,
                          path_.pass_z.size(), w_.num(path_.pass_z[pass])));
      ++pass;
    }
    if (!s_.known && m.kind == MoveKind::Rapid) {
      // The first move: at safe height already (the line above), across to the start.
      w_.line(fmt::format("G0 X{} Y{}", w_.num(m.to.x()), w_.num(m.to.y())));
      s_.at = Vec3(w_.rounded(m.to.x()), w_.rounded(m.to.y()), w_.rounded(c.safe_z));
      s_.known = true;
      continue;
    }
    if (m.shape == PieceKind::Arc) {
      arc(m);
    } else {
      linear(m, m.to);
    }
  }
  if (!profiling.runs.empty()) profile(u);
  w_.line("M5");
  w_.line("M30");
  return w_.text;
}

void Encoder::profile(const std::string& u) {
  const CncOptions& c = path_.options;
  const ProfilePasses& p = path_.profiling;
  w_.line(
      fmt::format("(profiling: T{}, the profile bit {} {}: {}, along the exposed edges with its tip at z {})",
                  p.tool, w_.num(p.diameter), u, comment_text(p.profile), w_.num(-p.depth)));
  change_tool(p.tool, c.spindle);
  for (const ProfileRun& run : p.runs) {
    w_.line(fmt::format("({})", comment_text(run.label)));
    w_.line(fmt::format("G0 X{} Y{}", w_.num(run.path.front().x()), w_.num(run.path.front().y())));
    w_.line(fmt::format("G1 Z{} F{}", w_.num(-p.depth), w_.num(c.plunge)));
    for (std::size_t k = 1; k < run.path.size(); ++k) {
      w_.line(fmt::format("G1 X{} Y{}{}", w_.num(run.path[k].x()), w_.num(run.path[k].y()),
                          k == 1 ? " F" + w_.num(c.feed) : std::string()));
    }
    w_.line(fmt::format("G0 Z{}", w_.num(c.safe_z)));
  }
}

void Encoder::change_tool(int tool, double spindle) {
  if (spindle_on_) {
    w_.line(fmt::format("G0 Z{}", w_.num(path_.options.safe_z)));
    w_.line("M5");
  }
  w_.line(fmt::format("M6 T{}", tool));
  w_.line(fmt::format("M3 S{}", w_.plain(spindle)));
  spindle_on_ = true;
}

void Encoder::drilling(const std::string& u) {
  const CncOptions& c = path_.options;
  const bool peck = c.drill.peck > 0.0;
  // Every word on every block: nothing modal is left for a reader to carry over.
  const std::string cycle =
      fmt::format(" Z{} R{}{} F{}", w_.num(-(c.depth + c.breakthrough)), w_.num(drill_retract(c)),
                  peck ? " Q" + w_.num(c.drill.peck) : std::string(), w_.num(drill_feed(c)));
  for (std::size_t k = 0; k < path_.drills.size(); ++k) {
    const DrillHole& d = path_.drills[k];
    if (k == 0 || d.tool != path_.drills[k - 1].tool) {
      std::size_t holes = 0;
      for (const DrillHole& e : path_.drills) holes += e.tool == d.tool ? 1 : 0;
      w_.line(fmt::format("(drill T{}: diameter {} {}, {} {})", d.tool, w_.num(d.diameter), u, holes,
                          holes == 1 ? "hole" : "holes"));
      change_tool(d.tool, drill_spindle(c));
    }
    w_.line(fmt::format("G98 {} X{} Y{}{} ({})", peck ? "G83" : "G81", w_.num(d.center.x()),
                        w_.num(d.center.y()), cycle, comment_text(d.label)));
    if (k + 1 == path_.drills.size() || path_.drills[k + 1].tool != d.tool) w_.line("G80");
  }
  w_.line(fmt::format("(routing: T{}, the end mill)", end_mill_number(c)));
  change_tool(end_mill_number(c), c.spindle);
  s_.feed = -1.0;  // the cycles set F: the routing's first feed move states its own
}

}  // namespace

std::string encode_gcode(const Toolpath& path, const GcodeOptions& o) {
  if (o.units != "mm" && o.units != "in") {
    throw InputError(fmt::format("G-code units '{}' is not mm (G21) or in (G20)", o.units));
  }
  if (o.decimals < 0 || o.decimals > 9) {
    throw RangeError("decimals", o.decimals, fmt::format("decimals = {} is outside [0, 9]", o.decimals));
  }
  const double scale =
      millimetres_per_unit(o.model_units) / millimetres_per_unit(o.units);  // model -> program
  int decimals = o.decimals;
  if (decimals == 0) {
    // Rounding moves a point by at most sqrt(2)/2 10^-d program units: keep
    // that within the toolpath's rounding share (a twentieth of the tolerance).
    const double allowed = path.rounding_allowance * scale;
    decimals = std::clamp(static_cast<int>(std::ceil(std::log10(std::sqrt(0.5) / allowed))), 3, 6);
  }
  return Encoder(path, scale, decimals).run(o);
}

void write_gcode(const std::string& file, const Toolpath& path, const GcodeOptions& options) {
  write_file_atomically(file, encode_gcode(path, options));
}

}  // namespace fabmesh
