#include "geometry/toolpath/toolpath.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/toolpath/path_clearance.h"
#include "geometry/toolpath/tabs.h"

namespace fabmesh {
namespace {

std::string at(const Vec2& p) { return fmt::format("({:.6g}, {:.6g})", p.x(), p.y()); }

// The tolerance's shares (header): chains t/2 (with arc fitting, chords and
// fitted arcs together: chords within t/4, the fit within what they left),
// boundary samples t/10, arc chords t/20.
struct Budget {
  double chain, fit, boundary, sagitta;
};
constexpr const char* kChordStage = "tool path chords";
constexpr const char* kFitStage = "tool path chords and fitted arcs";
Budget budget(ToleranceBudget& t, bool arc_fit) {
  const double path = t.take(arc_fit ? kFitStage : kChordStage, 0.5);
  const double boundary = t.take("boundary samples", 0.1);
  const double sagitta = t.take("arcs as chords in the clearance check", 0.05);
  return {arc_fit ? 0.5 * path : path, arc_fit ? path : 0.0, boundary, sagitta};
}

ToolMove move_along(const PathPiece& p, double z, MoveKind kind, std::size_t loop) {
  ToolMove m;
  m.kind = kind;
  m.shape = p.kind;
  m.to = Vec3(p.to.x(), p.to.y(), z);
  m.center = p.center;
  m.sweep = p.sweep;
  m.role = p.role;
  m.loop = loop;
  return m;
}

ToolMove move_to(MoveKind kind, const Vec2& xy, double z, std::size_t loop) {
  ToolMove m;
  m.kind = kind;
  m.to = Vec3(xy.x(), xy.y(), z);
  m.loop = loop;
  return m;
}

// The least distance from `path` to the sampled part boundary, minus the
// sample and chord allowances: a proven lower bound on the exact clearance.
double proven_clearance(const std::vector<PathPiece>& path, const BoundaryIndex& index, double r,
                        double deviation, const Budget& b, Clearance* found) {
  *found = path_clearance(path, index, r, b.sagitta);
  return std::min(found->distance, r) - deviation - b.sagitta;
}

void require_clearance(const LoopPath& lp, const std::vector<CutCurve>& loops, const BoundaryIndex& index,
                       const SampledBoundary& sb, const CncOptions& o, const Budget& b, double* clearance) {
  const double r = 0.5 * o.tool_diameter;
  Clearance c;
  const double proven = proven_clearance(lp.pieces, index, r, sb.deviation, b, &c);
  *clearance = std::min(*clearance, proven);
  if (proven >= r - o.tolerance) return;
  const BoundaryEdge& e = index.edges()[c.edge];
  const CutCurve& other = loops[e.loop];
  throw GeometryError(lp.label,
                      fmt::format("{}: the tool of diameter {} does not fit near {}: its centre comes "
                                  "within {:.6g} of {} {}, less than the tool radius {} (a passage "
                                  "narrower than the tool)",
                                  lp.label, o.tool_diameter, at(c.at), c.distance, other.label,
                                  segment_name(*other.curve, e.segment), r));
}

// The first lead arc (radius 2 lead_in / pi, then halved twice) that keeps clear of the part.
std::optional<PathPiece> choose_lead(const LoopPath& lp, const BoundaryIndex& index,
                                     const SampledBoundary& sb, const CncOptions& o, const Budget& b,
                                     double* clearance) {
  const double r = 0.5 * o.tool_diameter;
  double radius = 2.0 * o.lead_in / M_PI;
  for (int attempt = 0; attempt < 3 && radius > 0.0; ++attempt, radius *= 0.5) {
    const PathPiece lead = lead_arc(lp, o.direction, radius);
    Clearance c;
    const double proven = proven_clearance({lead}, index, r, sb.deviation, b, &c);
    if (proven >= r - o.tolerance) {
      *clearance = std::min(*clearance, proven);
      return lead;
    }
  }
  return std::nullopt;
}

// The helix circle of radius `radius` for the passes of `lp`: through the
// entry point (the lead's start, else the path's), tangent there to the
// entry's direction, curving the way the lead does (to the waste side
// without a lead), a whole turn ending where the entry begins.
PathPiece helix_circle(const LoopPath& lp, CutDirection direction, double radius) {
  const PathPiece& first = lp.pieces.front();
  const Vec2 e = lp.lead ? lp.lead->from : first.from;
  const Vec2 t = lp.lead ? piece_tangent(*lp.lead, 0.0) : piece_tangent(first, 0.0);
  Vec2 side = direction == CutDirection::Conventional ? Vec2(t.y(), -t.x()) : Vec2(-t.y(), t.x());
  if (lp.lead) side = (lp.lead->center - e).normalized();
  const Vec2 c = e + radius * side;
  PathPiece helix =
      arc_piece(c, e, cross2(e - c, t) > 0.0 ? 2.0 * M_PI : -2.0 * M_PI, PieceRole::Link, first.segment);
  helix.to = e;
  return helix;
}

// The helix circle that keeps the tool clear of the part: the asked radius,
// or the first of r/2, r/4, r/8. GeometryError when none does.
PathPiece choose_helix(const LoopPath& lp, const std::vector<CutCurve>& loops, const BoundaryIndex& index,
                       const SampledBoundary& sb, const CncOptions& o, const Budget& b, double* clearance) {
  const double r = 0.5 * o.tool_diameter;
  std::vector<double> radii{0.5 * r, 0.25 * r, 0.125 * r};
  if (o.helix_radius) radii = {*o.helix_radius};
  Clearance c;
  for (double radius : radii) {
    PathPiece helix = helix_circle(lp, o.direction, radius);
    const double proven = proven_clearance({helix}, index, r, sb.deviation, b, &c);
    if (proven >= r - o.tolerance) {
      *clearance = std::min(*clearance, proven);
      return helix;
    }
  }
  const double radius = radii.back();
  const PathPiece helix = helix_circle(lp, o.direction, radius);
  proven_clearance({helix}, index, r, sb.deviation, b, &c);
  const BoundaryEdge& e = index.edges()[c.edge];
  const CutCurve& other = loops[e.loop];
  throw GeometryError(
      lp.label,
      fmt::format("{}: no room in the waste for a helix entry at {}: a helix of radius {:.6g} about {} needs "
                  "a clear circle of radius {:.6g} (helix radius + tool radius {:.6g}), but {} {} comes "
                  "within {:.6g} of the circle{}; use entry: ramp, a longer lead_in or a smaller tool",
                  lp.label, at(helix.from), radius, at(helix.center), radius + r, r, other.label,
                  segment_name(*other.curve, e.segment), c.distance,
                  o.helix_radius ? "" : " (the smallest tried, an eighth of the tool radius)"));
}

std::vector<double> pass_depths(const CncOptions& o) {
  const double total = o.depth + o.breakthrough;
  const int n = std::max(1, static_cast<int>(std::ceil(total / o.step_down - 1e-9)));
  std::vector<double> z;
  for (int k = 1; k <= n; ++k) z.push_back(-total * k / n);
  return z;
}

// The first `length` of a closed chain of pieces from its start, going round
// again where the chain is shorter.
std::vector<PathPiece> stretch(const std::vector<PathPiece>& pieces, double path_length, double length) {
  std::vector<PathPiece> out;
  if (!(path_length > 0.0)) return out;
  double left = length;
  for (std::size_t i = 0; left > 0.0; i = (i + 1) % pieces.size()) {
    const double len = piece_length(pieces[i]);
    if (len <= left) {
      out.push_back(pieces[i]);
      left -= len;
    } else {
      out.push_back(split_piece(pieces[i], left).first);
      left = 0.0;
    }
  }
  return out;
}

// A zig-zag ramp from z_from at the start point down to z_to there again:
// forward along the path's first `half` and back, descending all the way.
void ramp_moves(const LoopPath& lp, std::size_t loop, double half, double z_from, double z_to,
                std::vector<ToolMove>& moves) {
  std::vector<PathPiece> legs = stretch(lp.pieces, lp.length, half);
  const std::size_t forward = legs.size();
  for (std::size_t i = forward; i-- > 0;) legs.push_back(reversed(legs[i]));
  double done = 0.0;
  for (const PathPiece& p : legs) {
    done += piece_length(p);
    const double z = z_from + (z_to - z_from) * std::min(1.0, done / (2.0 * half));
    moves.push_back(move_along(p, z, MoveKind::Ramp, loop));
  }
  moves.back().to.z() = z_to;  // exactly, whatever the sum's rounding
}

// One pass around a loop at depth z, rising to tab_z over the tabs when `tabs`.
void cut_pass(const LoopPath& lp, std::size_t loop, double z, bool tabs, double tab_z,
              std::vector<ToolMove>& moves) {
  std::vector<double> marks;  // tab boundaries, increasing
  if (tabs) {
    for (const auto& [a, bnd] : lp.tabs) marks.insert(marks.end(), {a, bnd});
  }
  auto on_tab = [&](double u) {
    for (const auto& [a, bnd] : lp.tabs) {
      if (tabs && u > a && u < bnd) return true;
    }
    return false;
  };
  bool raised = false;
  double u0 = 0.0;
  for (const PathPiece& whole : lp.pieces) {
    const double len = piece_length(whole);
    PathPiece rest = whole;
    double done = 0.0;  // of `whole`
    std::vector<double> cuts;
    for (double m : marks) {
      if (m > u0 + done && m < u0 + len) cuts.push_back(m - u0);
    }
    cuts.push_back(len);
    for (double cut : cuts) {
      PathPiece part = rest;
      if (cut < len) {
        auto halves = split_piece(rest, cut - done);
        part = halves.first;
        rest = halves.second;
      }
      const bool want = on_tab(u0 + 0.5 * (done + cut));
      if (want != raised) {
        moves.push_back(
            move_to(want ? MoveKind::TabUp : MoveKind::TabDown, part.from, want ? tab_z : z, loop));
        raised = want;
      }
      moves.push_back(move_along(part, raised ? tab_z : z, MoveKind::Cut, loop));
      done = cut;
    }
    u0 += len;
  }
  if (raised) moves.push_back(move_to(MoveKind::TabDown, lp.pieces.front().from, z, loop));
}

// The roughing path's tabs: the finishing path's, carried over by their
// nearest points and widened by the stock, so the roughing passes leave the
// same bridges.
std::vector<std::pair<double, double>> carried_tabs(const LoopPath& finish, const LoopPath& rough,
                                                    double stock) {
  std::vector<std::pair<double, double>> out;
  for (const auto& [a, b] : finish.tabs) {
    const double ra = nearest_along(rough.pieces, path_point(finish.pieces, a).first) - stock;
    const double rb = nearest_along(rough.pieces, path_point(finish.pieces, b).first) + stock;
    if (ra < rb) out.emplace_back(std::max(ra, 0.0), std::min(rb, rough.length));
  }
  std::sort(out.begin(), out.end());
  return out;
}

void add_fit(Toolpath& tp, const LoopPath& lp) {
  tp.fit_replaced += lp.fit_replaced;
  tp.fit_arcs += lp.fit_arcs;
  tp.fit_lines += lp.fit_lines;
  tp.fit_deviation = std::max(tp.fit_deviation, lp.fit_deviation);
}

// Half the length of path one pass's zig-zag ramp runs over (0: plunge entry).
// The helix moves of one pass: from z_from at the entry point down to z_to
// in whole turns round the circle, each no steeper than the ramp angle, then
// once round at z_to (clearing the bore's floor), back at the entry point.
void helix_moves(const PathPiece& helix, std::size_t loop, const CncOptions& o, double z_from, double z_to,
                 std::vector<ToolMove>& moves) {
  const double per_turn = 2.0 * M_PI * piece_radius(helix) * std::tan(o.ramp_angle_deg * M_PI / 180.0);
  const int turns = std::max(1, static_cast<int>(std::ceil((z_from - z_to) / per_turn - 1e-9)));
  for (int k = 1; k <= turns + 1; ++k) {
    ToolMove m =
        move_along(helix, k >= turns ? z_to : z_from + (z_to - z_from) * k / turns, MoveKind::Helix, loop);
    m.to.head<2>() = helix.from;  // a whole turn ends where it started
    moves.push_back(m);
  }
}

double ramp_half(const CncOptions& o, const std::vector<double>& pass_z) {
  if (o.entry != EntryKind::Ramp || pass_z.empty()) return 0.0;
  return 0.5 * ramp_length(o, -pass_z.front());  // every pass drops by the same step
}

// The finishing pass of a loop: down inside the roughed slot at the short
// lead's start, onto the edge, once round at full depth, off again.
void append_finishing(Toolpath& tp, std::size_t index) {
  const LoopPath& lp = tp.loops[index];
  const CncOptions& o = tp.options;
  const std::size_t first = tp.moves.size();
  const Vec2 start = lp.lead ? lp.lead->from : lp.pieces.front().from;
  const double z = tp.pass_z.back();
  const double tab_z = -(o.depth - lp.tab_height);
  tp.moves.push_back(move_to(MoveKind::Rapid, start, o.safe_z, index));
  tp.moves.push_back(move_to(MoveKind::Plunge, start, z, index));
  if (lp.lead) tp.moves.push_back(move_along(*lp.lead, z, MoveKind::LeadIn, index));
  cut_pass(lp, index, z, !lp.tabs.empty() && z < tab_z - 1e-9 * o.depth, tab_z, tp.moves);
  if (lp.lead) tp.moves.push_back(move_along(reversed(*lp.lead), z, MoveKind::LeadOut, index));
  tp.moves.push_back(move_to(MoveKind::Retract, start, o.safe_z, index));
  for (std::size_t i = first; i < tp.moves.size(); ++i) tp.moves[i].finishing = true;
}

void append_loop_moves(Toolpath& tp, std::size_t index) {
  const LoopPath& lp = tp.roughing.empty() ? tp.loops[index] : tp.roughing[index];
  const CncOptions& o = tp.options;
  const Vec2 start = lp.lead ? lp.lead->from : lp.pieces.front().from;
  tp.moves.push_back(move_to(MoveKind::Rapid, start, o.safe_z, index));
  const double tab_z = -(o.depth - lp.tab_height);
  const double half = ramp_half(o, tp.pass_z);
  double above = 0.0;  // the floor the previous pass left (the slab's top at first)
  for (double z : tp.pass_z) {
    // With a ramp, the tool goes down to the previous floor only, in the waste.
    const double enter = half > 0.0 || lp.helix ? above : z;
    tp.moves.push_back(move_to(MoveKind::Plunge, start, enter, index));
    if (lp.helix) helix_moves(*lp.helix, index, o, enter, z, tp.moves);
    const double at_lead = lp.helix ? z : enter;
    if (lp.lead) tp.moves.push_back(move_along(*lp.lead, at_lead, MoveKind::LeadIn, index));
    if (half > 0.0) ramp_moves(lp, index, half, enter, z, tp.moves);
    cut_pass(lp, index, z, !lp.tabs.empty() && z < tab_z - 1e-9 * o.depth, tab_z, tp.moves);
    if (lp.lead) tp.moves.push_back(move_along(reversed(*lp.lead), z, MoveKind::LeadOut, index));
    above = z;
  }
  tp.moves.push_back(move_to(MoveKind::Retract, start, o.safe_z, index));
  if (!tp.roughing.empty()) append_finishing(tp, index);
}

}  // namespace

ToolpathTotals toolpath_totals(const Toolpath& path) {
  ToolpathTotals t;
  if (path.moves.empty()) return t;
  Vec3 at = path.moves.front().to;
  for (const ToolMove& m : path.moves) {
    double length = (m.to - at).norm();
    if (m.shape == PieceKind::Arc) {
      // A planar arc about `center` at z = to.z(): radius times the turn.
      const double radius = (Vec2(at.x(), at.y()) - m.center).norm();
      length = std::hypot(radius * std::abs(m.sweep), m.to.z() - at.z());
    }
    at = m.to;
    switch (m.kind) {
      case MoveKind::LeadIn:
      case MoveKind::Ramp:
      case MoveKind::Helix:
      case MoveKind::Cut:
      case MoveKind::LeadOut:
        t.cutting += length;
        break;
      case MoveKind::Plunge:
      case MoveKind::TabUp:
      case MoveKind::TabDown:
        t.plunging += length;
        break;
      case MoveKind::Rapid:
      case MoveKind::Retract:
        t.rapid += length;
        break;
    }
  }
  const CncOptions& o = path.options;
  if (!path.drills.empty()) {
    const DrillingTotals d = drilling_totals(path.drills, o);
    const Vec3& start = path.moves.front().to;
    t.rapid += d.rapid + (Vec2(start.x(), start.y()) - path.drills.back().center).norm();
    t.drilling = d.feeding;
  }
  // The profiling passes: down at the plunge feed, along at the cutting
  // feed, up and across to the next at the rapid rate.
  Vec3 end = path.moves.back().to;
  for (const ProfileRun& run : path.profiling.runs) {
    for (std::size_t k = 1; k < run.path.size(); ++k) t.cutting += (run.path[k] - run.path[k - 1]).norm();
    t.plunging += o.safe_z + path.profiling.depth;
    t.rapid += o.safe_z + path.profiling.depth + (Vec2(end.x(), end.y()) - run.path.front()).norm();
    end = Vec3(run.path.back().x(), run.path.back().y(), o.safe_z);
  }
  t.minutes = t.cutting / o.feed + t.plunging / o.plunge + t.rapid / o.rapid;
  if (!path.drills.empty()) t.minutes += t.drilling / drill_feed(o);
  return t;
}

const char* to_string(MoveKind kind) {
  switch (kind) {
    case MoveKind::Rapid:
      return "rapid";
    case MoveKind::Plunge:
      return "plunge";
    case MoveKind::LeadIn:
      return "lead-in";
    case MoveKind::Ramp:
      return "ramp";
    case MoveKind::Helix:
      return "helix";
    case MoveKind::Cut:
      return "cut";
    case MoveKind::LeadOut:
      return "lead-out";
    case MoveKind::TabUp:
      return "tab-up";
    case MoveKind::TabDown:
      return "tab-down";
    case MoveKind::Retract:
      return "retract";
  }
  return "rapid";
}

Toolpath plan_toolpath(const CompositeCurve& outline, const std::vector<RegionHole>& holes,
                       const CncOptions& o) {
  validate_cnc_options(o);
  RegionOptions ro;
  ro.tolerance = o.tolerance;
  ro.max_points = o.max_points;
  const Region2 region = build_region(outline, holes, ro);
  std::vector<CutCurve> loops{{&outline, "outline", true, region.reversed[0]}};
  for (std::size_t i = 0; i < holes.size(); ++i) {
    loops.push_back({&holes[i].curve, holes[i].label, false, region.reversed[i + 1]});
  }
  const double r = 0.5 * o.tool_diameter;
  ToleranceBudget tolerance(o.tolerance);
  const Budget b = budget(tolerance, o.arc_fit);
  const SampledBoundary sb = sample_boundary(loops, b.boundary, o.max_points);
  tolerance.use("boundary samples", sb.deviation);
  const BoundaryIndex index(sb.edges, r);

  Toolpath tp;
  tp.options = o;
  tp.checks = check_manufacturability(loops, index, sb.deviation, o);
  // The material a shallow concave corner keeps at its point (the tool's round there).
  tolerance.take("shallow concave corners", 0.25);
  double shallow = 0.0;
  for (const LoopCheck& c : tp.checks.loops) {
    for (const LoopCorner& k : c.shallow_corners) shallow = std::max(shallow, corner_round_depth(r, k.turn));
  }
  tolerance.use("shallow concave corners", shallow);
  LoopPathOptions lo;
  lo.radius = r;
  lo.chain_tolerance = b.chain;
  lo.direction = o.direction;
  lo.gentle_radius = tab_min_radius(o.tabs, o.tool_diameter);
  lo.max_points = o.max_points;
  lo.arc_fit_tolerance = b.fit;
  tp.clearance = r;
  tp.pass_z = pass_depths(o);
  double chords = 0.0;
  // Tabs keep clear of the start point, and of a ramp's stretch after it.
  const double half = ramp_half(o, tp.pass_z);
  const double clear_start = o.tool_diameter + half;
  for (std::size_t k = 1; k <= loops.size(); ++k) {
    const std::size_t l = k % loops.size();  // holes first, the outline (0) last
    LoopPath lp = build_loop_path(loops[l], tp.checks.loops[l], lo);
    require_clearance(lp, loops, index, sb, o, b, &tp.clearance);
    if (o.lead_in > 0.0) lp.lead = choose_lead(lp, index, sb, o, b, &tp.clearance);
    if (o.entry == EntryKind::Helix && o.finish == 0.0)
      lp.helix = choose_helix(lp, loops, index, sb, o, b, &tp.clearance);
    const TabOptions tabs = l == 0 ? o.tabs : (l - 1 < o.hole_tabs.size() ? o.hole_tabs[l - 1] : no_tabs());
    TabPlacement placed = place_tabs(lp, tabs, o, clear_start);
    lp.tabs = std::move(placed.tabs);
    lp.tab_height = tabs.height;
    if (!placed.warning.empty()) tp.warnings.push_back(std::move(placed.warning));
    if (o.finish > 0.0) {
      // Roughing at the tool radius + the stock, from the point nearest the
      // finishing path's start (so the ramps and tabs keep apart on both).
      LoopPathOptions rough_options = lo;
      rough_options.radius = r + o.finish;
      LoopPath rough = build_loop_path(loops[l], tp.checks.loops[l], rough_options);
      rough.pieces = rotate_path(rough.pieces, nearest_along(rough.pieces, lp.pieces.front().from));
      require_clearance(rough, loops, index, sb, o, b, &tp.clearance);
      if (o.lead_in > 0.0) rough.lead = choose_lead(rough, index, sb, o, b, &tp.clearance);
      if (o.entry == EntryKind::Helix)
        rough.helix = choose_helix(rough, loops, index, sb, o, b, &tp.clearance);
      add_fit(tp, rough);
      rough.tabs = carried_tabs(lp, rough, o.finish);
      rough.tab_height = lp.tab_height;
      tp.roughing.push_back(std::move(rough));
      // The finishing lead starts inside the roughed slot: a tangent arc of radius `finish`.
      lp.lead.reset();
      const PathPiece lead = lead_arc(lp, o.direction, o.finish);
      Clearance c;
      const double proven = proven_clearance({lead}, index, r, sb.deviation, b, &c);
      if (proven >= r - o.tolerance) {
        lp.lead = lead;
        tp.clearance = std::min(tp.clearance, proven);
      }
    }
    tp.deviation = std::max(tp.deviation, lp.deviation);
    chords = std::max(chords, lp.chord_deviation);
    add_fit(tp, lp);
    tp.loops.push_back(std::move(lp));
  }
  for (const LoopPath& rough : tp.roughing) {
    tp.deviation = std::max(tp.deviation, rough.deviation);
    chords = std::max(chords, rough.chord_deviation);
  }
  tolerance.use(o.arc_fit ? kFitStage : kChordStage, o.arc_fit ? tp.deviation : chords);
  // The arcs-as-chords share is a bound the clearance check allows for, not
  // a measured use: it stays open (reported without `used`), as G-code rounding.
  tp.rounding_allowance = tolerance.take("G-code rounding", 0.05);
  tp.tolerance_shares = tolerance.shares();
  tp.tab_z = -(o.depth - o.tabs.height);
  for (std::size_t i = 0; i < tp.loops.size(); ++i) append_loop_moves(tp, i);
  return tp;
}

}  // namespace fabmesh
