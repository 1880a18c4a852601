#include "tests/io/cutting/gcode_checks.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "geometry/fairing/build_curve.h"
#include "geometry/toolpath/curvature_bound.h"
#include "io/design/read_design.h"

namespace fabmesh::test {
namespace {

std::string run_command(const std::string& command, int* status) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run: " + command);
  std::string out;
  char buffer[65536];
  std::size_t n = 0;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  *status = pclose(pipe);
  return out;
}

std::string script_path() { return std::string(FABMESH_SOURCE_DIR) + "/tools/node/gcode-trace.js"; }

Vec3 vec3(const nlohmann::json& j) {
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

// Signed angle turned by an arc motion (G2 negative), in (0, 2 pi] in magnitude.
double arc_sweep(const TraceMotion& m) {
  const Vec2 c = m.center.head<2>();
  const Vec2 a = m.start.head<2>() - c, b = m.end.head<2>() - c;
  double t = std::atan2(cross2(a, b), a.dot(b));  // (-pi, pi]
  if (m.motion == "G3") {
    if (t <= 0.0) t += 2.0 * M_PI;
  } else {
    if (t >= 0.0) t -= 2.0 * M_PI;
  }
  return t;
}

}  // namespace

std::string gcode_interpreter_problem() {
  int status = 0;
  run_command("node --version > /dev/null 2>&1", &status);
  if (status != 0)
    return "node (Node.js) must be on PATH to interpret G-code (scripts/install-deps.sh --test)";
  const std::string package = std::string(FABMESH_SOURCE_DIR) + "/tools/node/node_modules/gcode-toolpath";
  if (!std::filesystem::exists(package)) {
    return "the npm package gcode-toolpath must be installed in tools/node (scripts/install-deps.sh "
           "--test): " +
           package + " is missing";
  }
  return "";
}

Trace interpret_gcode(const std::string& gcode, const std::string& name) {
  // Named for this process too: ctest runs test cases as parallel processes,
  // and two of them interpret programs of the same example.
  const std::filesystem::path file =
      std::filesystem::path(FABMESH_TEST_TMP) / ("gcode-" + std::to_string(::getpid()) + "-" + name);
  {
    std::ofstream out(file, std::ios::binary);
    out << gcode;
    if (!out.good()) throw std::runtime_error("cannot write " + file.string());
  }
  Trace trace = interpret_gcode_file(file.string());
  std::filesystem::remove(file);  // kept only when the interpreter failed on it
  return trace;
}

Trace interpret_gcode_file(const std::string& file) {
  const std::string problem = gcode_interpreter_problem();
  if (!problem.empty()) throw std::runtime_error(problem);
  int status = 0;
  const std::string json_text = run_command(fmt::format("node '{}' '{}'", script_path(), file), &status);
  if (status != 0) throw std::runtime_error("gcode-trace.js failed on " + file);
  return parse_trace(json_text);
}

Trace parse_trace(const std::string& json_text) {
  const nlohmann::json j = nlohmann::json::parse(json_text);
  Trace trace;
  for (const auto& u : j["unknown"]) trace.unknown.push_back(u["code"].get<std::string>());
  trace.units = j["modal"]["units"].get<std::string>();
  for (const auto& m : j["motions"]) {
    TraceMotion t;
    t.arc = m["type"] == "arc";
    t.motion = m["motion"].get<std::string>();
    t.start = vec3(m["start"]);
    t.end = vec3(m["end"]);
    if (t.arc) t.center = vec3(m["center"]);
    t.feed = m["feed"].is_null() ? 0.0 : m["feed"].get<double>();
    if (m["units"] == "G20") t.feed *= 25.4;  // F is in inches per minute under G20
    if (m.contains("comment")) t.comment = m["comment"].get<std::string>();
    t.section = m["section"].get<std::string>();
    t.line = m["line"].get<int>();
    trace.motions.push_back(t);
  }
  return trace;
}

namespace {

// The words of a line without its comments: (letter, number text) pairs.
std::vector<std::pair<char, std::string>> words_of(const std::string& line) {
  std::string text;
  int depth = 0;
  for (char c : line) {
    if (c == '(') ++depth;
    if (depth == 0 && c != ';') text += c;
    if (c == ')') --depth;
    if (c == ';' && depth == 0) break;
  }
  std::vector<std::pair<char, std::string>> words;
  for (std::size_t i = 0; i < text.size();) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(text[i])));
    if (std::isalpha(static_cast<unsigned char>(c)) == 0) {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) != 0 || text[j] == '.' ||
                               text[j] == '-' || text[j] == '+'))
      ++j;
    words.emplace_back(c, text.substr(i + 1, j - i - 1));
    i = j;
  }
  return words;
}

}  // namespace

CannedCycles read_canned_cycles(const std::string& program) {
  CannedCycles out;
  std::istringstream in(program);
  std::string cycle;  // the canned cycle in force ("" after G80 or another motion)
  bool g98 = false, spindle = false, m5_before = false;
  int tool = 0, pending_tool = 0, number = 0;
  double z = 0.0;
  std::size_t open = 0;                  // the first block no G80 or motion has closed yet
  std::optional<double> mz, mr, mq, mf;  // modal words of the cycle
  std::size_t awaiting_start = 0;        // 1 + the tool change whose next line may start the spindle
  for (std::string line; std::getline(in, line);) {
    ++number;
    const auto words = words_of(line);
    if (words.empty()) {
      out.without_cycles += line + "\n";
      continue;
    }
    bool motion = false, feed_motion = false, g80 = false, m3 = false, m5 = false, m6 = false;
    std::string block_cycle;
    std::optional<double> x, y, bz, br, bq, bf;
    for (const auto& [letter, value] : words) {
      const double v = value.empty() ? 0.0 : std::stod(value);
      if (letter == 'G') {
        if (v == 98.0) g98 = true;
        if (v == 99.0) g98 = false;
        if (v == 20.0 || v == 21.0) out.units = fmt::format("G{}", v);
        if (v == 80.0) g80 = true;
        if (v == 0.0 || v == 1.0 || v == 2.0 || v == 3.0) motion = true, feed_motion = v != 0.0;
        if (v == 81.0 || v == 83.0) block_cycle = fmt::format("G{}", v);
        if (v == 73.0 || v == 76.0 || v == 82.0 || (v >= 84.0 && v <= 89.0))
          throw std::runtime_error(fmt::format("line {}: canned cycle G{} is not read here", number, value));
      } else if (letter == 'M') {
        m3 = m3 || v == 3.0;
        m5 = m5 || v == 5.0;
        m6 = m6 || v == 6.0;
      } else if (letter == 'T') {
        pending_tool = static_cast<int>(v);
      } else if (letter == 'X') {
        x = v;
      } else if (letter == 'Y') {
        y = v;
      } else if (letter == 'Z') {
        bz = v;
      } else if (letter == 'R') {
        br = v;
      } else if (letter == 'Q') {
        bq = v;
      } else if (letter == 'F') {
        bf = v;
      }
    }
    if (awaiting_start > 0) out.changes[awaiting_start - 1].started_after = m3, awaiting_start = 0;
    if (m6) {
      ToolChange c;
      c.line = number;
      c.tool = pending_tool;
      c.spindle_was_on = spindle;
      c.stopped_first = m5_before;
      c.z_before = z;
      tool = pending_tool;
      out.changes.push_back(c);
      awaiting_start = out.changes.size();
    }
    if (m3) spindle = true;
    if (m5) spindle = false;
    m5_before = m5;
    if (g80 || motion) {
      // G80 cancels the cycle (a motion word too, without cancelling it properly).
      for (std::size_t k = open; k < out.blocks.size(); ++k) out.blocks[k].cancelled = g80;
      open = out.blocks.size();
      cycle.clear();
    }
    if (motion && feed_motion && out.first_feed_motion == 0) {
      out.first_feed_motion = number;
      out.routing_tool = tool;
    }
    if (!block_cycle.empty()) cycle = block_cycle;
    // A block: a cycle word, or X/Y while a cycle is in force.
    if (cycle.empty() || (block_cycle.empty() && !x && !y)) {
      if (motion && bz) z = *bz;
      out.without_cycles += line + "\n";
      continue;
    }
    const DrillBlock* previous = out.blocks.empty() ? nullptr : &out.blocks.back();
    if (bz) mz = bz;
    if (br) mr = br;
    if (bq) mq = bq;
    if (bf) mf = bf;
    if ((!x || !y) && !previous)
      throw std::runtime_error(fmt::format("line {}: a cycle block without X or Y", number));
    if (!mz || !mr || !mf || (cycle == "G83" && !mq))
      throw std::runtime_error(fmt::format("line {}: a cycle block missing Z, R, F or Q", number));
    DrillBlock b;
    b.line = number;
    b.cycle = cycle;
    b.initial_level = g98;
    b.stated_all = x && y && bz && br && bf && (cycle != "G83" || bq);
    b.x = x ? *x : previous->x;
    b.y = y ? *y : previous->y;
    b.z = *mz, b.r = *mr, b.f = *mf, b.q = mq.value_or(0.0);
    b.tool = tool;
    b.spindle_on = spindle;
    b.start_z = z;  // with G98 the tool is back there after the block
    if (!g98) z = *mr;
    out.blocks.push_back(b);
  }
  return out;
}

double motion_length(const TraceMotion& m) {
  if (!m.arc) return (m.end.head<2>() - m.start.head<2>()).norm();
  return (m.start.head<2>() - m.center.head<2>()).norm() * std::abs(arc_sweep(m));
}

Vec3 motion_point(const TraceMotion& m, double f) {
  const double z = m.start.z() + f * (m.end.z() - m.start.z());
  if (!m.arc) {
    const Vec2 p = m.start.head<2>() + f * (m.end.head<2>() - m.start.head<2>());
    return Vec3(p.x(), p.y(), z);
  }
  const Vec2 c = m.center.head<2>(), a = m.start.head<2>() - c;
  const double angle = std::atan2(a.y(), a.x()) + f * arc_sweep(m);
  const double r = a.norm();
  return Vec3(c.x() + r * std::cos(angle), c.y() + r * std::sin(angle), z);
}

double motion_distance(const TraceMotion& m, const Vec2& p) {
  const Vec2 a = m.start.head<2>(), b = m.end.head<2>();
  if (!m.arc) {
    const Vec2 d = b - a;
    const double len2 = d.squaredNorm();
    const double t = len2 == 0.0 ? 0.0 : std::clamp((p - a).dot(d) / len2, 0.0, 1.0);
    return (a + t * d - p).norm();
  }
  const Vec2 c = m.center.head<2>();
  const double r = (a - c).norm(), sweep = arc_sweep(m);
  const Vec2 q = p - c;
  const double a0 = std::atan2(a.y() - c.y(), a.x() - c.x());
  double delta = sweep > 0 ? std::atan2(q.y(), q.x()) - a0 : a0 - std::atan2(q.y(), q.x());
  delta = std::fmod(delta + 4.0 * M_PI, 2.0 * M_PI);
  if (delta <= std::abs(sweep)) return std::abs(q.norm() - r);
  return std::min((p - a).norm(), (p - b).norm());
}

CurveDistance::CurveDistance(CompositeCurve curve, double spacing)
    : curve_(std::move(curve)), cell_(4.0 * spacing) {
  for (std::size_t i = 0; i < curve_.size(); ++i) {
    const Segment& seg = curve_.segments()[i];
    double length = 0.0;
    for (int k = 0; k < 256; ++k) length += (seg.point((k + 1) / 256.0) - seg.point(k / 256.0)).norm();
    const int n = std::max(8, static_cast<int>(std::ceil(length / spacing)));
    for (int k = 0; k < n; ++k) {
      const double s = static_cast<double>(k) / n;
      samples_.push_back({seg.point(s), i, s});
      polygon_.push_back(samples_.back().p);
    }
  }
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    max_gap_ = std::max(max_gap_, (samples_[(i + 1) % samples_.size()].p - samples_[i].p).norm());
    const Vec2& p = samples_[i].p;
    grid_[key(static_cast<long long>(std::floor(p.x() / cell_)),
              static_cast<long long>(std::floor(p.y() / cell_)))]
        .push_back(static_cast<int>(i));
  }
}

double CurveDistance::newton(std::size_t segment, double s, const Vec2& q) const {
  const Segment& seg = curve_.segments()[segment];
  for (int it = 0; it < 50; ++it) {
    const CurveJet j = seg.jet(s);
    const double f = (j[0] - q).dot(j[1]);
    const double fp = j[1].squaredNorm() + (j[0] - q).dot(j[2]);
    const double next = std::clamp(fp > 0.0 ? s - f / fp : s - f / j[1].squaredNorm(), 0.0, 1.0);
    if (std::abs(next - s) < 1e-15) return next;
    s = next;
  }
  return s;
}

CurveDistance::Foot CurveDistance::nearest(const Vec2& q, double limit) const {
  const long long cx = static_cast<long long>(std::floor(q.x() / cell_));
  const long long cy = static_cast<long long>(std::floor(q.y() / cell_));
  double best = INFINITY;
  std::vector<int> near;
  // Rings of cells until the ring is farther than the best sample found (plus a margin for the candidates).
  // Every curve point is within max_gap of a sample: no sample within limit + max_gap proves d >= limit.
  const double reach = limit + max_gap_;
  for (long long ring = 0; ring < 1000000; ++ring) {
    if (best<INFINITY&& static_cast<double>(ring - 1) * cell_> best + cell_) break;
    if (best == INFINITY && static_cast<double>(ring - 1) * cell_ > reach) {
      Foot bound;
      bound.distance = limit;
      bound.segment = static_cast<std::size_t>(-1);
      return bound;
    }
    for (long long ix = cx - ring; ix <= cx + ring; ++ix) {
      for (long long iy = cy - ring; iy <= cy + ring; ++iy) {
        if (std::max(std::abs(ix - cx), std::abs(iy - cy)) != ring) continue;
        const auto it = grid_.find(key(ix, iy));
        if (it == grid_.end()) continue;
        for (int i : it->second) {
          near.push_back(i);
          best = std::min(best, (samples_[i].p - q).norm());
        }
      }
    }
  }
  Foot foot;
  foot.distance = INFINITY;
  const int n = static_cast<int>(samples_.size());
  auto dist = [&](int i) { return (samples_[(i + n) % n].p - q).norm(); };
  for (int i : near) {
    // Seeds: samples closer than both neighbours (local minima along the curve) near the best.
    const double di = dist(i);
    if (di > best + cell_ || di > dist(i - 1) || di > dist(i + 1)) continue;
    // Newton on the exact segment from the sample; a run stopped at a segment's end goes on
    // into the neighbouring segment from its joint end.
    std::size_t segment = samples_[i].segment;
    double s = samples_[i].s;
    for (int hop = 0; hop < 3; ++hop) {
      s = newton(segment, s, q);
      const Vec2 p = curve_.segments()[segment].point(s);
      if ((p - q).norm() < foot.distance) foot = {(p - q).norm(), segment, s, p};
      const std::size_t n_seg = curve_.size();
      if (s == 0.0 && (curve_.closed() || segment > 0)) {
        segment = (segment + n_seg - 1) % n_seg, s = 1.0;
      } else if (s == 1.0 && (curve_.closed() || segment + 1 < n_seg)) {
        segment = (segment + 1) % n_seg, s = 0.0;
      } else {
        break;
      }
    }
  }
  return foot;
}

bool inside_polygon(const std::vector<Vec2>& poly, const Vec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if ((poly[i].y() > p.y()) != (poly[j].y() > p.y()) &&
        p.x() <
            (poly[j].x() - poly[i].x()) * (p.y() - poly[i].y()) / (poly[j].y() - poly[i].y()) + poly[i].x()) {
      in = !in;
    }
  }
  return in;
}

double lipschitz_walk(const TraceMotion& m, const std::function<double(const Vec2&)>& margin, double min_step,
                      Vec2* where) {
  const double length = motion_length(m);
  Vec2 p = m.start.head<2>();
  double mk = margin(p), worst = mk;
  if (where) *where = p;
  if (length == 0.0) return mk;
  double u = 0.0;
  while (u < length) {
    double step = std::min(std::max(min_step, mk), length - u);
    for (;;) {
      const Vec2 q = motion_point(m, (u + step) / length).head<2>();
      const double mq = margin(q);
      const double bound = std::min(mk, mq) - 0.5 * step;
      if (bound < 0.0 && step > min_step) {
        step *= 0.5;
        continue;
      }
      if (bound < worst) {
        worst = bound;
        if (where) *where = mq < mk ? q : p;
      }
      if (bound < 0.0) return worst;  // a failure: no need to walk on
      u += step;
      p = q;
      mk = mq;
      break;
    }
  }
  return worst;
}

double lipschitz_walk_curve(const CompositeCurve& curve, const std::function<double(const Vec2&)>& margin,
                            double min_step, Vec2* where) {
  double worst = INFINITY;
  for (const Segment& seg : curve.segments()) {
    const double m4 = seg.fourth_derivative_bound();
    double s = 0.0;
    Vec2 p = seg.point(0.0);
    double mk = margin(p);
    while (s < 1.0) {
      const double target = std::max(min_step, mk);
      double ds = std::min(1.0 - s, target / std::max(seg.jet(s)[1].norm(), 1e-300));
      for (;;) {
        // Proven arc length of [s, s + ds]: at most ds (|c'(mid)| + E1) (curvature_bound.h).
        const JetBounds jb = jet_bounds(seg, s, s + ds, m4);
        const double e1 = jb.half * jb.at_center[2].norm() +
                          0.5 * jb.half * jb.half * jb.at_center[3].norm() +
                          jb.half * jb.half * jb.half / 6.0 * m4;
        const double arc = ds * (jb.at_center[1].norm() + e1);
        const Vec2 q = seg.point(s + ds);
        const double mq = margin(q);
        const double bound = std::min(mk, mq) - 0.5 * arc;
        if ((bound < 0.0 && arc > min_step) || arc > 2.0 * target) {
          ds *= 0.5;
          continue;
        }
        if (bound < worst) {
          worst = bound;
          if (where) *where = mq < mk ? q : p;
        }
        if (bound < 0.0) return worst;  // a failure: no need to walk on
        s += ds;
        p = q;
        mk = mq;
        break;
      }
    }
  }
  return worst;
}

ExampleRegion load_countertop_example(const std::string& file_name) {
  const bool bare = file_name.find('/') == std::string::npos;
  const Design design =
      read_design(bare ? std::string(FABMESH_SOURCE_DIR) + "/configs/examples/" + file_name : file_name);
  const auto& c = std::get<CountertopDesign>(design.body);
  ExampleRegion out;
  out.outline = build_curve(c.outline).curve;
  for (std::size_t i = 0; i < c.holes.size(); ++i) {
    out.holes.push_back(
        {build_curve(c.holes[i].curve).curve, fmt::format("holes[{}] ({})", i, c.holes[i].shape)});
  }
  out.thickness = c.thickness;
  out.tolerance = design.common.tolerance;
  out.name = design.common.name;
  return out;
}

}  // namespace fabmesh::test
