// STEP files of the exact geometry (io/step: written by the OpenCASCADE
// module): each kind's exact shape, and a vessel's mould as exact solids.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/core/errors.h"
#include "geometry/mould/master_sectors.h"
#include "geometry/surfaces/bspline_patch.h"
#include "geometry/surfaces/bspline_shell.h"
#include "io/step/step.h"
#include "pipeline/encoders/encoding.h"

namespace fabmesh {
namespace {

// Exact curves as STEP loops, keeping the largest proven bound of an
// approximated piece (0 while every piece is exact).
class StepLoops {
 public:
  explicit StepLoops(double tolerance) : tolerance_(tolerance) {}
  template <class Curve>
  StepLoop operator()(const Curve& curve) {
    try {
      StepLoopOf l = step_loop(curve, tolerance_);
      added_ = std::max(added_, l.max_error);
      return std::move(l.loop);
    } catch (const InputError& e) {
      throw OutputError("step", std::string("step: ") + e.what());
    }
  }
  double added() const { return added_; }

 private:
  double tolerance_;
  double added_ = 0.0;
};

// The file written, its added error `added` (the curves' approximation) and
// the most any body was made within of its exact solid (a stopped round as
// tall as the edge made smaller by its slack).
Encoded encoded(const EncodeContext& c, StepWritten written, double added) {
  Encoded e;
  e.bytes = std::move(written.bytes);
  e.units = c.common.units;
  double slack = 0.0;
  for (const StepShapeFacts& f : written.bodies) slack = std::max(slack, f.added);
  e.added_error = added + slack;
  return e;
}

Encoded step_file(const EncodeContext& c, const StepModel& model, double added) {
  return encoded(c, write_step(model), added);
}

// `model` written, its bodies' volume as OpenCASCADE integrates them checked
// against `exact` when every piece is exact (`added` 0): a boolean or a
// revolution that lost a face or a key would show. `holds` begins the
// message: "the master as OpenCASCADE built it holds".
Encoded checked_step(const EncodeContext& c, const StepModel& model, double added, double exact,
                     const std::string& holds) {
  StepWritten written = write_step(model);
  double volume = 0.0;
  for (const StepShapeFacts& f : written.bodies) volume += f.volume;
  if (added == 0.0 && !(std::abs(volume - exact) <= 1e-6 * std::abs(exact))) {
    throw OutputError("step", fmt::format("step: {} {:.9g} {}^3, not the exact {:.9g}; nothing is written",
                                          holds, volume, c.common.units, exact));
  }
  return encoded(c, std::move(written), added);
}

// A surface's B-spline faces as one body: sewn into an open shell (Sheet) or
// a closed one (Closed). Border curves agree to the poles' rounding (about
// 1e-13 of the size).
Encoded step_faces(const EncodeContext& c, const PatchNetwork& network, std::vector<BSplineFace> faces,
                   StepForm form, double bound, StepModel model) {
  StepBody body;
  body.name = c.common.name;
  body.form = form;
  body.sewing_tolerance = 1e-7 * network.size;
  body.surfaces = std::move(faces);
  model.bodies.push_back(std::move(body));
  return step_file(c, model, bound);
}

// An open surface as one shell of B-spline faces, one per patch, sewn along
// the shared borders: each patch within what the build left of the
// tolerance (geometry/surfaces/bspline_patch.h), the largest bound the file's
// added error. A thickened one as the closed shell of its sheets and walls
// (geometry/surfaces/bspline_shell.h): a sheet on the surface as above, an
// offset sheet through the proven mesh's grid, within the mesh's bound.
Encoded surface_step(const EncodeContext& c, const SurfaceProducts& surface, StepModel model) {
  const PatchNetwork& network = surface.patches;
  const std::optional<ShellGrid>& grid = surface.shell;
  if (!grid && c.result.purpose == MeshPurpose::Fabrication) {
    throw OutputError("step",
                      "step: the shell's grid was not kept by its build (it did not know a step "
                      "output was asked for)");
  }
  std::vector<BSplineFace> faces;
  double bound = 0.0;
  try {
    if (grid) {
      BSplineShell shell = bspline_shell(network, *grid, c.output_tolerance);
      faces = std::move(shell.faces);
      bound = shell.bound;
    } else {
      BSplineNetwork sheet = bspline_network(network, c.output_tolerance);
      for (std::size_t p = 0; p < sheet.patches.size(); ++p)
        faces.push_back(bspline_face(sheet.patches[p], network.names[p]));
      bound = sheet.max_bound;
    }
  } catch (const InputError& e) {
    throw OutputError("step", std::string("step: ") + e.what());
  }
  return step_faces(c, network, std::move(faces), grid ? StepForm::Closed : StepForm::Sheet, bound,
                    std::move(model));
}

// A countertop's extrusion, or a vessel's revolution (a solid per loop: a
// profile that runs along the axis between parts makes one per part).
Encoded solid_step(const EncodeContext& c, const ExactSolid& solid, StepModel model) {
  StepLoops loop_of(c.output_tolerance);
  StepBody body;
  body.name = c.common.name;
  body.height = solid.height;
  if (solid.form == ExactSolid::Form::Extrusion) {
    body.form = StepForm::Extrusion;
    for (const std::vector<ExactPiece>& loop : solid.loops) body.loops.push_back(loop_of(loop));
    // One curve per exact piece (step_loop), so the flags carry over. A round as tall as the edge
    // that stops on a wall or a seam may be made smaller by half the output's share of the tolerance.
    const ProfileEdges e = profile_edges(solid.edges);
    if (e.top > 0.0 && std::find(solid.profiled.begin(), solid.profiled.end(), true) != solid.profiled.end())
      body.rounds = {e.top, e.bottom, e.chamfer, solid.profiled, 0.5 * c.output_tolerance};
    model.bodies.push_back(std::move(body));
    return step_file(c, model, loop_of.added());
  }
  body.form = StepForm::Revolution;
  for (std::size_t i = 0; i < solid.loops.size(); ++i) {
    StepBody part = body;
    if (solid.loops.size() > 1) part.name += fmt::format(" part {}", i + 1);
    part.loops.push_back(loop_of(solid.loops[i]));
    model.bodies.push_back(std::move(part));
  }
  return step_file(c, model, loop_of.added());
}

// A curve design's curves as a wireframe.
Encoded wireframe_step(const EncodeContext& c, StepModel model) {
  StepLoops loop_of(c.output_tolerance);
  StepBody body;
  body.name = c.common.name;
  body.form = StepForm::Wireframe;
  for (const NamedBuiltCurve& curve : c.result.curves) body.loops.push_back(loop_of(curve.curve.curve));
  model.bodies.push_back(std::move(body));
  return step_file(c, model, loop_of.added());
}

}  // namespace

// The exact shape of the design's kind in the design's unit. Exact segments
// stay exact; an H-Bézier segment becomes a cubic B-spline within what the
// build left of the tolerance, and that bound is the file's added error.
EncodedFiles encode_step_output(const EncodeContext& c) {
  StepModel model;
  model.name = c.common.name;
  model.unit = c.common.units;
  const auto* countertop = std::get_if<CountertopProducts>(&c.result.products);
  if (countertop != nullptr && countertop->kitchen) {
    // A kitchen: one file per piece, its exact solid.
    const KitchenProducts& k = *countertop->kitchen;
    EncodedFiles files;
    for (std::size_t i = 0; i < k.exact.size(); ++i) {
      const std::string& piece = k.split.pieces[i].name;
      if (!k.exact[i].solid) throw OutputError("step", "step: " + k.exact[i].why_not);
      StepModel one = model;
      one.name = c.common.name + " " + piece;
      Encoded e = solid_step(c, *k.exact[i].solid, std::move(one));
      e.suffix = "." + piece + ".step";
      e.parts = {piece};
      files.push_back(std::move(e));
    }
    return files;
  }
  struct Visitor {
    const EncodeContext& c;
    StepModel& model;
    Encoded operator()(const CurveProducts&) const { return wireframe_step(c, std::move(model)); }
    Encoded operator()(const CountertopProducts& p) const {
      if (p.solid.loops.empty())  // a job that plans a step output builds it (JobPlan::wants_exact)
        throw std::logic_error("step: the countertop was built without its exact solid");
      return solid_step(c, p.solid, std::move(model));
    }
    Encoded operator()(const SurfaceProducts& p) const { return surface_step(c, p, std::move(model)); }
    Encoded operator()(const VesselProducts& p) const {
      if (!p.solid)
        throw OutputError("step",
                          "step: a shell whose profile runs along the axis is not written as STEP yet");
      return solid_step(c, *p.solid, std::move(model));
    }
  };
  return {std::visit(Visitor{c, model}, c.result.products)};
}

// The casting master as an exact solid of revolution. Its volume as
// OpenCASCADE integrates it must be the exact one (Pappus on the exact
// profile and spare) when every piece is exact: a lost face would show.
EncodedFiles encode_master_step_output(const EncodeContext& c) {
  const auto& vessel = std::get<VesselProducts>(c.result.products);
  if (!vessel.master) throw std::logic_error("master_step: the master was not built");
  StepModel model;
  model.name = c.common.name + " master";
  model.unit = c.common.units;
  StepLoops loop_of(c.output_tolerance);
  double volume = c.result.facts.group("master").number("volume");
  if (const auto& cut = vessel.master_sections) {
    // Cut for the bed: each section the exact master between its heights, its pin added and its hole
    // taken; together the master plus each joint's pin minus its hole.
    if (vessel.master->loops.size() != 1)
      throw std::logic_error("master_step: a cut master of several bodies");
    const StepLoop loop = loop_of(vessel.master->loops.front());
    std::vector<std::string> parts;
    double joints = 0.0;  // pins (and their holes) across joints: each adds its pin and takes its hole
    double levels = 0.0;
    for (const MasterSections::Section& s : cut->sections) {
      StepBody body;
      body.name = model.name + " " + s.name;
      body.form = StepForm::Slice;
      body.loops = {loop};
      body.block = {false,    cut->enclosing_radius,        s.z_low,
                    s.z_high, 0.5 * M_PI * s.from_quadrant, 0.5 * M_PI * s.to_quadrant};
      if (s.pin)
        body.cylinders.push_back(
            {{0.0, 0.0, s.z_high}, {0.0, 0.0, 1.0}, cut->pin_radius, cut->pin_height, true, false});
      if (s.hole) {
        body.cylinders.push_back(
            {{0.0, 0.0, s.z_low}, {0.0, 0.0, 1.0}, cut->hole_radius, cut->hole_depth, false, false});
      }
      if (s.to_quadrant - s.from_quadrant < 4) {
        // The pin of the joint at its last half-plane, out across it; the hole of the one at its first, in.
        const auto across = [&](int quadrant, double radius, double length, bool added) {
          const Vec2 d = quadrant_direction(quadrant);
          const Vec3 base(s.joint_pin.x() * d.x(), s.joint_pin.x() * d.y(), s.joint_pin.y());
          body.cylinders.push_back({base, Vec3(-d.y(), d.x(), 0.0), radius, length, added, true});
        };
        across(s.to_quadrant, cut->pin_radius, cut->pin_height, true);
        across(s.from_quadrant, cut->hole_radius, cut->hole_depth, false);
        joints += 1.0;
      }
      if (s.from_quadrant == 0) levels += 1.0;
      model.bodies.push_back(std::move(body));
      parts.push_back(s.name);
    }
    joints += levels - 1.0;
    volume += joints * M_PI *
              (cut->pin_radius * cut->pin_radius * cut->pin_height -
               cut->hole_radius * cut->hole_radius * cut->hole_depth);
    Encoded written = checked_step(c, model, loop_of.added(), volume,
                                   "the master's sections as OpenCASCADE built them hold");
    written.parts = std::move(parts);
    return {std::move(written)};
  }
  for (const std::vector<ExactPiece>& loop : vessel.master->loops) {
    StepBody body;
    body.name = model.name;
    body.form = StepForm::Revolution;
    body.loops.push_back(loop_of(loop));
    model.bodies.push_back(std::move(body));
  }
  Encoded e = checked_step(c, model, loop_of.added(), volume, "the master as OpenCASCADE built it holds");
  e.parts = {"master"};
  return {std::move(e)};
}

// The mould part `part` as a Carved body (its block, the cavity, its keys).
StepBody carved_part(const ExactMould& mould, const ExactMould::Part& part, const StepLoop& cavity,
                     std::string name) {
  StepBody body;
  body.name = std::move(name);
  body.form = StepForm::Carved;
  body.loops = {cavity};
  body.block = {mould.box, mould.block_radius, part.z_low, part.z_high, part.from_angle, part.to_angle};
  for (const ExactMould::Key& k : part.keys) body.hemispheres.push_back({k.centre, k.axis, k.radius, k.bump});
  return body;
}

// The mould's parts as exact solids, one product each, in the design's unit:
// OpenCASCADE takes the revolved cavity and the sockets from each block and
// adds the bumps. When the cavity is exact, the parts' volumes together must
// be the exact plaster volume (block - cavity + bumps - sockets) within
// OpenCASCADE's integration: a boolean operation that lost the cavity or a
// key (a key is about 1e-4 of a mould) would show there.
EncodedFiles encode_mould_step_output(const EncodeContext& c) {
  const ExactMould& mould = *std::get<VesselProducts>(c.result.products).mould;
  StepModel model;
  model.name = c.common.name + " mould";
  model.unit = c.common.units;
  StepLoops loop_of(c.output_tolerance);
  const StepLoop cavity = loop_of(mould.cavity);
  Encoded e;
  for (const ExactMould::Part& part : mould.parts) {
    model.bodies.push_back(carved_part(mould, part, cavity, c.common.name + " mould " + part.name));
    e.parts.push_back(part.name);
  }
  Encoded written = checked_step(c, model, loop_of.added(), mould.volume,
                                 "the mould's parts as OpenCASCADE built them hold");
  written.parts = std::move(e.parts);
  return {std::move(written)};
}

// Each casting case as an exact solid in the mould's frame (where its part
// lies in it), one file per case: its box less the exact mould part, the
// module checking that the cut took exactly the part's volume. The box is
// the mesh case's; its open side lies on the part's exact flat face. A
// two-piece case is written assembled: its main piece (its box to the face
// its plate lies under, less the part with that face's keys left out, and
// less the holes of the plate's pins) and its plate (the slab beyond that
// face, with the sockets there filled, the bumps there taken away and the
// pins standing on it).
EncodedFiles encode_case_step_output(const EncodeContext& c) {
  require_cases(c, "case_step");
  const auto& vessel = std::get<VesselProducts>(c.result.products);
  const ExactMould& mould = *vessel.mould;
  StepLoops loop_of(c.output_tolerance);
  const StepLoop cavity = loop_of(mould.cavity);
  EncodedFiles files;
  for (const VesselProducts::CaseBox& box : vessel.cases) {
    const ExactMould::Part& part = mould.parts.at(box.part);
    // The coordinate of the part's exact flat face across an axis direction.
    const auto face = [&](int k, double sign) {
      if (k == 2) return sign > 0.0 ? part.z_high : part.z_low;
      return sign > 0.0 ? mould.block_radius : -mould.block_radius;
    };
    StepModel model;
    model.name = c.common.name + " " + box.name;
    model.unit = c.common.units;
    StepBody body = carved_part(mould, part, cavity, model.name);
    body.form = StepForm::Case;
    body.case_lo = box.lo;
    body.case_hi = box.hi;
    for (const CaseDraft& d : box.drafts) {
      body.drafts.push_back({{d.section.begin(), d.section.end()}, d.along, d.about_axis});
    }
    for (int k = 0; k < 3; ++k) {
      if (box.opening[k] != 0.0) {
        (box.opening[k] > 0.0 ? body.case_hi : body.case_lo)[k] = face(k, box.opening[k]);
      }
    }
    Encoded e;
    if (box.carved) {
      // Its pieces cut from the exact case by their regions, in order; the
      // main piece first, less the pins' holes.
      std::vector<StepRegion> regions;
      for (const VesselProducts::CaseBox::Piece& p : box.pieces) {
        StepRegion r{p.corner, p.u, p.v, p.d, {}, {}, {}};
        if (!p.hollow.empty()) r.hollows.push_back({p.hollow, p.hollow_along});
        for (const CasePrism& prism : p.cores) r.adds.push_back({prism.ring, prism.along});
        if (p.face_axis >= 0) {
          // Its seam on the part's exact face.
          const int q = p.face_axis;
          const double side = p.corner[q] + 0.5 * p.d[q] > p.face_at ? 1.0 : -1.0;
          const double at = face(q, side);
          if (side > 0.0) {
            r.d[q] = p.corner[q] + p.d[q] - at;
            r.corner[q] = at;
          } else {
            r.d[q] = at - p.corner[q];
          }
          // The sockets behind that face: the part's hemispheres taken away there, filled.
          Vec3 way = Vec3::Zero();  // the way the piece comes off
          way[q] = side;
          for (const StepHemisphere& h : body.hemispheres) {
            if (!h.added && std::abs(h.centre[q] - at) <= 1e-9 * (1.0 + std::abs(at)) &&
                std::abs(h.axis.dot(way) + 1.0) <= 1e-12) {
              StepHemisphere fill = h;
              fill.added = true;
              r.fills.push_back(fill);
            }
          }
        }
        regions.push_back(std::move(r));
      }
      body.form = StepForm::CasePiece;
      body.regions = std::move(regions);
      std::vector<std::string> names{box.name};
      const StepBody whole = body;
      std::vector<StepBody> pieces;
      for (std::size_t n = 0; n < box.pieces.size(); ++n) {
        StepBody piece = whole;
        piece.name = c.common.name + " " + box.pieces[n].name;
        piece.piece = n + 1;
        // The holes of the pieces before it (in it where their pins reach in), then its own pins.
        piece.cylinders = body.cylinders;
        for (const VesselProducts::CaseBox::Plate::Pin& pin : box.pieces[n].pins) {
          piece.cylinders.push_back({pin.base, pin.axis, pin.radius, pin.height, true, false});
          body.cylinders.push_back({pin.base, pin.axis, pin.hole_radius, pin.hole_depth, false, false});
        }
        names.push_back(box.pieces[n].name);
        pieces.push_back(std::move(piece));
      }
      model.bodies.push_back(std::move(body));
      for (StepBody& piece : pieces) model.bodies.push_back(std::move(piece));
      e = step_file(c, model, loop_of.added());
      e.parts = std::move(names);
    } else if (box.plate) {
      const VesselProducts::CaseBox::Plate& p = *box.plate;
      const int k = p.pull.x() != 0.0 ? 0 : (p.pull.y() != 0.0 ? 1 : 2);
      const double at = face(k, p.pull[k]);
      StepBody plate;
      plate.name = c.common.name + " " + p.name;
      plate.form = StepForm::CasePlate;
      plate.case_lo = p.lo;
      plate.case_hi = p.hi;
      // The face between them: the plate beyond it along its pull, the main piece short of it.
      (p.pull[k] > 0.0 ? plate.case_lo : plate.case_hi)[k] = at;
      (p.pull[k] > 0.0 ? body.case_hi : body.case_lo)[k] = at;
      // The keys on that face go with the plate: a socket of the part is
      // plate (the mesh makes plates under sockets only; a bump would be a
      // socket in the plate).
      std::vector<StepHemisphere> kept;
      for (const StepHemisphere& h : body.hemispheres) {
        const bool on_face = std::abs(h.centre[k] - at) <= 1e-9 * (1.0 + std::abs(at)) &&
                             std::abs(h.axis.dot(p.pull) + 1.0) <= 1e-12;
        if (!on_face) {
          kept.push_back(h);
          continue;
        }
        StepHemisphere moved = h;
        moved.added = !h.added;
        plate.hemispheres.push_back(moved);
      }
      body.hemispheres = std::move(kept);
      // The plate's pins stand on that face, in holes of the main piece.
      for (const VesselProducts::CaseBox::Plate::Pin& pin : p.pins) {
        Vec3 base = pin.base;
        base[k] = at;
        plate.cylinders.push_back({base, pin.axis, pin.radius, pin.height, true, false});
        body.cylinders.push_back({base, pin.axis, pin.hole_radius, pin.hole_depth, false, false});
      }
      model.bodies.push_back(std::move(body));
      model.bodies.push_back(std::move(plate));
      e = step_file(c, model, loop_of.added());
      e.parts = {box.name, p.name};
    } else {
      model.bodies.push_back(std::move(body));
      e = step_file(c, model, loop_of.added());
      e.parts = {box.name};
    }
    e.suffix = "." + box.name + ".step";
    files.push_back(std::move(e));
  }
  return files;
}

}  // namespace fabmesh
