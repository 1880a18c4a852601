#include "geometry/mould/mould.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/fairing/gauss_legendre.h"
#include "geometry/mesh/revolve.h"
#include "geometry/mesh/volume.h"
#include "geometry/mould/shrinkage.h"

namespace fabmesh {
namespace {

// Pappus: the solid closed to the axis has volume pi |int r^2 dz| along the profile, its lateral surface
// area 2 pi int r |r'| (Gauss-Legendre on each segment).
void pappus(const CompositeCurve& profile, double* volume, double* lateral_area) {
  const QuadratureRule q = gauss_legendre(40);
  double v = 0.0, a = 0.0;
  for (const Segment& s : profile.segments()) {
    for (std::size_t i = 0; i < q.nodes.size(); ++i) {
      const CurveJet j = s.jet(q.nodes[i]);
      v += q.weights[i] * M_PI * j[0].x() * j[0].x() * j[1].y();
      a += q.weights[i] * 2.0 * M_PI * j[0].x() * j[1].norm();
    }
  }
  *volume = std::abs(v);
  *lateral_area = a;
}

}  // namespace

double solid_of_revolution_volume(const CompositeCurve& profile) {
  double volume = 0.0, area = 0.0;
  pappus(profile, &volume, &area);
  return volume;
}

namespace {

MouldSizes sizes_of(const MouldSection& s, double factor) {
  MouldSizes z;
  z.factor = factor;
  z.master_height = s.rim_z - s.base_z;
  for (std::size_t i = s.profile_begin; i < s.profile_end; ++i) {
    z.master_diameter = std::max(z.master_diameter, 2.0 * s.cavity[i].x());
  }
  z.fired_height = z.master_height / factor;
  z.fired_diameter = z.master_diameter / factor;
  return z;
}

// Undercuts and binding keys: bad input unless allowed; the reasons otherwise.
void check_release(Mould& m, const MouldOptions& o) {
  m.undercuts = find_undercuts(m.section.side_cavity, m.section.base_cavity);
  const bool keys_ok = m.keys.centres.empty() || keys_release(o.parts, m.keys.radius, m.keys.socket_radius);
  const double alpha = key_pull_angle(o.parts);
  if (!m.undercuts.empty()) {
    const std::string text = describe_undercuts(m.undercuts);
    if (!o.allow_undercuts) {
      throw GeometryError("profile",
                          fmt::format("the mould cannot be opened: {} (set allow_undercuts to build "
                                      "it anyway)",
                                      text));
    }
    m.warnings.push_back(text);
  }
  if (!keys_ok) {
    const double needed = m.keys.radius / std::cos(alpha) - m.keys.radius;
    const std::string text = fmt::format(
        "with {} parts each part is pulled along its bisector, {:.6g} degrees off its keys' axes: a bump "
        "of radius {} binds in a socket of radius {:.6g}; key_clearance {} must be >= {:.6g} (key_radius "
        "(1 / cos {:.6g} deg - 1))",
        o.parts, alpha * 180.0 / M_PI, m.keys.radius, m.keys.socket_radius, o.key_clearance, needed,
        alpha * 180.0 / M_PI);
    if (!o.allow_undercuts) throw GeometryError("key_clearance", text + " (or set allow_undercuts)");
    m.warnings.push_back(text);
  }
  m.release_proof = fmt::format(
      "side parts: the cavity's boundary above {} never rises walking down from the opening (sampled "
      "section), so every horizontal slice of the cavity is a disc and each part, spanning {:.6g} degrees, "
      "leaves it pulled along its bisector (|p + t d| > |p| when p.d >= 0)",
      m.section.has_cut ? fmt::format("the base cut z = {:.6g}", m.section.z_cut) : std::string("the bottom"),
      360.0 / o.parts);
  if (!m.keys.centres.empty()) {
    m.release_proof += fmt::format(
        "; keys: sockets {:.6g} >= {:.6g} = key radius / cos {:.6g} deg (the pull's angle to their axes)",
        m.keys.socket_radius, m.keys.radius / std::cos(alpha), alpha * 180.0 / M_PI);
  }
  if (m.section.has_cut) {
    m.release_proof +=
        "; base part: the cavity inside it never widens walking from the cut to the axis, so every "
        "vertical line meets it in one interval up to the cut and the base pulls down";
    m.release_proof +=
        m.keys.base_centres.empty()
            ? "; the flat cut carries no keys (a side part slides off it horizontally)"
            : "; the keys on the cut have vertical axes, so the base pulls down off them first "
              "and then the side parts come apart";
  }
  if (!m.warnings.empty())
    m.release_proof = "NOT RELEASABLE as built: " + fmt::format("{}", fmt::join(m.warnings, "; "));
}

std::string side_proof(const Mould& m, const MouldPart& p, const MouldOptions& o) {
  std::string proof = fmt::format(
      "{}; swept from {:.6g} to {:.6g} degrees in {} steps of at most {:.6g} degrees: in each wedge the "
      "half-plane at angle phi meets the lateral mesh in the section with its revolved vertices scaled "
      "radially by cos(step/2)/cos(phi - mid) in [cos(step/2), 1]{} (a simple polygon), so slices at "
      "distinct angles are disjoint simple polygons in disjoint half-planes; the caps are CGAL constrained "
      "Delaunay triangulations of that section (counter-clockwise by the exact orientation predicate) in "
      "the two bounding half-planes, with the keys' circles as holes; each socket lies within its radius "
      "of its centre in every section (|(rho - r_c, z - z_c)| <= |v|), which keeps >= key_margin + sagitta "
      "{:.3g} from the section's boundary, and within asin(r_s / r_c) < 90 degrees of its plane; each bump "
      "lies outside the wedge (angles in (b, b + asin(r / r_c)]) and meets the part only along its base "
      "circle",
      m.section.proof, p.from_angle * 180.0 / M_PI, p.to_angle * 180.0 / M_PI, p.angular_steps,
      m.max_angular_step * 180.0 / M_PI,
      o.block == BlockShape::Box ? " and its block side on the box's flat side (every corner is a sample)"
                                 : "",
      chord_sagitta(m.section.block_radius, m.max_angular_step));
  if (m.keys.base_centres.empty()) return proof;
  return proof +
         fmt::format(
             "; its bottom on the base cut z = {:.6g} is a CGAL constrained Delaunay triangulation of "
             "the plaster there (between the block's and the cavity's rings) with the base keys' "
             "socket circles as holes, so every half-plane meets it at that height only, between the "
             "rings; each socket lies within its radius of its centre in every half-plane and keeps "
             ">= {:.3g} from the cavity above and below the cut, from the block and from the split "
             "planes",
             m.section.z_cut,
             *std::min_element(m.keys.base_clearances.begin(), m.keys.base_clearances.end()));
}

}  // namespace

Mould build_mould(const CompositeCurve& profile, const MouldOptions& o) {
  Mould m;
  StageTimer timer(m.timings_ms);
  check_mould_options(o);
  const double factor = shrinkage_factor(o.shrinkage);
  const CompositeCurve master = scale_curve(profile, factor);
  ToleranceBudget tolerance(o.tolerance);
  m.section = build_mould_section(master, o, tolerance.take("section", 0.5));
  const MouldSection& s = m.section;
  tolerance.use("section", s.max_deviation);
  m.sizes = sizes_of(s, factor);

  // Angular step: sagitta of the largest revolved radius within what the profile sampling left.
  const double revolved_radius = o.block == BlockShape::Box ? s.cavity_radius : s.block_radius;
  const int turn = angular_segments(revolved_radius, tolerance.take_rest("revolution"));
  m.max_angular_step = angular_step(turn);
  const double sagitta = chord_sagitta(revolved_radius, m.max_angular_step);
  tolerance.use("revolution", sagitta);
  m.tolerance_shares = tolerance.shares();
  m.max_deviation = std::max(s.max_deviation + sagitta, 0.0);
  m.keys = place_keys(s, o, sagitta);
  if (!m.keys.centres.empty()) {
    m.max_deviation =
        std::max(m.max_deviation, 2.0 * chord_sagitta(m.keys.socket_radius, angular_step(m.keys.segments)));
  }
  check_release(m, o);
  timer.lap("section");

  std::size_t budget = o.max_triangles;
  for (int k = 0; k < o.parts; ++k) m.splits.push_back(split_plane(k, o.parts));
  for (int k = 0; k < o.parts; ++k) {
    MouldPart part =
        build_side_part(s, m.keys, o, m.splits[k], m.splits[(k + 1) % o.parts], m.max_angular_step, budget);
    part.name = fmt::format("side {} of {}", k + 1, o.parts);
    part.proof = EmbeddingProof();
    part.proof.statement = side_proof(m, part, o);
    budget -= std::min(budget, part.soup.triangles.size());
    m.parts.push_back(std::move(part));
  }
  if (s.has_cut) {
    MouldPart base = build_base_part(s, m.keys, o, m.max_angular_step, budget);
    base.proof.statement = fmt::format(
        "{}; the base section swept all the way round in {} steps of at most {:.6g} degrees: every "
        "half-plane meets it in the section scaled radially about the axis{}, simple, in disjoint "
        "half-planes",
        s.proof, base.angular_steps, m.max_angular_step * 180.0 / M_PI,
        o.block == BlockShape::Box ? " with its block side on the box's flat side" : "");
    if (!m.keys.base_centres.empty()) {
      base.proof.statement += fmt::format(
          "; its top on the cut z = {:.6g} is a CGAL constrained Delaunay triangulation of the annulus "
          "between the block's and the cavity's rings with the keys' circles as holes, so every half-plane "
          "meets it at that height only, between the rings; each bump rises above the cut, where the base "
          "section has nothing, within its radius of its centre",
          s.z_cut);
    }
    m.parts.push_back(std::move(base));
  }
  timer.lap("parts");

  const double h = s.z_top - s.z_bottom, r = s.block_radius;
  m.block_volume = o.block == BlockShape::Box ? 4.0 * r * r * h : M_PI * r * r * h;
  double cavity_area = 0.0;
  pappus(master, &m.vessel_volume, &cavity_area);
  const double r1 = s.rim_radius, r2 = s.opening_radius;
  m.spare_volume = M_PI * o.spare * (r1 * r1 + r1 * r2 + r2 * r2) / 3.0;
  m.cavity_volume = m.vessel_volume + m.spare_volume;
  cavity_area += M_PI * (r1 + r2) * std::hypot(o.spare, r2 - r1);
  const double rs = m.keys.socket_radius, rk = m.keys.radius;
  const auto keys = static_cast<double>(m.splits.size() * m.keys.centres.size() + m.keys.base_centres.size());
  m.key_volume = keys * 2.0 / 3.0 * M_PI * (rk * rk * rk - rs * rs * rs);
  for (const MouldPart& part : m.parts) m.plaster_volume += signed_volume(part.soup);
  // Only curved surfaces deviate: the cavity's, a cylinder's side, the hemispheres (mould.h).
  const double curved = cavity_area + (o.block == BlockShape::Box ? 0.0 : 2.0 * M_PI * r * h) +
                        keys * 2.0 * M_PI * (rk * rk + rs * rs);
  m.volume_error_bound = m.max_deviation * curved;
  return m;
}

}  // namespace fabmesh
