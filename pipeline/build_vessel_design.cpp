// kind: vessel -> profile curve (scaled for shrinkage) -> section ->
// revolution, proven embedded; the profile's template for the workshop; the
// slip-casting mould when the design has one.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/vessel.h"
#include "geometry/mould/case_sections.h"
#include "geometry/mould/master_sections.h"
#include "geometry/mould/mould.h"
#include "geometry/mould/shrinkage.h"
#include "geometry/section/print_checks.h"
#include "geometry/section/vessel_section.h"
#include "io/design/schema.h"
#include "pipeline/build_design.h"
#include "pipeline/validate_parts.h"

namespace fabmesh {
namespace {

// Runs `f`. A GeometryError it throws at one of its options ("wall",
// "keys[1]"), named as in the design's map `group` ("vessel.body"), is
// rethrown at that option's design key ("body.wall": `prefix` + its name).
template <class F>
auto keyed_in(const char* group, const std::string& prefix, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (GeometryError& e) {
    const std::string& key = e.location().key;
    const std::vector<std::string>& options = key_group(group).keys;
    if (std::find(options.begin(), options.end(), key.substr(0, key.find('['))) != options.end()) {
      ErrorLocation at = e.location();
      at.key = prefix + key;
      e.set_location(std::move(at));
    }
    throw;
  }
}

// The outer profile closed along the axis: the shape a potter's rib (or a
// jigger template) is cut to, at the size it is made (the master).
CutLoop profile_template(const CompositeCurve& profile, double tolerance) {
  std::vector<Segment> segments = profile.segments();
  if (!profile.closed()) {
    const Vec2 start = segments.front().point(0.0), end = segments.back().point(1.0);
    const Vec2 axis_end(0.0, end.y()), axis_start(0.0, start.y());
    if (end.x() != 0.0) segments.push_back(Segment::line(end, axis_end));
    if (axis_end != axis_start) segments.push_back(Segment::line(axis_end, axis_start));
    if (start.x() != 0.0) segments.push_back(Segment::line(axis_start, start));
  }
  CutLoopOptions options;
  options.tolerance = tolerance;
  return cut_loop(CompositeCurve(std::move(segments), true), "profile template", true, options);
}

std::vector<double> size_of(const Vec3& lo, const Vec3& hi) {
  const Vec3 s = hi - lo;
  return {s.x(), s.y(), s.z()};
}

void add_line(std::vector<ExactPiece>& loop, const Vec2& a, const Vec2& b);
std::optional<ExactSolid> exact_revolution(const CompositeCurve& profile, const VesselSection& section);

// The mould as exact solids, from the mould's blocks and keys and the exact
// master profile (the mesh's cavity is that profile sampled).
ExactMould exact_mould(const Mould& mould, const CompositeCurve& master, const MouldOptions& options) {
  const MouldSection& s = mould.section;
  ExactMould exact;
  exact.box = options.block == BlockShape::Box;
  exact.block_radius = s.block_radius;
  exact.volume = mould.block_volume - mould.cavity_volume + mould.key_volume;
  // Down the profile from the rim, to the axis, up it past the block's top,
  // and back down the reservoir's wall (continued upward) to the rim.
  const std::vector<Segment>& segments = master.segments();
  const bool upward = segments.back().point(1.0).y() > segments.front().point(0.0).y();
  std::vector<ExactPiece>& loop = exact.cavity;
  if (upward) {
    for (auto g = segments.rbegin(); g != segments.rend(); ++g) loop.push_back({*g, {}, 1.0, 0.0});
  } else {
    loop = exact_pieces(master);
  }
  const Vec2 rim = upward ? segments.back().point(1.0) : segments.front().point(0.0);
  const Vec2 base = upward ? segments.front().point(0.0) : segments.back().point(1.0);
  const double z_above = s.z_top + options.spare;
  const double r_above =
      rim.x() + (s.opening_radius - s.rim_radius) * (z_above - rim.y()) / (s.z_top - rim.y());
  add_line(loop, base, Vec2(0.0, base.y()));
  add_line(loop, Vec2(0.0, base.y()), Vec2(0.0, z_above));
  add_line(loop, Vec2(0.0, z_above), Vec2(r_above, z_above));
  add_line(loop, Vec2(r_above, z_above), rim);
  for (const MouldPart& p : mould.parts) {
    ExactMould::Part part;
    const bool side = p.kind == MouldPartKind::Side;
    part.z_low = side && s.has_cut ? s.z_cut : s.z_bottom;
    part.z_high = side ? s.z_top : s.z_cut;
    part.from_angle = p.from_angle;
    part.to_angle = p.to_angle;
    for (const KeyFeature& k : p.keys) part.keys.push_back({k.centre, k.axis, k.radius, k.bump});
    exact.parts.push_back(std::move(part));
  }
  return exact;
}

// The master's profile: the vessel's outer profile as written and, with a
// mould, the spare's wall from the rim up to the spare's top and its top
// across to the axis, so that it revolves into the master standing on the
// vessel's base with the spare on its rim (the mould cavity's shape).
CompositeCurve master_profile(const CompositeCurve& master, const MouldSection* spare) {
  if (spare == nullptr) return master;
  std::vector<Segment> segments = master.segments();
  const Vec2 opening(spare->opening_radius, spare->z_top), top(0.0, spare->z_top);
  if (segments.back().point(1.0).y() > segments.front().point(0.0).y()) {  // upward: the rim is its end
    const Vec2 rim = segments.back().point(1.0);
    segments.push_back(Segment::line(rim, opening));
    segments.push_back(Segment::line(opening, top));
  } else {
    const Vec2 rim = segments.front().point(0.0);
    segments.insert(segments.begin(), {Segment::line(top, opening), Segment::line(opening, rim)});
  }
  return CompositeCurve(std::move(segments), false);
}

// How many pieces through its axis a master of `radius` needs to stand on a
// bed `bed` wide (x, y), each standing upright, its joint pin (`pin` long)
// standing out of one cut face: 1 (whole), 2 (halves), 4 (quarters), or 0
// when even a quarter is too wide.
int sectors_for_bed(double radius, double pin, const Vec3& bed) {
  const auto fits = [&](double a, double b) {
    return (a <= bed.x() && b <= bed.y()) || (b <= bed.x() && a <= bed.y());
  };
  if (fits(2.0 * radius, 2.0 * radius)) return 1;
  if (fits(2.0 * radius, radius + pin)) return 2;
  if (fits(radius + pin, radius)) return 4;
  return 0;
}

// With print.bed: a master taller than the bed cut into sections with pins,
// one wider than it into halves or quarters (each section), pinned across
// each joint (their facts in `facts`, their pieces in `products`); or a
// warning for one too wide even in quarters; nothing when it fits.
std::optional<MasterSplit> cut_for_bed(const VesselDesign& design, const VesselMesh& mesh,
                                       const BoundingBox& box, const BuildContext& context, Facts& facts,
                                       Result& out, VesselProducts& products) {
  if (!design.print || !design.print->bed) return std::nullopt;
  const Vec3& bed = *design.print->bed;
  const Vec3 size = box.hi - box.lo;
  double radius = 0.0;
  for (const auto& loop : mesh.section.loops) {
    for (const Vec2& p : loop) radius = std::max(radius, p.x());
  }
  const int sectors = sectors_for_bed(radius, design.print->pin_diameter, bed);
  facts.set("fits_bed", sectors == 1 && size.z() <= bed.z());
  const double across = std::min(bed.x(), bed.y());
  if (!(sectors == 1 && size.z() <= bed.z()) && !(across > design.print->pin_diameter)) {
    // Cut, its sections could not hold their pins.
    throw RangeError(
        "print.bed", across,
        fmt::format("the bed's width {:.6g} leaves no room for a section beside its "
                    "registration pin ({:.6g} across: pin_diameter), and the master ({:.6g} x "
                    "{:.6g} {}) does not fit it whole; use a smaller pin_diameter",
                    across, design.print->pin_diameter, 2.0 * radius, size.z(), context.common.units),
        ErrorLocation{"print.bed"});
  }
  if (sectors == 0) {
    out.warnings.push_back(fmt::format(
        "{}: the master ({:.6g} {} across) is wider than the bed {:g} x {:g} {} even in quarters (each "
        "{:.6g} x {:.6g} {} with its joint's pin); print it on a larger printer",
        key_label(context.common, "print.bed"), 2.0 * radius, context.common.units, bed.x(), bed.y(),
        context.common.units, radius + design.print->pin_diameter, radius, context.common.units));
    return std::nullopt;
  }
  if (sectors == 1 && size.z() <= bed.z()) return std::nullopt;
  if (mesh.section.loops.size() != 1) {
    throw GeometryError("print.bed", fmt::format("the master is {} bodies (its profile runs along the axis "
                                                 "between them): fabmesh cuts one body into sections",
                                                 mesh.section.loops.size()));
  }
  MasterSplitOptions so;
  so.bed_height = bed.z();
  so.pin_diameter = design.print->pin_diameter;
  so.pin_clearance = design.print->pin_clearance;
  so.segments = mesh.segments;
  so.sectors = sectors;
  MasterSplit split = split_master(mesh.section.loops.front(), so);
  // The print checks' finding that the vessel does not fit the bed: its master is printed in pieces.
  const std::string too_big = key_label(context.common, "print.bed") + ": the vessel (";
  const std::size_t levels = split.sections.size() / static_cast<std::size_t>(sectors);
  const std::string pieces =
      sectors == 1 ? fmt::format("{} sections", levels)
                   : fmt::format("{} {}", split.sections.size(),
                                 levels == 1 ? (sectors == 2 ? "halves" : "quarters")
                                             : fmt::format("pieces ({} sections, each in {})", levels,
                                                           sectors == 2 ? "halves" : "quarters"));
  for (std::string& w : out.warnings) {
    if (w.rfind(too_big, 0) == 0) w += fmt::format("; its casting master is cut into {} that fit it", pieces);
  }
  std::vector<Facts> sections;
  MasterSections cut;
  for (const MasterSection& s : split.sections) {
    Facts f;
    f.set("name", s.name)
        .set("z_low", s.z_low)
        .set("z_high", s.z_high)
        .set("height", s.z_high - s.z_low + (s.pin ? split.pin_height : 0.0))
        .set("pin", s.pin)
        .set("hole", s.hole);
    if (s.sector()) {
      f.set("from_deg", 90.0 * s.from_quadrant)
          .set("to_deg", 90.0 * s.to_quadrant)
          .set("joint_pin", std::vector<double>{s.joint_pin.x(), s.joint_pin.y()});
    }
    f.set("volume", s.volume);
    sections.push_back(std::move(f));
    cut.sections.push_back(
        {s.name, s.z_low, s.z_high, s.pin, s.hole, s.from_quadrant, s.to_quadrant, s.joint_pin});
  }
  Facts pin;
  pin.set("diameter", so.pin_diameter)
      .set("height", split.pin_height)
      .set("clearance", so.pin_clearance)
      .set("hole_diameter", 2.0 * split.hole_radius)
      .set("hole_depth", split.hole_depth);
  facts.set("sectors", sectors).set("sections", std::move(sections)).set("pin", std::move(pin));
  cut.pin_radius = 0.5 * so.pin_diameter;
  cut.pin_height = split.pin_height;
  cut.hole_radius = split.hole_radius;
  cut.hole_depth = split.hole_depth;
  cut.enclosing_radius = 2.0 * std::max(size.x(), size.y()) + 1.0;
  products.master_sections = std::move(cut);
  return split;
}

// The casting master (outputs master_stl, master_3mf, master_step): the
// solid revolution of master_profile, proven like the vessel (a simple
// section revolved on a closed grid), with its exact solid and its exact
// volume (Pappus: the mould's cavity volume when it has the spare).
void add_master(const VesselDesign& design, const CompositeCurve& master, const MouldSection* spare,
                const BuildContext& context, Result& out, VesselProducts& products) {
  const CompositeCurve profile = master_profile(master, spare);
  VesselOptions options;
  options.mode = BodyMode::Solid;
  options.tolerance = context.tolerance;
  options.max_triangles = design.max_triangles;
  options.max_bytes = context.memory_limit;
  options.name_key = [&](const std::string& key) { return key_label(context.common, key); };
  VesselMesh mesh = build_vessel(profile, options);
  context.watch.lap("master");
  products.master = exact_revolution(profile, mesh.section);
  out.max_deviation = std::max(out.max_deviation, mesh.max_deviation);
  append_shares(out.tolerance_shares, "master: ", mesh.tolerance_shares);
  const BoundingBox box = bounding_box(mesh.soup.vertices);
  Facts facts;
  facts.set("spare", spare != nullptr)
      .set("volume", solid_of_revolution_volume(profile))
      .set("size", size_of(box.lo, box.hi))
      .set("triangles", mesh.soup.triangles.size())
      .set("max_deviation", mesh.max_deviation);
  std::optional<MasterSplit> split = cut_for_bed(design, mesh, box, context, facts, out, products);
  out.facts.set("master", std::move(facts));
  if (split) {
    // Each section is a part of its own, in the master's frame (together they are the master).
    for (MasterSection& s : split->sections) {
      Part part;
      part.name = s.name;
      part.role = PartRole::Master;
      part.mesh = std::move(s.soup);
      part.proofs.topology = std::move(s.topology);
      part.proofs.embedding = std::move(s.proof);
      out.parts.push_back(std::move(part));
    }
    return;
  }
  Part part;
  part.name = "master";
  part.role = PartRole::Master;
  part.mesh = std::move(mesh.soup);
  part.proofs.topology = std::move(mesh.topology);
  part.proofs.embedding = std::move(mesh.proof);
  out.parts.push_back(std::move(part));
}

// Plaster and water by weight (g) for `millilitres` of set plaster: the mix
// fills its volume with the plaster's solid (its density) and the water
// (1 g/ml), at plaster_ratio grams of plaster to each gram of water; air left
// out, so a lower bound of what the mix needs.
struct CastingWeights {
  double plaster = 0.0;
  double water = 0.0;
};

CastingWeights casting_weights(const VesselDesign& design, double millilitres) {
  const double plaster = millilitres / (1.0 / design.plaster_density + 1.0 / design.plaster_ratio);
  return {plaster, plaster / design.plaster_ratio};
}

// A pin's size, for the report.
Facts pin_facts(const CasePin& pin) {
  return Facts()
      .set("diameter", 2.0 * pin.radius)
      .set("height", pin.height)
      .set("hole_diameter", 2.0 * pin.hole_radius)
      .set("hole_depth", pin.hole_depth)
      .set("sides", pin.sides);
}

// Where the casting cases' pieces are written: side by side along x, `gap`
// apart, in rows no wider than `width` (a wider piece has a row of its
// own), the rows `gap` apart along y, so that the coordinates stay small
// for the files' single-precision floats.
class Shelf {
 public:
  Shelf(double gap, double width) : gap_(gap), width_(width) {}

  /// The corner a piece of `size` is written from.
  Vec3 place(const Vec3& size) {
    if (x_ > 0.0 && x_ + size.x() > width_) {
      y_ += depth_ + gap_;
      x_ = 0.0;
      depth_ = 0.0;
    }
    Vec3 corner(x_, y_, 0.0);
    x_ += size.x() + gap_;
    depth_ = std::max(depth_, size.y());
    return corner;
  }

 private:
  double gap_, width_;
  double x_ = 0.0, y_ = 0.0, depth_ = 0.0;
};

// The sections of a case's piece `name` as parts of their own, validated in
// full, written where `shelf` places them, and their facts.
std::vector<Facts> case_sections(SectionedPiece& cut, const std::string& name, Shelf& shelf, Result& out) {
  std::vector<Facts> facts;
  for (std::size_t n = 0; n < cut.sections.size(); ++n) {
    CaseSection& s = cut.sections[n];
    Part part;
    part.name = fmt::format("{}-section-{}", name, n + 1);
    part.role = PartRole::Case;
    const Vec3 size = bounding_box(s.soup.vertices).size();
    const Vec3 corner = shelf.place(size);
    part.mesh = standing(s.soup, Vec3::UnitZ(), corner);  // as it stands, moved to its corner
    validate_part(part);
    facts.push_back(Facts()
                        .set("name", part.name)
                        .set("cell", std::vector<double>{s.cell[0] + 1.0, s.cell[1] + 1.0, s.cell[2] + 1.0})
                        .set("size", std::vector<double>{size.x(), size.y(), size.z()})
                        .set("written_from", std::vector<double>{corner.x(), corner.y(), corner.z()})
                        .set("triangles", part.mesh.triangles.size())
                        .set("volume", part.validation.volume)
                        .set("pins", s.pins)
                        .set("holes", s.holes));
    out.parts.push_back(std::move(part));
  }
  return facts;
}

// The casting case of each of the mould's parts (outputs case_stl, case_3mf),
// after the parts (the last of `out.parts`): parts of their own, validated
// in full, a two-piece case's plate after its case. A part no case releases
// has none, and its reason is kept for the outputs and the report.
std::vector<Facts> add_cases(const VesselDesign& design, const Mould& mould, const BuildContext& context,
                             Result& out, VesselProducts& products) {
  const std::size_t first = out.parts.size() - mould.parts.size();
  std::vector<Facts> cases;
  // Written standing on their floors (plates on their outer faces), side by
  // side along x 10 mm apart, in rows of at most a metre.
  const double mm = millimetres_per_unit(context.common.units);
  Shelf shelf(10.0 / mm, 1000.0 / mm);
  CaseOptions case_options = design.casting_case;
  case_options.tolerance = context.tolerance;
  // The mould's outside: a part's flat faces on it touch no other part, and lean by the draft.
  BoundingBox outside;
  for (std::size_t i = 0; i < mould.parts.size(); ++i) {
    const BoundingBox b = bounding_box(out.parts[first + i].mesh.vertices);  // the parts' meshes moved there
    outside.lo = outside.lo.cwiseMin(b.lo);
    outside.hi = outside.hi.cwiseMax(b.hi);
  }
  case_options.outside = outside;
  // A cylinder block's back is curved: its side parts' cases are lidded.
  if (design.mould->block == BlockShape::Cylinder) case_options.cylinder_radius = mould.section.block_radius;
  for (std::size_t i = 0; i < mould.parts.size(); ++i) {
    const MouldPart& p = mould.parts[i];
    const std::string name = out.parts[first + i].name;  // copied: the cases are added to out.parts
    const double mid = 0.5 * (p.from_angle + p.to_angle);
    const Vec3 outward =
        p.kind == MouldPartKind::Base ? Vec3(0.0, 0.0, -1.0) : Vec3(std::cos(mid), std::sin(mid), 0.0);
    // The key a point is on, for the reasons a case is refused.
    const auto what_is_at = [&p](const Vec3& at) -> std::string {
      for (const KeyFeature& k : p.keys) {
        if ((at - k.centre).norm() > 1.001 * k.radius) continue;
        if (k.on_base) return ", on a base key's socket in its bottom,";
        const double deg = std::atan2(k.centre.y(), k.centre.x()) * 180.0 / M_PI;
        return fmt::format(", on the {} of a key on its split face at {:.4g} degrees,",
                           k.bump ? "bump" : "socket", deg < -1e-9 ? deg + 360.0 : std::max(deg, 0.0));
      }
      return {};
    };
    Facts facts;
    facts.set("part", name);
    try {
      const CastingCase c = build_casting_case(out.parts[first + i].mesh, name, outward, case_options,
                                               what_is_at, split_faces(p));
      VesselProducts::CaseBox box{"case-" + name, i,        c.lo, c.hi, c.pull, c.opening,
                                  std::nullopt,   c.carved, {},   {}};
      // A piece of the case as it is printed (standing at the origin),
      // validated in full where it is written, its facts; with a bed it does
      // not fit, its sections (each validated in full) in its place.
      const auto piece = [&](const std::string& piece_name, TriangleSoup printed, const Vec3& pull,
                             const char* standing_on) {
        Part part;
        part.name = piece_name;
        part.role = PartRole::Case;
        part.mesh = std::move(printed);
        const Vec3 size = bounding_box(part.mesh.vertices).size();
        const Vec3* bed = design.print && design.print->bed ? &*design.print->bed : nullptr;
        std::optional<SectionedPiece> cut;
        if (bed != nullptr && !fits_bed(size, *bed)) {
          validate_part(part);  // the cut needs a valid solid; an invalid one is reported whole
          try {
            if (part.validation.valid()) cut = cut_case_piece(part.mesh, part.name, *bed, case_options);
          } catch (const GeometryError& e) {
            out.warnings.push_back(fmt::format(
                "{}: {} ({:.6g} x {:.6g} x {:.6g} {} standing on its {}) does not fit the bed {:g} x {:g} x "
                "{:g} {} and is written whole: {}",
                key_label(context.common, "print.bed"), part.name, size.x(), size.y(), size.z(),
                context.common.units, standing_on, bed->x(), bed->y(), bed->z(), context.common.units,
                e.what()));
          }
        }
        Facts f;
        f.set("name", part.name)
            .set("pull", std::vector<double>{pull.x(), pull.y(), pull.z()})
            .set("size", std::vector<double>{size.x(), size.y(), size.z()});
        if (!cut) {
          const Vec3 corner = shelf.place(size);
          part.mesh = standing(part.mesh, Vec3::UnitZ(), corner);  // as it stands, moved to its corner
          validate_part(part);
          f.set("written_from", std::vector<double>{corner.x(), corner.y(), corner.z()});
        }
        f.set("triangles", part.mesh.triangles.size()).set("volume", part.validation.volume);
        if (bed != nullptr) f.set("fits_bed", fits_bed(size, *bed));
        if (cut) {
          // Written in its sections instead.
          f.set("cells",
                std::vector<double>{static_cast<double>(cut->counts[0]), static_cast<double>(cut->counts[1]),
                                    static_cast<double>(cut->counts[2])})
              .set("sections", case_sections(*cut, part.name, shelf, out))
              .set("section_pin", pin_facts(cut->pins.front()))
              .set("sections_volume_error", cut->volume_error);
          return f;
        }
        out.parts.push_back(std::move(part));
        return f;
      };
      Facts whole = piece(box.name, standing(c, Vec3::Zero()), c.pull, "floor");
      for (const char* fact : {"name", "pull", "size", "written_from"}) {
        if (const Facts::Value* v = whole.find(fact)) facts.set(fact, *v);
      }
      facts.set("wall", design.casting_case.wall)
          .set("clearance", design.casting_case.clearance)
          .set("opening", std::vector<double>{c.opening.x(), c.opening.y(), c.opening.z()})
          .set("opening_area", c.pour_area);
      // The part as the case casts it: its free faces along the pull leaned.
      std::vector<std::string> leaned;
      for (const CaseDraft& d : c.drafts) leaned.push_back(d.face);
      box.drafts = c.drafts;
      facts.set("draft", Facts()
                             .set("deg", design.casting_case.draft_deg)
                             .set("faces", std::move(leaned))
                             .set("volume", c.draft_volume)
                             .set("volume_error", c.draft_volume_error)
                             .set("part_volume", out.parts[first + i].validation.volume - c.draft_volume)
                             .set("not_leaned", c.undrafted));
      for (const char* fact : {"triangles", "volume"}) facts.set(fact, *whole.find(fact));
      facts.set("release", c.release_proof);
      for (const char* fact : {"fits_bed", "cells", "sections", "section_pin", "sections_volume_error"}) {
        if (const Facts::Value* v = whole.find(fact)) facts.set(fact, *v);
      }
      // A piece taken off first: its facts, with its pins where they stand
      // in the mould's frame (as the STEP file has the case assembled).
      const auto plate_facts = [&](const CasePlate& cp, const std::string& piece_name) {
        Facts plate = piece(piece_name, standing(cp, Vec3::Zero()), cp.pull, "outer face");
        plate.set("features", cp.features);
        std::vector<Facts> pins;
        for (const CasePin& pin : cp.pins) {
          pins.push_back(Facts()
                             .set("at", std::vector<double>{pin.base.x(), pin.base.y(), pin.base.z()})
                             .set("axis", std::vector<double>{pin.axis.x(), pin.axis.y(), pin.axis.z()}));
        }
        if (!cp.pins.empty()) {
          const CasePin& pin = cp.pins.front();
          plate.set("pins", std::move(pins)).set("pin", pin_facts(pin));
        }
        return plate;
      };
      if (c.carved) {
        // Carved in several pieces, taken off in order before the part comes out.
        std::vector<Facts> pieces;
        for (std::size_t n = 0; n < c.plates.size(); ++n) {
          const CasePlate& cp = c.plates[n];
          const std::string piece_name = fmt::format("{}-piece-{}", box.name, n + 1);
          Facts f = plate_facts(cp, piece_name);
          VesselProducts::CaseBox::Piece region{
              piece_name, cp.corner,       cp.u, cp.v,    cp.d, cp.face_axis, cp.face_at,
              cp.hollow,  cp.hollow_along, {},   cp.cores};
          for (const CasePin& pin : cp.pins) {
            // The cylinder from its end inside the piece, `buried` behind the seam.
            region.pins.push_back({pin.base - pin.buried * pin.axis, pin.axis, pin.radius,
                                   pin.buried + pin.height, pin.hole_radius, pin.buried + pin.hole_depth});
          }
          box.pieces.push_back(std::move(region));
          f.set("beyond", cp.face);
          pieces.push_back(std::move(f));
        }
        facts.set("pieces", std::move(pieces));
      } else if (!c.plates.empty()) {
        // The plate under the part's keyed face: a piece of its own, off first.
        const CasePlate& cp = c.plates.front();
        box.plate = VesselProducts::CaseBox::Plate{box.name + "-plate", cp.lo, cp.hi, cp.pull, {}};
        for (const CasePin& pin : cp.pins) {
          box.plate->pins.push_back(
              {pin.base, pin.axis, pin.radius, pin.height, pin.hole_radius, pin.hole_depth});
        }
        facts.set("plate", plate_facts(cp, box.plate->name));
      }
      products.cases.push_back(std::move(box));
    } catch (const GeometryError& e) {
      facts.set("refused", e.what());
      products.case_refusals.push_back(e.what());
      out.warnings.push_back(fmt::format("case: {}", e.what()));
    }
    cases.push_back(std::move(facts));
  }
  return cases;
}

// The mould's parts, each with its proof of embedding, what a workshop
// needs to know, and the mould as exact solids.
MouldSection add_mould(const VesselDesign& design, const CompositeCurve& fired_profile,
                       const CompositeCurve& master, const BuildContext& context, Result& out,
                       VesselProducts& products) {
  MouldOptions options = *design.mould;
  options.tolerance = context.tolerance;
  Mould mould = keyed_in("vessel.mould", "mould.", [&] { return build_mould(fired_profile, options); });
  products.mould = exact_mould(mould, master, options);
  std::size_t sides = 0;
  std::vector<Facts> parts;
  for (std::size_t i = 0; i < mould.parts.size(); ++i) {
    MouldPart& p = mould.parts[i];
    const bool side = p.kind == MouldPartKind::Side;
    Part part;
    part.name = side ? fmt::format("side-{}", ++sides) : p.name;  // "side 1 of 2" -> "side-1"; "base"
    part.role = side ? PartRole::MouldSide : PartRole::MouldBase;
    part.mesh = std::move(p.soup);
    part.proofs.embedding = p.proof;
    validate_part(part);  // its verdict is one of the mould's facts
    const ValidationReport& v = part.validation;
    Facts facts;
    facts.set("genus", v.genus ? Facts::Value(std::int64_t{*v.genus}) : Facts::Value(nullptr))
        .set("name", part.name)
        .set("self_intersection", to_string(v.self_intersection))
        .set("triangles", part.mesh.triangles.size())
        .set("volume", v.volume);
    parts.push_back(std::move(facts));
    products.mould->parts[i].name = part.name;
    out.parts.push_back(std::move(part));
  }
  context.watch.lap("mould");
  out.max_deviation = std::max(out.max_deviation, mould.max_deviation);
  append_shares(out.tolerance_shares, "mould: ", mould.tolerance_shares);
  // What a potter weighs, from the exact volumes (model units^3 -> ml).
  const double ml = std::pow(millimetres_per_unit(context.common.units), 3) / 1000.0;
  const CastingWeights total = casting_weights(design, mould.plaster_volume * ml);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    // Each part's plaster: its mesh's volume (within the build's deviation of the exact part).
    const CastingWeights part =
        casting_weights(design, out.parts[out.parts.size() - parts.size() + i].validation.volume * ml);
    parts[i].set("plaster_grams", part.plaster).set("water_grams", part.water);
  }
  Facts facts;
  facts.set("parts", std::move(parts))
      .set("plaster_ratio", design.plaster_ratio)
      .set("plaster_density", design.plaster_density)
      .set("slip_density", design.slip_density)
      .set("plaster_grams", total.plaster)
      .set("water_grams", total.water)
      .set("slip_millilitres", mould.cavity_volume * ml)
      .set("slip_grams", mould.cavity_volume * ml * design.slip_density)
      .set("slip_volume", mould.cavity_volume)
      .set("plaster_volume", mould.plaster_volume)
      .set("block_volume", mould.block_volume)
      .set("spare_volume", mould.spare_volume)
      .set("vessel_volume", mould.vessel_volume)
      .set("volume_identity_error_bound", mould.volume_error_bound)
      .set("max_deviation", mould.max_deviation)
      .set("release", mould.release_proof)
      .set("warnings", mould.warnings);
  if (context.wants_cases) facts.set("cases", add_cases(design, mould, context, out, products));
  out.facts.set("mould", std::move(facts));
  return std::move(mould.section);
}

// Appends the line from `a` to `b`, unless they are one point.
void add_line(std::vector<ExactPiece>& loop, const Vec2& a, const Vec2& b) {
  if (a != b) loop.push_back({Segment::line(a, b), {}, 0.0, 1.0});
}

// True for a line along the axis.
bool on_axis(const Segment& s) {
  return s.kind() == SegmentKind::Line && s.control_points()[0].x() == 0.0 &&
         s.control_points()[1].x() == 0.0;
}

// A vessel's exact section, as its mesh's section closes it: a solid's
// profile closed along the rim and base levels to the axis and along the
// axis (one loop per part when it runs along the axis between parts, each
// part its own body); a shell's profile, the rim, the inner wall (arcs of the
// profile's offset and straight pieces), the base to the axis, the axis and
// the bottom. None for a shell that runs along the axis.
std::optional<ExactSolid> exact_revolution(const CompositeCurve& profile, const VesselSection& section) {
  const std::vector<Segment>& segments = profile.segments();
  const bool axis_runs = std::any_of(segments.begin(), segments.end(), on_axis);
  if (axis_runs && section.inner_wall) return std::nullopt;
  ExactSolid solid;
  solid.form = ExactSolid::Form::Revolution;
  if (profile.closed()) {
    solid.loops.push_back(exact_pieces(profile));
    return solid;
  }
  // From the base up to the rim, in runs off the axis.
  const bool upward = segments.back().point(1.0).y() > segments.front().point(0.0).y();
  std::vector<std::vector<ExactPiece>> runs(1);
  const auto add = [&](const ExactPiece& piece) {
    if (!on_axis(piece.segment)) {
      runs.back().push_back(piece);
    } else if (!runs.back().empty()) {
      runs.emplace_back();
    }
  };
  if (upward) {
    for (const Segment& s : segments) add({s, {}, 0.0, 1.0});
  } else {
    for (auto s = segments.rbegin(); s != segments.rend(); ++s) add({*s, {}, 1.0, 0.0});
  }
  if (runs.back().empty()) runs.pop_back();
  for (std::vector<ExactPiece>& loop : runs) {
    const auto end_of = [](const ExactPiece& p) { return p.segment.point(p.s1); };
    const Vec2 bottom = loop.front().segment.point(loop.front().s0);
    const Vec2 top = end_of(loop.back());
    Vec2 last = top;
    if (const auto& wall = section.inner_wall) {
      add_line(loop, top, wall->points.front().point);
      for (ExactPiece& piece : inner_wall_exact_pieces(*wall, profile)) loop.push_back(std::move(piece));
      last = wall->points.back().point;
    }
    add_line(loop, last, Vec2(0.0, last.y()));
    add_line(loop, Vec2(0.0, last.y()), Vec2(0.0, bottom.y()));
    add_line(loop, Vec2(0.0, bottom.y()), bottom);
    solid.loops.push_back(std::move(loop));
  }
  return solid;
}

std::vector<double> coordinates(const Vec2& p) { return {p.x(), p.y()}; }

// The print checks in one line, for the HTML report and the studio.
std::string print_check_line(const PrintCheck& check, const PrintOptions& options) {
  const std::string& u = options.units;
  // To 4 significant digits of the size: a refined point 1e-7 above the foot is at z 0.
  const double extent = check.size.maxCoeff();
  const auto shown = [extent](double x) { return std::abs(x) < 1e-4 * extent ? 0.0 : x; };
  const auto where = [&](const Vec2& p) {
    return fmt::format("r {:.4g}, z {:.4g}", shown(p.x()), shown(p.y()));
  };
  std::string text =
      fmt::format("printed upright: outer wall overhangs at most {:.3g} degrees", check.outer.angle_deg);
  if (check.outer.angle_deg > 0.0) text += fmt::format(" (at {})", where(check.outer.at));
  if (check.inner) {
    text += fmt::format(", inner wall {:.3g} degrees", check.inner->angle_deg);
    if (check.inner->angle_deg > 0.0) text += fmt::format(" (at {})", where(check.inner->at));
  }
  if (check.rim) text += fmt::format(", rim {:.3g} degrees", check.rim->angle_deg);
  text += fmt::format(" (limit {:g} degrees)", options.max_overhang_deg);
  text += check.widest_ledge
              ? fmt::format("; widest unsupported ledge {:.4g} {}", check.runs[*check.widest_ledge].width, u)
              : std::string("; no unsupported ledge");
  if (!std::isnan(check.min_wall)) text += fmt::format("; thinnest wall {:.4g} {}", check.min_wall, u);
  text += fmt::format("; {:.5g} {} across, {:.5g} {} tall", check.size.x(), u, check.size.z(), u);
  if (options.bed) {
    text += fmt::format(", {} the bed {:g} x {:g} x {:g} {}",
                        check.fits_bed.value_or(false) ? "fits" : "does not fit", options.bed->x(),
                        options.bed->y(), options.bed->z(), u);
  }
  return text;
}

// The print checks of the vessel as written (the master, printed upright),
// reported as `build.print`; with the design's `print` limits, what they find
// is a warning each, or with `print.strict` bad input at the limit's key.
// The overhangs beyond the limit are kept, at the fired size, for the plot.
void add_print_checks(const VesselDesign& design, const CompositeCurve& master, const VesselSection& section,
                      double factor, const BuildContext& context, Result& out, VesselProducts& products) {
  PrintOptions options = design.print.value_or(PrintOptions{});
  if (!design.print) options.min_wall /= millimetres_per_unit(context.common.units);  // the default's 1.2 mm
  options.units = context.common.units;
  const PrintCheck check = check_print(master, section, options);
  if (design.print && design.print->strict && !check.findings.empty()) {
    std::string message =
        "the vessel does not print upright within print's limits: " + check.findings.front().message;
    for (std::size_t i = 1; i < check.findings.size(); ++i) message += "; " + check.findings[i].message;
    throw GeometryError(check.findings.front().key, message);
  }
  const auto overhang = [](const Overhang& o) {
    Facts f;
    return std::move(f.set("angle_deg", o.angle_deg).set("at", coordinates(o.at)));
  };
  Facts facts;
  facts.set("max_overhang_deg", options.max_overhang_deg).set("outer", overhang(check.outer));
  if (check.inner) facts.set("inner", overhang(*check.inner));
  if (check.rim) facts.set("rim", overhang(*check.rim));
  std::vector<Facts> runs;
  for (const OverhangRun& r : check.runs) {
    Facts f;
    f.set("face", to_string(r.face))
        .set("from", coordinates(r.from))
        .set("to", coordinates(r.to))
        .set("ledge", r.width)
        .set("max_angle_deg", r.max_angle_deg);
    runs.push_back(std::move(f));
    if (!design.print) continue;  // the plot flags them for a design that prints
    std::vector<Vec2> fired = r.points;
    for (Vec2& p : fired) p /= factor;
    products.overhangs.push_back(std::move(fired));
  }
  products.overhang_limit_deg = options.max_overhang_deg;
  facts.set("overhangs", std::move(runs))
      .set("widest_ledge", check.widest_ledge ? check.runs[*check.widest_ledge].width : 0.0);
  if (!std::isnan(check.min_wall)) {
    facts.set("min_wall", check.min_wall).set("min_wall_where", check.min_wall_where);
    facts.set("min_wall_limit", options.min_wall);
  }
  facts.set("size", std::vector<double>{check.size.x(), check.size.y(), check.size.z()});
  if (options.bed) {
    facts.set("bed", std::vector<double>{options.bed->x(), options.bed->y(), options.bed->z()})
        .set("fits_bed", check.fits_bed.value_or(false));
  }
  facts.set("summary", print_check_line(check, options));
  std::vector<std::string> findings;
  for (const PrintFinding& f : check.findings) findings.push_back(f.message);
  facts.set("checked", design.print.has_value()).set("findings", findings);
  if (design.print) {
    for (const PrintFinding& f : check.findings)
      out.warnings.push_back(key_label(context.common, f.key) + ": " + f.message);
  }
  out.facts.set("print", std::move(facts));
}

// The section's loops at the fired size (the plot draws the design as fired).
std::vector<std::vector<Vec2>> fired_loops(std::vector<std::vector<Vec2>> loops, double factor) {
  for (auto& loop : loops) {
    for (Vec2& p : loop) p /= factor;
  }
  return loops;
}

}  // namespace

Result build(const VesselDesign& design, const BuildContext& context) {
  const BuiltCurve profile = build_curve(design.profile);
  // What is written is the master: the fired design scaled up for the clay's shrinkage.
  const double factor = shrinkage_factor(design.shrinkage);
  const CompositeCurve master = factor == 1.0 ? profile.curve : scale_curve(profile.curve, factor);
  context.watch.lap("curve");
  VesselOptions options;
  options.mode = design.mode;
  options.wall = design.wall * factor;
  options.base = design.base * factor;
  options.rim = design.rim;
  options.tolerance = context.tolerance;
  options.max_triangles = design.max_triangles;
  options.max_bytes = context.memory_limit;
  options.name_key = [&](const std::string& key) { return key_label(context.common, key); };
  VesselMesh vessel = keyed_in("vessel.body", "body.", [&] {
    try {
      return build_vessel(master, options);
    } catch (const GeometryError& e) {
      if (design.mode != BodyMode::Shell || e.location().key != "wall") throw;
      // A shell over a profile that crosses itself fails at the wall whatever its thickness:
      // say what the solid says (build_vessel_section throws at the crossing), else the wall error.
      VesselSectionOptions solid;
      solid.mode = BodyMode::Solid;
      solid.tolerance = options.tolerance / 2.0;  // the share build_vessel samples the profile with
      solid.name_key = options.name_key;
      build_vessel_section(master, solid);
      throw;
    }
  });
  context.watch.lap("build");
  std::size_t section_points = 0;
  for (const auto& loop : vessel.section.loops) section_points += loop.size();
  Result out;
  Part product;
  product.name = context.common.name;
  product.mesh = std::move(vessel.soup);
  product.proofs.topology = std::move(vessel.topology);  // the revolution grid's connectivity
  product.proofs.embedding = std::move(vessel.proof);    // the simple section's revolution
  out.max_deviation = vessel.max_deviation;
  append_shares(out.tolerance_shares, "", vessel.tolerance_shares);
  out.facts.set("angular_segments", vessel.segments)
      .set("section_loops", vessel.section.loops.size())
      .set("section_points", section_points)
      .set("max_radius", vessel.section.max_radius);
  if (!std::isnan(vessel.section.min_clearance)) {
    // The thinnest place of the shell, between the exact outer and inner surfaces.
    out.facts.set("min_clearance", vessel.section.min_clearance)
        .set("min_clearance_where", vessel.section.clearance_where);
  }
  if (design.shrinkage > 0.0) {
    const BoundingBox box = bounding_box(product.mesh.vertices);
    Facts shrinkage;
    shrinkage.set("shrinkage", design.shrinkage).set("factor", factor);
    if (design.shrinkage_wet > 0.0)
      shrinkage.set("measured", std::vector<double>{design.shrinkage_wet, design.shrinkage_fired});
    shrinkage.set("master_size", size_of(box.lo, box.hi))
        .set("fired_size", size_of(box.lo / factor, box.hi / factor));
    out.facts.set("shrinkage", std::move(shrinkage));
  }
  out.parts.push_back(std::move(product));
  VesselProducts products;
  // Before the mould: a strict print check that fails leaves nothing else to build.
  add_print_checks(design, master, vessel.section, factor, context, out, products);
  context.watch.lap("print");
  if (context.wants_cutting) {
    products.profile_template.push_back(profile_template(master, context.tolerance));
    context.watch.lap("template");
  }
  std::optional<MouldSection> spare;
  if (design.mould) spare = add_mould(design, profile.curve, master, context, out, products);
  if (context.wants_master) add_master(design, master, spare ? &*spare : nullptr, context, out, products);
  out.curves.push_back({"profile", profile});
  products.section = fired_loops(vessel.section.loops, factor);
  products.solid = exact_revolution(master, vessel.section);
  out.products = std::move(products);
  return out;
}

}  // namespace fabmesh
