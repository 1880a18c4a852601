// The STEP module: the only file that includes OpenCASCADE. Built as its own
// shared object (fabmesh-step.so) and loaded by io/step/step.cpp only when
// a STEP file is written or read, so no other run pays for loading OCCT.
//
// OCCT's data exchange keeps its settings (units, messages) in process-wide
// statics: every call here holds one lock, and sets every setting it relies on.

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_Result.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepExtrema_ExtPC.hxx>
#include <BRepExtrema_ExtPF.hxx>
#include <BRepFilletAPI_MakeChamfer.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GProp_GProps.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeFix_Face.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <StepAP214.hxx>
#include <StepAP214_Protocol.hxx>
#include <StepBasic_Product.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopAbs.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Wire.hxx>
#include <UnitsMethods.hxx>
#include <algorithm>
#include <cmath>
#include <gp_Ax1.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pln.hxx>
#include <gp_Trsf.hxx>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#if defined(__SANITIZE_ADDRESS__)
#define FABMESH_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FABMESH_ASAN 1
#endif
#endif
#ifdef FABMESH_ASAN
#include <sanitizer/lsan_interface.h>
#endif
#include <utility>
#include <vector>

#include "io/step/step_model.h"

namespace fabmesh {
namespace {

std::mutex& occt_lock() {
  static std::mutex m;
  return m;
}

// OCCT prints transfer statistics and warnings to stdout through its default
// messenger: fabmesh's stdout is its own report.
void quiet_occt() {
  static std::once_flag once;
  std::call_once(once, [] { Message::DefaultMessenger()->ChangePrinters().Clear(); });
}

// The file's unit as OCCT names it for "write.step.unit" and "xstep.cascade.unit".
const char* occt_unit(const std::string& unit) {
  if (unit == "mm") return "MM";
  if (unit == "cm") return "CM";
  if (unit == "m") return "M";
  if (unit == "in") return "INCH";
  throw std::invalid_argument("unit '" + unit + "' is not one of mm, cm, m, in");
}

// Millimetres per unit of a length unit as OCCT's settings ("CM") or a
// file's units ("centimetre") name it; 0 for others.
double millimetres_of(const std::string& unit) {
  if (unit == "MM" || unit == "millimetre") return 1.0;
  if (unit == "CM" || unit == "centimetre") return 10.0;
  if (unit == "M" || unit == "metre") return 1000.0;
  if (unit == "INCH" || unit == "inch") return 25.4;
  return 0.0;
}

// Makes `reader` give shapes in the unit of its file, unscaled; that unit's name.
std::string read_in_file_unit(STEPControl_Reader& reader) {
  TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
  reader.FileUnits(lengths, angles, solid_angles);
  std::string unit = lengths.Length() > 0 ? lengths.Value(1).ToCString() : "";
  const double millimetres = millimetres_of(unit);
  if (millimetres > 0.0) {
    UnitsMethods::SetCasCadeLengthUnit(millimetres);
    reader.SetSystemLengthUnit(millimetres);
  }
  return unit;
}

// True for the forms whose loops lie in the (radius, height) half-plane.
bool revolved(StepForm form) {
  return form == StepForm::Revolution || form == StepForm::Carved || form == StepForm::Slice;
}

// Where a plane point goes: the xy plane (extrusions, wireframes) or the
// (radius, height) half-plane as x and z (revolutions, carved bodies).
gp_Pnt place(const Vec2& p, StepForm form) {
  return revolved(form) ? gp_Pnt(p.x(), 0.0, p.y()) : gp_Pnt(p.x(), p.y(), 0.0);
}

// OCCT's 1-based arrays of a vector's values.
TColStd_Array1OfReal reals(const std::vector<double>& v) {
  TColStd_Array1OfReal a(1, static_cast<int>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) a.SetValue(static_cast<int>(i) + 1, v[i]);
  return a;
}

TColStd_Array1OfInteger integers(const std::vector<int>& v) {
  TColStd_Array1OfInteger a(1, static_cast<int>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) a.SetValue(static_cast<int>(i) + 1, v[i]);
  return a;
}

TColgp_Array1OfPnt poles_of(const StepCurve& c, StepForm form) {
  TColgp_Array1OfPnt poles(1, static_cast<int>(c.poles.size()));
  for (std::size_t i = 0; i < c.poles.size(); ++i)
    poles.SetValue(static_cast<int>(i) + 1, place(c.poles[i], form));
  return poles;
}

TopoDS_Edge make_edge(const StepCurve& c, StepForm form) {
  switch (c.kind) {
    case StepCurve::Kind::Line: {
      BRepBuilderAPI_MakeEdge e(place(c.poles.at(0), form), place(c.poles.at(1), form));
      if (!e.IsDone()) throw std::runtime_error("a line of zero length");
      return e.Edge();
    }
    case StepCurve::Kind::Bezier: {
      const TColgp_Array1OfPnt poles = poles_of(c, form);
      Handle(Geom_BezierCurve) curve;
      if (c.weights.empty()) {
        curve = new Geom_BezierCurve(poles);
      } else {
        curve = new Geom_BezierCurve(poles, reals(c.weights));
      }
      return BRepBuilderAPI_MakeEdge(curve).Edge();
    }
    case StepCurve::Kind::BSpline: {
      const TColgp_Array1OfPnt poles = poles_of(c, form);
      Handle(Geom_BSplineCurve) curve =
          new Geom_BSplineCurve(poles, reals(c.knots), integers(c.multiplicities), c.degree);
      return BRepBuilderAPI_MakeEdge(curve).Edge();
    }
    case StepCurve::Kind::Conic: {
      const StepConic& k = c.conic;
      const gp_Pnt centre = place(k.center, form);
      const gp_Dir normal = revolved(form) ? gp_Dir(0, -1, 0) : gp_Dir(0, 0, 1);
      const Vec2 axis(std::cos(k.axis_angle), std::sin(k.axis_angle));
      const gp_Pnt tip = place(k.center + axis, form);
      const gp_Ax2 frame(centre, normal, gp_Dir(gp_Vec(centre, tip)));
      Handle(Geom_Curve) conic;
      if (k.major == k.minor) {
        conic = new Geom_Circle(frame, k.major);
      } else {
        conic = new Geom_Ellipse(frame, k.major, k.minor);
      }
      const double lo = std::min(k.from, k.to), hi = std::max(k.from, k.to);
      TopoDS_Edge edge = hi - lo >= 2.0 * M_PI ? BRepBuilderAPI_MakeEdge(conic).Edge()
                                               : BRepBuilderAPI_MakeEdge(conic, lo, hi).Edge();
      if (k.to < k.from) edge.Reverse();
      return edge;
    }
  }
  throw std::logic_error("unknown curve kind");
}

TopoDS_Wire make_wire(const StepLoop& loop, StepForm form, std::size_t index) {
  BRepBuilderAPI_MakeWire wire;
  for (const StepCurve& c : loop.curves) {
    wire.Add(make_edge(c, form));
    if (!wire.IsDone()) {
      throw std::runtime_error("loop " + std::to_string(index) + ": its pieces do not join end to end");
    }
  }
  return wire.Wire();
}

// The face the body's loops bound in its plane, turned so that its normal is
// the plane's: the outer loop counter-clockwise about it, the holes clockwise
// (the loops may come in either direction).
TopoDS_Face plane_face(const StepBody& body) {
  const gp_Pln plane =
      revolved(body.form) ? gp_Pln(gp::Origin(), gp_Dir(0, -1, 0)) : gp_Pln(gp::Origin(), gp::DZ());
  BRepBuilderAPI_MakeFace face(plane, make_wire(body.loops[0], body.form, 0), Standard_True);
  for (std::size_t i = 1; i < body.loops.size(); ++i) face.Add(make_wire(body.loops[i], body.form, i));
  if (!face.IsDone()) throw std::runtime_error("the loops make no face");
  ShapeFix_Face fix(face.Face());
  fix.FixOrientation();
  return fix.Face();
}

// The plane face revolved all the way about the z axis.
TopoDS_Shape revolution_of(const TopoDS_Face& face) {
  BRepPrimAPI_MakeRevol revol(face, gp_Ax1(gp::Origin(), gp::DZ()), 2.0 * M_PI);
  if (!revol.IsDone()) throw std::runtime_error("the revolution failed");
  return revol.Shape();
}

// Where the ray from the axis at `angle` leaves the square |x|, |y| <= r.
gp_Pnt on_square(double r, double angle, double z) {
  const double c = std::cos(angle), s = std::sin(angle);
  const double t = r / std::max(std::abs(c), std::abs(s));
  return gp_Pnt(t * c, t * s, z);
}

// A carved body's block: a cylinder or its sector, or a box or its part
// between the two half-planes (the polygon of the square's corners between
// them, extruded), so that no boolean operation is needed for it.
TopoDS_Shape make_block(const StepBlock& b) {
  const double height = b.z_high - b.z_low, sweep = b.to_angle - b.from_angle;
  if (!(height > 0.0) || !(b.radius > 0.0) || !(sweep > 0.0) || sweep > 2.0 * M_PI + 1e-12)
    throw std::runtime_error("a block without room (height, radius or angle not positive)");
  const bool whole = sweep >= 2.0 * M_PI - 1e-12;
  if (!b.box) {
    const gp_Ax2 frame(gp_Pnt(0.0, 0.0, b.z_low), gp::DZ(),
                       gp_Dir(std::cos(b.from_angle), std::sin(b.from_angle), 0.0));
    return whole ? BRepPrimAPI_MakeCylinder(frame, b.radius, height).Shape()
                 : BRepPrimAPI_MakeCylinder(frame, b.radius, height, sweep).Shape();
  }
  BRepBuilderAPI_MakePolygon polygon;
  if (whole) {
    for (const double angle : {-0.75 * M_PI, -0.25 * M_PI, 0.25 * M_PI, 0.75 * M_PI})
      polygon.Add(on_square(b.radius, angle, b.z_low));
  } else {
    polygon.Add(gp_Pnt(0.0, 0.0, b.z_low));
    polygon.Add(on_square(b.radius, b.from_angle, b.z_low));
    const double margin = 1e-12;
    for (int k = -8; k <= 16; ++k) {
      const double corner = 0.25 * M_PI + 0.5 * M_PI * k;
      if (corner > b.from_angle + margin && corner < b.to_angle - margin)
        polygon.Add(on_square(b.radius, corner, b.z_low));
    }
    polygon.Add(on_square(b.radius, b.to_angle, b.z_low));
  }
  polygon.Close();
  if (!polygon.IsDone()) throw std::runtime_error("the box's outline makes no polygon");
  BRepBuilderAPI_MakeFace face(polygon.Wire(), Standard_True);
  if (!face.IsDone()) throw std::runtime_error("the box's outline makes no face");
  BRepPrimAPI_MakePrism prism(face.Face(), gp_Vec(0.0, 0.0, height));
  if (!prism.IsDone()) throw std::runtime_error("the box's extrusion failed");
  return prism.Shape();
}

TopoDS_Shape make_hemisphere(const StepHemisphere& h) {
  if (!(h.radius > 0.0)) throw std::runtime_error("a hemisphere without radius");
  const gp_Ax2 frame(gp_Pnt(h.centre.x(), h.centre.y(), h.centre.z()),
                     gp_Dir(h.axis.x(), h.axis.y(), h.axis.z()));
  return BRepPrimAPI_MakeSphere(frame, h.radius, 0.0, 0.5 * M_PI).Shape();
}

// OpenCASCADE 7.6's general fuse loses a few of its own allocations on some
// inputs: BRepClass3d_SolidExplorer::InitShape binds one new
// IntCurvesFace_Intersector per face it meets into a map keyed by the face, so
// a face met twice in one shell (as the caps of a stopped edge profile make
// in its intermediate shells) leaves the first unfreed; ProjLib_ComputeApprox
// loses a projected B-spline the same way. Neither can be freed from here. In
// a build with AddressSanitizer, the allocations made while a boolean
// operation builds are left out of the leak report (what they hold counts as
// reachable); everything this module allocates itself is still checked.
#ifdef FABMESH_ASAN
using OcctLeaksIgnored = __lsan::ScopedDisabler;
#else
struct OcctLeaksIgnored {};
#endif

// `object` with `tools` taken away (Cut), added (Fuse) or kept in common, by
// OpenCASCADE's general fuse: shapes closer than `fuzzy` taken as touching
// (0: exactly). Empty when the operation reports an error.
template <class Operation>
std::optional<TopoDS_Shape> try_boolean(const TopoDS_Shape& object, const TopTools_ListOfShape& tools,
                                        double fuzzy = 0.0) {
  Operation operation;
  TopTools_ListOfShape objects;
  objects.Append(object);
  operation.SetArguments(objects);
  operation.SetTools(tools);
  operation.SetRunParallel(Standard_False);
  if (fuzzy > 0.0) operation.SetFuzzyValue(fuzzy);
  {
    [[maybe_unused]] const OcctLeaksIgnored ignored;
    operation.Build();
  }
  if (!operation.IsDone() || operation.HasErrors()) return std::nullopt;
  return operation.Shape();
}

// As try_boolean, exactly; refused when it reports an error.
template <class Operation>
TopoDS_Shape boolean(const TopoDS_Shape& object, const TopTools_ListOfShape& tools, const char* what) {
  std::optional<TopoDS_Shape> shape = try_boolean<Operation>(object, tools);
  if (!shape) throw std::runtime_error(std::string("OpenCASCADE's boolean operation failed ") + what);
  return *shape;
}

// The one solid of a boolean operation's result, or the result as it is
// when it holds several (facts_of then counts them).
TopoDS_Shape the_solid(const TopoDS_Shape& shape) {
  TopTools_IndexedMapOfShape solids;
  TopExp::MapShapes(shape, TopAbs_SOLID, solids);
  return solids.Extent() == 1 ? solids(1) : shape;
}

// The block minus the revolved section (the mould's cavity) and the
// hemispheres taken away, plus those added: one solid when all went well.
TopoDS_Shape make_carved(const StepBody& body) {
  TopTools_ListOfShape removed, added;
  removed.Append(revolution_of(plane_face(body)));
  for (const StepHemisphere& h : body.hemispheres) (h.added ? added : removed).Append(make_hemisphere(h));
  TopoDS_Shape shape = boolean<BRepAlgoAPI_Cut>(make_block(body.block), removed, "taking the cavity away");
  if (!added.IsEmpty()) shape = boolean<BRepAlgoAPI_Fuse>(shape, added, "adding the keys");
  return the_solid(shape);
}

TopoDS_Shape make_cylinder(const StepCylinder& c) {
  if (!(c.radius > 0.0) || !(c.height > 0.0)) throw std::runtime_error("a cylinder without room");
  const gp_Ax2 frame(gp_Pnt(c.base.x(), c.base.y(), c.base.z()), gp_Dir(c.axis.x(), c.axis.y(), c.axis.z()));
  return BRepPrimAPI_MakeCylinder(frame, c.radius, c.height).Shape();
}

// The revolution cut to the block's heights (their common part), with the
// cylinders added and then those taken away: one solid when all went well.
TopoDS_Shape make_slice(const StepBody& body) {
  TopTools_ListOfShape slab, added, removed, across_added, across_removed;
  StepBlock heights = body.block;
  heights.from_angle = 0.0;
  heights.to_angle = 2.0 * M_PI;
  slab.Append(make_block(heights));
  for (const StepCylinder& c : body.cylinders) {
    TopTools_ListOfShape& list =
        c.across ? (c.added ? across_added : across_removed) : (c.added ? added : removed);
    list.Append(make_cylinder(c));
  }
  TopoDS_Shape shape =
      boolean<BRepAlgoAPI_Common>(revolution_of(plane_face(body)), slab, "cutting the slice");
  if (!added.IsEmpty()) shape = boolean<BRepAlgoAPI_Fuse>(shape, added, "adding the pins");
  if (!removed.IsEmpty()) shape = boolean<BRepAlgoAPI_Cut>(shape, removed, "taking the holes away");
  if (body.block.to_angle - body.block.from_angle < 2.0 * M_PI - 1e-12) {
    // The wedge between the block's half-planes, tall enough for the pin above and the hole below.
    StepBlock wedge = body.block;
    const double room = body.block.z_high - body.block.z_low + body.block.radius;
    wedge.z_low -= room;
    wedge.z_high += room;
    TopTools_ListOfShape tool;
    tool.Append(make_block(wedge));
    shape = boolean<BRepAlgoAPI_Common>(shape, tool, "cutting the slice through its axis");
  }
  if (!across_added.IsEmpty())
    shape = boolean<BRepAlgoAPI_Fuse>(shape, across_added, "adding the joint's pin");
  if (!across_removed.IsEmpty())
    shape = boolean<BRepAlgoAPI_Cut>(shape, across_removed, "taking the joint's hole away");
  return the_solid(shape);
}

// One face of a sheet: the whole B-spline surface, its sides the face's
// edges (a side that is one point within `tolerance` a degenerate edge).
TopoDS_Face sheet_face(const StepSurface& s, double tolerance) {
  if (s.poles.size() != s.u_poles * s.v_poles || s.u_poles < 2 || s.v_poles < 2)
    throw std::runtime_error("face '" + s.name + "': its poles are not a grid");
  TColgp_Array2OfPnt poles(1, static_cast<int>(s.u_poles), 1, static_cast<int>(s.v_poles));
  for (std::size_t k = 0; k < s.u_poles; ++k) {
    for (std::size_t l = 0; l < s.v_poles; ++l) {
      const Vec3& p = s.poles[k * s.v_poles + l];
      poles.SetValue(static_cast<int>(k) + 1, static_cast<int>(l) + 1, gp_Pnt(p.x(), p.y(), p.z()));
    }
  }
  Handle(Geom_BSplineSurface) surface =
      new Geom_BSplineSurface(poles, reals(s.u_knots), reals(s.v_knots), integers(s.u_multiplicities),
                              integers(s.v_multiplicities), s.u_degree, s.v_degree);
  BRepBuilderAPI_MakeFace face(surface, tolerance);
  if (!face.IsDone()) throw std::runtime_error("face '" + s.name + "': OpenCASCADE makes no face of it");
  if (BRepCheck_Analyzer(face.Face()).IsValid() != Standard_True)
    throw std::runtime_error("face '" + s.name + "': OpenCASCADE finds it not valid");
  return face.Face();
}

// The faces sewn along their common borders: one shell, or refused.
TopoDS_Shape make_sheet(const StepBody& body) {
  if (body.surfaces.empty()) throw std::runtime_error("a sheet without faces");
  if (!(body.sewing_tolerance > 0.0)) throw std::runtime_error("a sheet without a sewing tolerance");
  BRepBuilderAPI_Sewing sewing(body.sewing_tolerance);
  for (const StepSurface& s : body.surfaces) sewing.Add(sheet_face(s, body.sewing_tolerance));
  sewing.Perform();
  const TopoDS_Shape sewn = sewing.SewedShape();
  if (sewn.ShapeType() == TopAbs_FACE) {
    TopoDS_Shell shell;
    BRep_Builder builder;
    builder.MakeShell(shell);
    builder.Add(shell, sewn);
    return shell;
  }
  // The pieces: the shells, and the faces sewn to none.
  TopTools_IndexedMapOfShape shells, faces, in_shells;
  TopExp::MapShapes(sewn, TopAbs_SHELL, shells);
  TopExp::MapShapes(sewn, TopAbs_FACE, faces);
  for (int i = 1; i <= shells.Extent(); ++i) TopExp::MapShapes(shells(i), TopAbs_FACE, in_shells);
  const int pieces = shells.Extent() + faces.Extent() - in_shells.Extent();
  if (pieces != 1 || shells.Extent() != 1) {
    throw std::runtime_error("the patches' faces, sewn, make " + std::to_string(pieces) +
                             " pieces, not one shell: some patches do not meet along whole borders");
  }
  return shells(1);
}

// How the faces use the edges: every edge that is not degenerate (a
// revolution's pole) used twice by the faces (a seam twice by its one face),
// but for an open shell's border, whose edges one face uses once (free).
struct EdgeUses {
  bool all_twice = true;
  int free = 0;
};
EdgeUses edge_uses(const TopoDS_Shape& shape) {
  TopTools_IndexedMapOfShape edges;
  std::vector<int> uses;
  for (TopExp_Explorer face(shape, TopAbs_FACE); face.More(); face.Next()) {
    for (TopExp_Explorer edge(face.Current(), TopAbs_EDGE); edge.More(); edge.Next()) {
      const int i = edges.Add(edge.Current());
      if (static_cast<std::size_t>(i) > uses.size()) uses.resize(static_cast<std::size_t>(i), 0);
      ++uses[static_cast<std::size_t>(i) - 1];
    }
  }
  EdgeUses out;
  for (int i = 1; i <= edges.Extent(); ++i) {
    if (BRep_Tool::Degenerated(TopoDS::Edge(edges.FindKey(i)))) continue;
    const int n = uses[static_cast<std::size_t>(i) - 1];
    if (n != 2) out.all_twice = false;
    if (n == 1) ++out.free;
  }
  return out;
}

// The faces sewn into one closed shell, and the solid it bounds, turned outward.
TopoDS_Shape make_closed(const StepBody& body) {
  const TopoDS_Shell shell = TopoDS::Shell(make_sheet(body));
  const EdgeUses uses = edge_uses(shell);
  if (!uses.all_twice) {
    throw std::runtime_error("the faces, sewn, leave " + std::to_string(uses.free) +
                             " edges free: they do not close into a solid");
  }
  BRepBuilderAPI_MakeSolid solid(shell);
  if (!solid.IsDone()) throw std::runtime_error("OpenCASCADE makes no solid of the closed shell");
  TopoDS_Solid out = solid.Solid();
  BRepLib::OrientClosedSolid(out);
  return out;
}

// The point half way along an edge's parameter range (the same on the
// curve it was made from and on its copy at the top of a prism).
gp_Pnt edge_middle(const TopoDS_Edge& e) {
  const BRepAdaptor_Curve c(e);
  return c.Value(0.5 * (c.FirstParameter() + c.LastParameter()));
}

// The plan face extruded from z0 to z1.
TopoDS_Shape prism_between(const TopoDS_Face& face, double z0, double z1) {
  gp_Trsf lift;
  lift.SetTranslation(gp_Vec(0.0, 0.0, z0));
  const TopoDS_Shape base = BRepBuilderAPI_Transform(face, lift, Standard_True).Shape();
  BRepPrimAPI_MakePrism prism(base, gp_Vec(0.0, 0.0, z1 - z0));
  if (!prism.IsDone()) throw std::runtime_error("the extrusion failed");
  return prism.Shape();
}

// Where the profiled curves of the outer loop lie: their middles, found
// again on a prism by within `tolerance` (1e-7 of the body's size).
struct ProfiledMiddles {
  std::vector<gp_Pnt> points;
  double tolerance = 0.0;
};

ProfiledMiddles profiled_middles(const StepBody& body, const std::vector<TopoDS_Edge>& edges) {
  ProfiledMiddles m;
  double size = body.height;
  const StepLoop& outer = body.loops.at(0);
  for (std::size_t i = 0; i < outer.curves.size(); ++i) {
    for (const Vec2& p : outer.curves[i].poles) size = std::max({size, std::abs(p.x()), std::abs(p.y())});
    if (body.rounds.profiled[i]) m.points.push_back(edge_middle(edges[i]));
  }
  m.tolerance = 1e-7 * std::max(1.0, size);
  return m;
}

// The edges of `prism` over the profiled curves, at its top or its bottom
// (height z), each found by its middle.
std::vector<TopoDS_Edge> profiled_edges(const TopoDS_Shape& prism, const ProfiledMiddles& middles, double z) {
  const double tolerance = middles.tolerance;
  std::vector<TopoDS_Edge> found;
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(prism, TopAbs_EDGE, edges);
  for (int i = 1; i <= edges.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(edges(i));
    if (BRep_Tool::Degenerated(e)) continue;
    const gp_Pnt m = edge_middle(e);
    if (std::abs(m.Z() - z) > tolerance) continue;
    for (const gp_Pnt& c : middles.points) {
      if (std::hypot(m.X() - c.X(), m.Y() - c.Y()) > tolerance) continue;
      found.push_back(e);
      break;
    }
  }
  if (found.size() != middles.points.size()) {
    throw std::runtime_error("edge profile: " + std::to_string(found.size()) +
                             " edges found at z = " + std::to_string(z) + " for " +
                             std::to_string(middles.points.size()) + " profiled curves");
  }
  return found;
}

// `prism` (from z0 to z1) with its profiled top edges rounded (or
// chamfered) by `top` and its bottom ones rounded by `bottom` (0: none).
TopoDS_Shape round_edges(const TopoDS_Shape& prism, const StepBody& body, const ProfiledMiddles& middles,
                         double z0, double z1, double top, double bottom) {
  if (body.rounds.chamfer) {
    BRepFilletAPI_MakeChamfer chamfer(prism);
    for (const TopoDS_Edge& e : profiled_edges(prism, middles, z1)) chamfer.Add(top, e);
    chamfer.Build();
    if (!chamfer.IsDone())
      throw std::runtime_error("edge profile: OpenCASCADE could not bevel the top edges");
    return chamfer.Shape();
  }
  BRepFilletAPI_MakeFillet fillet(prism);
  if (top > 0.0) {
    for (const TopoDS_Edge& e : profiled_edges(prism, middles, z1)) fillet.Add(top, e);
  }
  if (bottom > 0.0) {
    for (const TopoDS_Edge& e : profiled_edges(prism, middles, z0)) fillet.Add(bottom, e);
  }
  fillet.Build();
  if (!fillet.IsDone()) throw std::runtime_error("edge profile: OpenCASCADE could not round the edges");
  return fillet.Shape();
}

TopoDS_Shape common_of(const TopoDS_Shape& a, const TopoDS_Shape& b) {
  TopTools_ListOfShape tools;
  tools.Append(b);
  return boolean<BRepAlgoAPI_Common>(a, tools, "keeping the slab's thickness");
}

// Where a profile stops: the prism minus what a profile bit takes off.
//
// OpenCASCADE's fillets follow a whole chain of tangent edges, so where an
// exposed curve runs on tangentially into a wall or a seam they would round
// the wall too. There the solid is built as the mesh defines it: the prism
// minus, for each exposed curve, the points within d(z) of it. That is the
// profile's section swept along the curve (a prism along a line, a
// revolution about a circle arc's centre) and, where the round stops (on a
// wall or a seam met at more than a right angle, or at a reflex corner),
// the half-section revolved about the vertical through that end. Exact for
// lines and circle arcs; other curves are refused there.

// Where an edge starts (or ends) as its loop runs, and its direction of travel there.
void travel(const TopoDS_Edge& e, bool at_end, gp_Pnt& point, gp_Vec& tangent) {
  const BRepAdaptor_Curve c(e);
  const bool reversed = e.Orientation() == TopAbs_REVERSED;
  c.D1(at_end != reversed ? c.LastParameter() : c.FirstParameter(), point, tangent);
  if (reversed) tangent.Reverse();
}

// +1 when the loop of `edges` runs counter-clockwise seen from above, -1
// when clockwise (the shoelace sum of points along them).
double loop_sense(const std::vector<TopoDS_Edge>& edges) {
  constexpr int kSamples = 16;
  std::vector<gp_Pnt> points;
  for (const TopoDS_Edge& e : edges) {
    const BRepAdaptor_Curve c(e);
    const bool reversed = e.Orientation() == TopAbs_REVERSED;
    for (int k = 0; k < kSamples; ++k) {
      const double f = static_cast<double>(reversed ? kSamples - k : k) / kSamples;
      points.push_back(c.Value(c.FirstParameter() + f * (c.LastParameter() - c.FirstParameter())));
    }
  }
  double twice_area = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const gp_Pnt& a = points[i];
    const gp_Pnt& b = points[(i + 1) % points.size()];
    twice_area += a.X() * b.Y() - b.X() * a.Y();
  }
  return twice_area >= 0.0 ? 1.0 : -1.0;
}

// One round (or bevel) of size r, on the top face (at height t) or the
// bottom one, in the vertical plane through `origin` spanned by `inward`
// (horizontal, unit, into the plan) and z. In that plane s runs into the
// plan and w from the face into the slab; the profile takes off s < d(w),
// the region between the line s = 0 and the round from (0, r) to (r, 0).
// The section is that region reaching `over` past the face and, unless
// `half`, `over` back out past the edge, so that it cuts clear of the
// solid's faces; with `half` it stops at s = 0, the axis a cap turns about.
TopoDS_Face cut_section(const gp_Pnt& origin, const gp_Vec& inward, double t, double r, bool top,
                        bool chamfer, double over, bool half) {
  const auto at = [&](double s, double w) {
    return gp_Pnt(origin.X() + s * inward.X(), origin.Y() + s * inward.Y(), top ? t - w : w);
  };
  BRepBuilderAPI_MakeWire wire;
  if (chamfer) {
    wire.Add(BRepBuilderAPI_MakeEdge(at(0.0, r), at(r, 0.0)).Edge());
  } else {
    const double m = r * (1.0 - std::sqrt(0.5));
    const GC_MakeArcOfCircle arc(at(0.0, r), at(m, m), at(r, 0.0));
    if (!arc.IsDone()) throw std::runtime_error("edge profile: the round's arc could not be made");
    wire.Add(BRepBuilderAPI_MakeEdge(arc.Value()).Edge());
  }
  std::vector<gp_Pnt> corners{at(r, 0.0), at(r, -over)};
  if (half) {
    corners.insert(corners.end(), {at(0.0, -over), at(0.0, r)});
  } else {
    corners.insert(corners.end(), {at(-over, -over), at(-over, r + over), at(0.0, r)});
  }
  for (std::size_t i = 0; i + 1 < corners.size(); ++i)
    wire.Add(BRepBuilderAPI_MakeEdge(corners[i], corners[i + 1]).Edge());
  if (!wire.IsDone()) throw std::runtime_error("edge profile: the section's edges do not close");
  BRepBuilderAPI_MakeFace face(wire.Wire(), Standard_True);
  if (!face.IsDone()) throw std::runtime_error("edge profile: the section makes no face");
  return face.Face();
}

// The rounds a profile cuts: (size, on the top face, a bevel).
struct ProfileCut {
  double size;
  bool top;
  bool chamfer;
};

std::vector<ProfileCut> profile_cuts(const StepEdgeRounds& r) {
  std::vector<ProfileCut> cuts;
  if (r.top > 0.0) cuts.push_back({r.top, true, r.chamfer});
  if (r.bottom > 0.0) cuts.push_back({r.bottom, false, false});
  return cuts;
}

// The region the profile takes off along one exposed curve of the outline
// (a line or a circle arc; `sense` the loop's, from loop_sense).
void add_sweep_cutters(const StepCurve& curve, const TopoDS_Edge& edge, const StepBody& body, double sense,
                       std::size_t index, TopTools_ListOfShape& cutters) {
  const double t = body.height;
  if (curve.kind == StepCurve::Kind::Line) {
    gp_Pnt a, b;
    gp_Vec ta, tb;
    travel(edge, false, a, ta);
    travel(edge, true, b, tb);
    const gp_Vec along(a, b);
    gp_Vec inward(-sense * along.Y(), sense * along.X(), 0.0);
    inward.Normalize();
    for (const ProfileCut& c : profile_cuts(body.rounds)) {
      BRepPrimAPI_MakePrism prism(cut_section(a, inward, t, c.size, c.top, c.chamfer, c.size, false), along);
      if (!prism.IsDone()) throw std::runtime_error("edge profile: the cutter along a line failed");
      cutters.Append(prism.Shape());
    }
    return;
  }
  const StepConic& k = curve.conic;
  if (curve.kind != StepCurve::Kind::Conic || k.major != k.minor) {
    throw std::runtime_error(
        "edge profile: an exposed edge runs on tangentially into a wall or a seam, and curve " +
        std::to_string(index + 1) +
        " of the outline, exposed, is neither a line nor a circle arc: the stopped round is cut "
        "exactly only along those, so this solid is not written");
  }
  const double lo = std::min(k.from, k.to), hi = std::max(k.from, k.to), radius = k.major;
  const double angle = k.axis_angle + lo;
  const gp_Vec radial(std::cos(angle), std::sin(angle), 0.0);
  const gp_Pnt centre(k.center.x(), k.center.y(), 0.0);
  const gp_Pnt start = centre.Translated(radius * radial);
  // Travelled counter-clockwise about its centre in a counter-clockwise loop
  // (or both clockwise), the plan lies towards the centre.
  const bool towards_centre = (k.to > k.from) == (sense > 0.0);
  const gp_Vec inward = towards_centre ? -radial : radial;
  for (const ProfileCut& c : profile_cuts(body.rounds)) {
    const double over = towards_centre ? c.size : std::min(c.size, 0.5 * radius);
    BRepPrimAPI_MakeRevol revol(cut_section(start, inward, t, c.size, c.top, c.chamfer, over, false),
                                gp_Ax1(centre, gp::DZ()), std::min(hi - lo, 2.0 * M_PI));
    if (!revol.IsDone()) throw std::runtime_error("edge profile: the cutter along an arc failed");
    cutters.Append(revol.Shape());
  }
}

// The region within d(z) of the corner `end` and inside the plan there: the
// half-sections revolved about the vertical through it, from the direction
// the outline leaves it (`leaving`, unit) by `sweep` radians about z times
// `sense`, to the direction it came from. The sector's sides lie in the
// planes of the corner's edges, so no face crosses the revolution's axis.
void add_cap_cutters(const gp_Pnt& end, const gp_Vec& leaving, double sweep, double sense,
                     const StepBody& body, TopTools_ListOfShape& cutters) {
  for (const ProfileCut& c : profile_cuts(body.rounds)) {
    BRepPrimAPI_MakeRevol revol(
        cut_section(end, leaving, body.height, c.size, c.top, c.chamfer, c.size, true),
        gp_Ax1(gp_Pnt(end.X(), end.Y(), 0.0), sense > 0.0 ? gp::DZ() : -gp::DZ()), sweep);
    if (!revol.IsDone()) throw std::runtime_error("edge profile: the cutter about a stop failed");
    cutters.Append(revol.Shape());
  }
}

double volume_of(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  return props.Mass();
}

// As volume_of, integrated adaptively to a relative error of 1e-10 (slower):
// for checks finer than the fixed-order integration's error on curved faces.
double precise_volume_of(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props, 1e-10);
  return props.Mass();
}

// `solid` without the closed shells OpenCASCADE's boolean operations can
// leave where surfaces touch at a point (a bubble of a few faces whose area
// is 1e-9 of the solid's or less): numerical debris, not geometry.
TopoDS_Shape without_bubbles(const TopoDS_Shape& solid) {
  std::vector<std::pair<double, TopoDS_Shell>> shells;
  double largest = 0.0;
  for (TopExp_Explorer e(solid, TopAbs_SHELL); e.More(); e.Next()) {
    GProp_GProps props;
    BRepGProp::SurfaceProperties(e.Current(), props);
    shells.emplace_back(props.Mass(), TopoDS::Shell(e.Current()));
    largest = std::max(largest, props.Mass());
  }
  if (shells.size() < 2) return solid;
  BRepBuilderAPI_MakeSolid kept;
  for (const auto& [area, shell] : shells) {
    if (area > 1e-9 * largest) kept.Add(shell);
  }
  return kept.IsDone() ? kept.Solid() : solid;
}

// `object` minus `cutter`: one valid solid, every edge used twice, smaller
// than `object` (of `volume`) by no more than the cutter's volume. Exactly,
// or where OpenCASCADE's exact operation fails (a cap's sides lying in the
// corner's faces, its apex on their common edge) with shapes closer than a
// fuzzy value taken as touching: the smallest that works of 1e-6, 1e-5 and
// 1e-4 model units. Refused when none does.
TopoDS_Shape cut_one(const TopoDS_Shape& object, double volume, const TopoDS_Shape& cutter) {
  TopTools_ListOfShape tools;
  tools.Append(cutter);
  const double most = volume_of(cutter) * (1.0 + 1e-9);
  for (const double fuzzy : {0.0, 1e-6, 1e-5, 1e-4}) {
    const std::optional<TopoDS_Shape> cut = try_boolean<BRepAlgoAPI_Cut>(object, tools, fuzzy);
    if (!cut) continue;
    TopTools_IndexedMapOfShape solids;
    TopExp::MapShapes(*cut, TopAbs_SOLID, solids);
    if (solids.Extent() != 1) continue;
    const TopoDS_Shape result = without_bubbles(solids(1));
    if (!edge_uses(result).all_twice || !BRepCheck_Analyzer(result).IsValid()) continue;
    const double taken = volume - volume_of(result);
    if (taken > 1e-12 * volume && taken <= most) return result;
  }
  throw std::runtime_error(
      "edge profile: OpenCASCADE's cut of a stopped profile failed or took nothing away, so this "
      "solid is not written");
}

// True when an exposed curve of the outline runs on tangentially into one
// that is not (a wall, a seam), where fillets would not stop.
bool profile_stops_on_tangent(const StepBody& body, const std::vector<TopoDS_Edge>& edges) {
  const std::vector<bool>& profiled = body.rounds.profiled;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const std::size_t j = (i + 1) % edges.size();
    if (profiled[i] == profiled[j]) continue;
    gp_Pnt p, q;
    gp_Vec ta, tb;
    travel(edges[i], true, p, ta);
    travel(edges[j], false, q, tb);
    if (ta.Magnitude() > 0.0 && tb.Magnitude() > 0.0 && ta.Angle(tb) < 1e-6) return true;
  }
  return false;
}

// The prism of `face` minus every exposed curve's cutter and a cap at each
// end where the round stops: at a wall or a seam met at more than a right
// angle (tangentially included), or at a reflex corner between two exposed
// curves. Elsewhere the sweeps meet in a mitre, as the mesh's rings do.
// Rounds as tall as the edge (a half bullnose of the full thickness, a
// bullnose's two rounds meeting at mid-height) would bring their caps to a
// point on the bottom face's edge or on each other's apex, where
// OpenCASCADE's cuts come out unclosed or wrong: they are made smaller by
// the rounds' slack (each arc then lies within it of the exact one, the
// band it leaves too), or refused without one.
TopoDS_Shape stopped_profile(const TopoDS_Face& face, const StepBody& body,
                             const std::vector<TopoDS_Edge>& edges) {
  if (!(body.rounds.top + body.rounds.bottom < body.height)) {
    const double slack = body.rounds.slack;
    if (!(slack > 0.0) || !(slack < 0.5 * body.rounds.top)) {
      throw std::runtime_error(
          "edge profile: a round as tall as the edge (a half bullnose of the full thickness, a "
          "bullnose of half of it) that stops on a wall or a seam is made smaller by a slack, and "
          "none was given, so this solid is not written");
    }
    StepBody smaller = body;
    smaller.rounds.top -= slack;
    if (smaller.rounds.bottom > 0.0) smaller.rounds.bottom -= slack;
    return stopped_profile(face, smaller, edges);
  }
  const StepLoop& outer = body.loops.at(0);
  const std::vector<bool>& profiled = body.rounds.profiled;
  const double sense = loop_sense(edges);
  TopTools_ListOfShape caps, sweeps;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (profiled[i]) add_sweep_cutters(outer.curves[i], edges[i], body, sense, i, sweeps);
    const std::size_t j = (i + 1) % edges.size();
    if (!profiled[i] && !profiled[j]) continue;
    gp_Pnt p, q;
    gp_Vec ta, tb;
    travel(edges[i], true, p, ta);
    travel(edges[j], false, q, tb);
    const double turn =
        sense * std::atan2(ta.X() * tb.Y() - ta.Y() * tb.X(), ta.X() * tb.X() + ta.Y() * tb.Y());
    const double bound = profiled[i] && profiled[j] ? 0.0 : 0.5 * M_PI;
    if (turn < bound - 1e-9) add_cap_cutters(p, tb.Normalized(), M_PI - turn, sense, body, caps);
  }
  // One cutter at a time, the caps first (each takes material no other has
  // taken yet), each required to take some: a boolean operation that finds
  // no intersection where there is one would leave the edge square.
  ShapeUpgrade_UnifySameDomain flat(prism_between(face, 0.0, body.height));
  flat.Build();
  TopoDS_Shape shape = flat.Shape();
  double volume = volume_of(shape);
  for (const TopTools_ListOfShape* list : {&caps, &sweeps}) {
    for (TopTools_ListOfShape::Iterator it(*list); it.More(); it.Next()) {
      shape = cut_one(shape, volume, it.Value());
      volume = volume_of(shape);
    }
  }
  ShapeUpgrade_UnifySameDomain unify(shape);
  unify.Build();
  return unify.Shape();
}

// The outer loop's curves as edges, one per profile flag.
std::vector<TopoDS_Edge> outline_edges(const StepBody& body) {
  const StepLoop& outer = body.loops.at(0);
  if (body.rounds.profiled.size() != outer.curves.size())
    throw std::runtime_error("edge profile: one flag per curve of the outline is needed");
  std::vector<TopoDS_Edge> edges;
  for (const StepCurve& c : outer.curves) edges.push_back(make_edge(c, body.form));
  return edges;
}

// How far the body's solid lies from the exact one it describes: the slack
// a stopped round as tall as the edge was made smaller by, else 0.
double added_by_slack(const StepBody& body) {
  const StepEdgeRounds& r = body.rounds;
  if (body.form != StepForm::Extrusion || !(r.top > 0.0) || r.top + r.bottom < body.height) return 0.0;
  return profile_stops_on_tangent(body, outline_edges(body)) ? r.slack : 0.0;
}

// An extrusion with its edge profile. A round (or bevel) shorter than the
// side face is a fillet (chamfer) of the prism's edges. One as tall as the
// face (a half bullnose of the full thickness, a full bullnose's two
// rounds meeting half way) would consume the face, which fillets cannot:
// then each round is made on a taller prism, cut back to its height, and
// a full bullnose's two halves are joined. All exact.
TopoDS_Shape profiled_prism(const TopoDS_Face& face, const StepBody& body) {
  const std::vector<TopoDS_Edge> edges = outline_edges(body);
  if (profile_stops_on_tangent(body, edges)) return stopped_profile(face, body, edges);
  const ProfiledMiddles m = profiled_middles(body, edges);
  const double t = body.height, top = body.rounds.top, bottom = body.rounds.bottom;
  if (bottom <= 0.0) {
    if (top < t) return round_edges(prism_between(face, 0.0, t), body, m, 0.0, t, top, 0.0);
    return common_of(round_edges(prism_between(face, -t, t), body, m, -t, t, top, 0.0),
                     prism_between(face, 0.0, t));
  }
  if (top + bottom < t) return round_edges(prism_between(face, 0.0, t), body, m, 0.0, t, top, bottom);
  const double mid = bottom * t / (top + bottom);
  const TopoDS_Shape upper =
      common_of(round_edges(prism_between(face, mid - t, t), body, m, mid - t, t, top, 0.0),
                prism_between(face, mid, t));
  const TopoDS_Shape lower =
      common_of(round_edges(prism_between(face, 0.0, mid + t), body, m, 0.0, mid + t, 0.0, bottom),
                prism_between(face, 0.0, mid));
  TopTools_ListOfShape tools;
  tools.Append(lower);
  ShapeUpgrade_UnifySameDomain unify(
      boolean<BRepAlgoAPI_Fuse>(upper, tools, "joining the bullnose's halves"));
  unify.Build();
  return unify.Shape();
}

// A casting case: its box minus the mould part. The part fills the box but
// for the walls, so the cut must take exactly the part's volume: a cut that
// lost a face or a key would show.
TopoDS_Shape case_box(const StepBody& body) {
  const gp_Pnt lo(body.case_lo.x(), body.case_lo.y(), body.case_lo.z());
  const gp_Pnt hi(body.case_hi.x(), body.case_hi.y(), body.case_hi.z());
  if (!((body.case_hi - body.case_lo).minCoeff() > 0.0))
    throw std::runtime_error("a case's box without room");
  return BRepPrimAPI_MakeBox(lo, hi).Shape();
}

// A case's plate: its slab with the hemispheres added and taken away and its
// pins added, the module checking that its volume is the slab's plus and
// minus theirs (each meets the slab in its flat disc alone), to 1e-9 of the
// slab's.
TopoDS_Shape make_case_plate(const StepBody& body) {
  const TopoDS_Shape slab = case_box(body);
  TopoDS_Shape shape = slab;
  TopTools_ListOfShape added, removed;
  const double slab_volume = volume_of(slab);
  double expected = slab_volume;
  for (const StepHemisphere& h : body.hemispheres) {
    (h.added ? added : removed).Append(make_hemisphere(h));
    expected += (h.added ? 2.0 : -2.0) * M_PI * h.radius * h.radius * h.radius / 3.0;
  }
  for (const StepCylinder& c : body.cylinders) {  // the pins, standing on its face
    added.Append(make_cylinder(c));
    expected += M_PI * c.radius * c.radius * c.height;
  }
  if (!added.IsEmpty()) shape = boolean<BRepAlgoAPI_Fuse>(shape, added, "filling the plate's sockets");
  if (!removed.IsEmpty()) shape = boolean<BRepAlgoAPI_Cut>(shape, removed, "taking the plate's bumps away");
  shape = the_solid(shape);
  const double got = precise_volume_of(shape);
  if (!(std::abs(got - expected) <= 1e-9 * slab_volume)) {
    throw std::runtime_error("the case's plate as made holds " + std::to_string(got) +
                             ", not its slab with its keys, " + std::to_string(expected));
  }
  return shape;
}

// A prism: its section's polygon swept along its vector, or in a whole
// turn about the z axis.
TopoDS_Shape make_prism(const StepPrism& p) {
  BRepBuilderAPI_MakePolygon polygon;
  for (const Vec3& v : p.section) polygon.Add(gp_Pnt(v.x(), v.y(), v.z()));
  polygon.Close();
  if (!polygon.IsDone()) throw std::runtime_error("a prism's section is not a polygon");
  BRepBuilderAPI_MakeFace face(polygon.Wire(), true);
  if (!face.IsDone()) throw std::runtime_error("a prism's section is not a plane face");
  if (p.about_axis) {
    BRepPrimAPI_MakeRevol ring(face.Face(), gp_Ax1(gp::Origin(), gp::DZ()), 2.0 * M_PI);
    if (!ring.IsDone()) throw std::runtime_error("a section's turn about the axis failed");
    return ring.Shape();
  }
  BRepPrimAPI_MakePrism prism(face.Face(), gp_Vec(p.along.x(), p.along.y(), p.along.z()));
  if (!prism.IsDone()) throw std::runtime_error("a prism failed");
  return prism.Shape();
}

// A casting case: its box less the part (less its drafts' prisms) and the
// holes of its plate's pins (in the walls, apart from the part), to 1e-9 of
// the box's volume.
TopoDS_Shape make_case(const StepBody& body) {
  const TopoDS_Shape box = case_box(body);
  StepBody carved = body;  // its loops lie in the (radius, height) half-plane, as a Carved body's
  carved.form = StepForm::Carved;
  TopoDS_Shape part = make_carved(carved);
  if (!body.drafts.empty()) {
    TopTools_ListOfShape prisms;
    for (const StepPrism& p : body.drafts) prisms.Append(make_prism(p));
    part = the_solid(boolean<BRepAlgoAPI_Cut>(part, prisms, "leaning the part's free faces"));
  }
  TopTools_ListOfShape tools;
  tools.Append(part);
  double expected = volume_of(box) - precise_volume_of(part);
  for (const StepCylinder& c : body.cylinders) {  // the holes of a plate's pins, in its walls
    tools.Append(make_cylinder(c));
    expected -= M_PI * c.radius * c.radius * c.height;
  }
  const TopoDS_Shape shape = the_solid(boolean<BRepAlgoAPI_Cut>(box, tools, "taking the part from its case"));
  const double got = precise_volume_of(shape);
  if (!(std::abs(got - expected) <= 1e-9 * volume_of(box))) {
    throw std::runtime_error("the case as cut holds " + std::to_string(got) +
                             ", not its box less its part, " + std::to_string(expected));
  }
  return shape;
}

// A region a carved case is cut by: its box, with its fills, less its hollows.
TopoDS_Shape make_region(const StepRegion& r) {
  const double a = r.u.norm(), b = r.v.norm(), c = r.d.norm();
  if (!(a > 0.0 && b > 0.0 && c > 0.0)) throw std::runtime_error("a case's region without room");
  const gp_Ax2 frame(gp_Pnt(r.corner.x(), r.corner.y(), r.corner.z()), gp_Dir(r.d.x(), r.d.y(), r.d.z()),
                     gp_Dir(r.u.x(), r.u.y(), r.u.z()));
  TopoDS_Shape shape = BRepPrimAPI_MakeBox(frame, a, b, c).Shape();
  if (!r.fills.empty()) {
    TopTools_ListOfShape fills;
    for (const StepHemisphere& h : r.fills) fills.Append(make_hemisphere(h));
    shape = the_solid(boolean<BRepAlgoAPI_Fuse>(shape, fills, "filling the sockets of a piece's face"));
  }
  if (!r.hollows.empty()) {
    TopTools_ListOfShape hollows;
    for (const StepPrism& p : r.hollows) hollows.Append(make_prism(p));
    shape = the_solid(boolean<BRepAlgoAPI_Cut>(shape, hollows, "taking the block's inside from a lid"));
  }
  if (!r.adds.empty()) {
    TopTools_ListOfShape adds;
    for (const StepPrism& p : r.adds) adds.Append(make_prism(p));
    shape = the_solid(boolean<BRepAlgoAPI_Fuse>(shape, adds, "adding the vessel's slice to a piece"));
  }
  return shape;
}

// The largest tolerance of the edges of `shape`: how far OpenCASCADE lets
// an edge (a curve where faces were cut) stray from the faces it bounds.
double largest_edge_tolerance(const TopoDS_Shape& shape) {
  double largest = 0.0;
  for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More(); e.Next()) {
    largest = std::max(largest, BRep_Tool::Tolerance(TopoDS::Edge(e.Current())));
  }
  return largest;
}

// `whole` split by `region`: the part in it, the module checking that it and
// the rest hold `whole`'s volume, to 1e-9 of it plus the new faces' area
// times the largest edge tolerance of the two (a cut through a curved face
// follows its approximated section curve; a split that lost a face would
// show).
std::pair<TopoDS_Shape, TopoDS_Shape> split_by(const TopoDS_Shape& whole, const TopoDS_Shape& region) {
  TopTools_ListOfShape tool;
  tool.Append(region);
  const TopoDS_Shape in = boolean<BRepAlgoAPI_Common>(whole, tool, "cutting a piece of the case");
  const TopoDS_Shape out = boolean<BRepAlgoAPI_Cut>(whole, tool, "cutting the rest of the case");
  const double all = precise_volume_of(whole), got = precise_volume_of(in) + precise_volume_of(out);
  GProp_GProps surface;
  BRepGProp::SurfaceProperties(in, surface);
  const double slack =
      1e-9 * all + surface.Mass() * std::max(largest_edge_tolerance(in), largest_edge_tolerance(out));
  if (!(std::abs(got - all) <= slack)) {
    throw std::runtime_error("a piece of the case and the rest hold " + std::to_string(got) +
                             ", not the case's " + std::to_string(all));
  }
  return {in, out};
}

// A piece of a carved casting case: the case (its box less the part,
// checked as make_case checks it) cut by its regions in order, each cut
// checked; with its pins added and the holes of the pieces' before it (the
// main piece: all of them) taken away, the volume checked to 1e-9 of the
// piece's plus its area times its largest edge tolerance.
TopoDS_Shape make_case_piece(const StepBody& body) {
  StepBody whole = body;
  whole.form = StepForm::Case;
  whole.cylinders.clear();
  TopoDS_Shape rest = make_case(whole);
  TopoDS_Shape piece;
  const std::size_t last = body.piece == 0 ? body.regions.size() : body.piece;
  if (last > body.regions.size()) throw std::runtime_error("a piece of a case beyond its regions");
  for (std::size_t i = 0; i < last; ++i) {
    auto [in, out] = split_by(rest, make_region(body.regions[i]));
    piece = std::move(in);
    rest = std::move(out);
  }
  TopoDS_Shape shape = the_solid(body.piece == 0 ? rest : piece);
  if (body.cylinders.empty()) return shape;
  // Each pin adds what of it stands out of the piece, each hole (of a pin of
  // a piece taken off before) takes what of it reaches into the piece: both
  // measured on the piece before either, by exact common parts.
  TopTools_ListOfShape added, removed;
  double expected = precise_volume_of(shape);
  for (const StepCylinder& c : body.cylinders) {
    const TopoDS_Shape cylinder = make_cylinder(c);
    TopTools_ListOfShape one;
    one.Append(cylinder);
    const double within =
        precise_volume_of(boolean<BRepAlgoAPI_Common>(shape, one, "measuring a pin or hole"));
    expected += c.added ? precise_volume_of(cylinder) - within : -within;
    (c.added ? added : removed).Append(cylinder);
  }
  if (!added.IsEmpty()) shape = the_solid(boolean<BRepAlgoAPI_Fuse>(shape, added, "adding the piece's pins"));
  if (!removed.IsEmpty()) {
    shape = the_solid(boolean<BRepAlgoAPI_Cut>(shape, removed, "taking the pins' holes away"));
  }
  const double got = precise_volume_of(shape);
  GProp_GProps surface;
  BRepGProp::SurfaceProperties(shape, surface);
  if (!(std::abs(got - expected) <=
        1e-9 * std::abs(expected) + surface.Mass() * largest_edge_tolerance(shape))) {
    throw std::runtime_error("a piece of the case with its pins or holes holds " + std::to_string(got) +
                             ", not " + std::to_string(expected));
  }
  return shape;
}

TopoDS_Shape make_body(const StepBody& body) {
  if (body.form == StepForm::Sheet) return make_sheet(body);
  if (body.form == StepForm::Closed) return make_closed(body);
  if (body.form == StepForm::CasePlate) return make_case_plate(body);
  if (body.form == StepForm::CasePiece) return make_case_piece(body);
  if (body.loops.empty()) throw std::runtime_error("a body without loops");
  if (body.form == StepForm::Wireframe) {
    TopoDS_Compound compound;
    BRep_Builder builder;
    builder.MakeCompound(compound);
    for (std::size_t i = 0; i < body.loops.size(); ++i)
      builder.Add(compound, make_wire(body.loops[i], body.form, i));
    return compound;
  }
  if (body.form == StepForm::Carved) return make_carved(body);
  if (body.form == StepForm::Case) return make_case(body);
  if (body.form == StepForm::Slice) return make_slice(body);
  TopoDS_Shape shape;
  if (body.form == StepForm::Extrusion) {
    if (body.rounds.top > 0.0) {
      shape = profiled_prism(plane_face(body), body);
    } else {
      BRepPrimAPI_MakePrism prism(plane_face(body), gp_Vec(0.0, 0.0, body.height));
      if (!prism.IsDone()) throw std::runtime_error("the extrusion failed");
      shape = prism.Shape();
    }
  } else {
    shape = revolution_of(plane_face(body));
  }
  // Solids made from faces of either orientation: turned outward.
  for (TopExp_Explorer s(shape, TopAbs_SOLID); s.More(); s.Next()) {
    TopoDS_Solid solid = TopoDS::Solid(s.Current());
    BRepLib::OrientClosedSolid(solid);
  }
  return shape;
}

StepShapeFacts facts_of(const TopoDS_Shape& shape, bool precise) {
  StepShapeFacts f;
  f.valid = BRepCheck_Analyzer(shape).IsValid() == Standard_True;
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, TopAbs_SOLID, map);
  f.solids = map.Extent();
  map.Clear();
  TopExp::MapShapes(shape, TopAbs_FACE, map);
  f.faces = map.Extent();
  map.Clear();
  TopExp::MapShapes(shape, TopAbs_EDGE, map);
  f.edges = map.Extent();
  if (!f.valid) {
    // What the analyzer objects to, for the message: the first few sub-shapes' statuses.
    BRepCheck_Analyzer analyzer(shape);
    for (const TopAbs_ShapeEnum type : {TopAbs_EDGE, TopAbs_WIRE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID}) {
      int index = 0;
      for (TopExp_Explorer e(shape, type); e.More() && f.problems.size() < 400; e.Next()) {
        ++index;
        const Handle(BRepCheck_Result)& result = analyzer.Result(e.Current());
        if (result.IsNull()) continue;
        for (const BRepCheck_Status status : result->Status()) {
          if (status == BRepCheck_NoError) continue;
          std::ostringstream os;
          BRepCheck::Print(status, os);
          std::string text = os.str();
          while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
          f.problems += (f.problems.empty() ? "" : ", ") + std::string(TopAbs::ShapeTypeToString(type)) +
                        " " + std::to_string(index) + ": " + text;
        }
      }
    }
  }
  map.Clear();
  TopExp::MapShapes(shape, TopAbs_SHELL, map);
  f.shells = map.Extent();
  if (f.faces > 0) {
    const EdgeUses uses = edge_uses(shape);
    f.free_edges = uses.free;
    f.closed = f.solids > 0 && uses.all_twice;
    GProp_GProps surface;
    BRepGProp::SurfaceProperties(shape, surface);
    f.area = surface.Mass();
  }
  if (f.solids > 0) {
    GProp_GProps props;
    if (precise) {
      BRepGProp::VolumeProperties(shape, props, 1e-10);  // adaptive: what a reader checks pieces against
    } else {
      BRepGProp::VolumeProperties(shape, props);
    }
    f.volume = props.Mass();
  }
  return f;
}

// Names the products after the bodies and fixes the header: the same design
// gives the same bytes (no time stamp).
void label(const Handle(StepData_StepModel) & model, const StepModel& m) {
  APIHeaderSection_MakeHeader header(model);
  header.SetName(new TCollection_HAsciiString(m.name.c_str()));
  header.SetTimeStamp(new TCollection_HAsciiString("1970-01-01T00:00:00"));
  header.SetAuthorValue(1, new TCollection_HAsciiString(""));
  header.SetOrganizationValue(1, new TCollection_HAsciiString(""));
  header.SetOriginatingSystem(new TCollection_HAsciiString("fabmesh"));
  header.SetAuthorisation(new TCollection_HAsciiString(""));
  std::size_t body = 0;
  for (int i = 1; i <= model->NbEntities(); ++i) {
    Handle(StepBasic_Product) product = Handle(StepBasic_Product)::DownCast(model->Value(i));
    if (product.IsNull()) continue;
    const std::string& name = body < m.bodies.size() ? m.bodies[body].name : m.name;
    ++body;
    product->SetId(new TCollection_HAsciiString(name.c_str()));
    product->SetName(new TCollection_HAsciiString(name.c_str()));
  }
}

// Runs `body` on a fresh Out holding the lock, with OCCT quiet and its STEP
// controller initialised; an exception (OCCT's or ours) becomes out.error.
template <class Out, class Body>
Out with_occt(Body body) {
  Out out;
  try {
    const std::lock_guard<std::mutex> lock(occt_lock());
    quiet_occt();
    STEPControl_Controller::Init();
    body(out);
  } catch (const Standard_Failure& e) {
    out.error = std::string("OpenCASCADE: ") + e.GetMessageString();
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

// Reads `bytes` into `reader`, set to give shapes in the file's own unit
// (named in *unit when given); false with `error` set when refused.
bool read_into(STEPControl_Reader& reader, const std::string& bytes, std::string& error, std::string* unit) {
  std::istringstream in(bytes);
  if (reader.ReadStream("fabmesh.step", in) != IFSelect_RetDone) {
    error = "OpenCASCADE's STEP reader refused the file";
    return false;
  }
  const std::string file_unit = read_in_file_unit(reader);
  if (unit != nullptr) *unit = file_unit;
  return true;
}

StepWritten write_model(const StepModel& m) {
  return with_occt<StepWritten>([&m](StepWritten& out) {
    // The shapes are in the file's unit, and so is the file: nothing is scaled.
    // The settings exist once the STEP controller is initialised, and are set
    // before the writer exists: it takes them when it makes its model.
    const char* unit = occt_unit(m.unit);
    Interface_Static::SetCVal("write.step.schema", "AP214IS");
    Interface_Static::SetCVal("write.step.unit", unit);
    Interface_Static::SetCVal("xstep.cascade.unit", unit);
    Interface_Static::SetCVal("write.step.product.name", m.name.c_str());
    const double millimetres = millimetres_of(unit);
    UnitsMethods::SetCasCadeLengthUnit(millimetres);
    STEPControl_Writer writer;
    writer.Model()->SetLocalLengthUnit(millimetres);
    writer.Model()->SetWriteLengthUnit(millimetres);
    for (const StepBody& body : m.bodies) {
      const TopoDS_Shape shape = make_body(body);
      out.bodies.push_back(facts_of(shape, false));
      out.bodies.back().added = added_by_slack(body);
      const STEPControl_StepModelType mode = body.form == StepForm::Wireframe ? STEPControl_GeometricCurveSet
                                             : body.form == StepForm::Sheet
                                                 ? STEPControl_ShellBasedSurfaceModel
                                                 : STEPControl_ManifoldSolidBrep;
      if (writer.Transfer(shape, mode) != IFSelect_RetDone) {
        out.error = "OpenCASCADE could not translate body '" + body.name + "' into STEP";
        return;
      }
    }
    const Handle(StepData_StepModel) model = writer.Model();
    label(model, m);
    StepData_StepWriter sw(model);
    sw.SendModel(StepAP214::Protocol());
    std::ostringstream os;
    if (!sw.Print(os)) {
      out.error = "OpenCASCADE could not print the STEP file";
      return;
    }
    out.bytes = os.str();
  });
}

StepRead read_bytes(const std::string& bytes) {
  return with_occt<StepRead>([&bytes](StepRead& out) {
    STEPControl_Reader reader;
    if (!read_into(reader, bytes, out.error, &out.length_unit)) return;
    const int roots = reader.NbRootsForTransfer();
    for (int i = 1; i <= roots; ++i) {
      if (!reader.TransferRoot(i)) {
        out.error = "root " + std::to_string(i) + " did not transfer";
        return;
      }
    }
    for (int i = 1; i <= reader.NbShapes(); ++i) out.roots.push_back(facts_of(reader.Shape(i), true));
  });
}

// A face's or an edge's extremum search, set up once, and the box that holds
// the shape (from its geometry, enlarged by its tolerance).
template <typename Search>
struct Searched {
  TopoDS_Shape shape;
  std::unique_ptr<Search> search;
  Bnd_Box box;
  // The square of the distance from `p` to the box: no point of the shape is nearer.
  double box_distance2(const gp_Pnt& p) const {
    if (box.IsVoid()) return 0.0;  // no box: always searched
    double lo[3], hi[3];
    box.Get(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    const double at[3] = {p.X(), p.Y(), p.Z()};
    double d2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double out = std::max({lo[i] - at[i], at[i] - hi[i], 0.0});
      d2 += out * out;
    }
    return d2;
  }
};

template <typename Search>
Searched<Search> searched(const TopoDS_Shape& shape) {
  Searched<Search> s{shape, std::make_unique<Search>(), {}};
  BRepBndLib::Add(shape, s.box, false);  // the geometry's own box, not a triangulation's
  return s;
}

// The indices of `shapes`, the nearest box to `p` first.
template <typename Search>
std::vector<std::size_t> nearest_first(const std::vector<Searched<Search>>& shapes, const gp_Pnt& p) {
  std::vector<std::pair<double, std::size_t>> order;
  order.reserve(shapes.size());
  for (std::size_t i = 0; i < shapes.size(); ++i) order.emplace_back(shapes[i].box_distance2(p), i);
  std::sort(order.begin(), order.end());
  std::vector<std::size_t> indices;
  indices.reserve(order.size());
  for (const auto& o : order) indices.push_back(o.second);
  return indices;
}

StepDistances distances_to(const std::string& bytes, const std::vector<Vec3>& points) {
  return with_occt<StepDistances>([&bytes, &points](StepDistances& out) {
    STEPControl_Reader reader;
    if (!read_into(reader, bytes, out.error, nullptr)) return;
    reader.TransferRoots();
    const TopoDS_Shape shape = reader.OneShape();
    // Distances to the faces (or, for a wireframe, the edges): the least of
    // those to the faces' insides, to the edges' insides and to the
    // vertices. Each face's and edge's extremum search is set up once and
    // kept from point to point, where BRepExtrema_DistShapeShape sets them
    // up again for every point; nearest boxes first, and a face or edge
    // whose box is no nearer than the least distance yet is not searched.
    const bool has_faces = TopExp_Explorer(shape, TopAbs_FACE).More();
    // The faces' own edges and vertices (with faces, a free edge is not a target).
    TopTools_IndexedMapOfShape face_map, edge_map, vertex_map;
    if (has_faces) {
      TopExp::MapShapes(shape, TopAbs_FACE, face_map);
      for (int i = 1; i <= face_map.Extent(); ++i) {
        TopExp::MapShapes(face_map(i), TopAbs_EDGE, edge_map);
        TopExp::MapShapes(face_map(i), TopAbs_VERTEX, vertex_map);
      }
    } else {
      TopExp::MapShapes(shape, TopAbs_EDGE, edge_map);
      TopExp::MapShapes(shape, TopAbs_VERTEX, vertex_map);
    }
    std::vector<Searched<BRepExtrema_ExtPF>> faces;
    TopoDS_Compound all_faces;  // for a point a face's search fails on
    BRep_Builder builder;
    builder.MakeCompound(all_faces);
    for (int i = 1; i <= face_map.Extent(); ++i) {
      builder.Add(all_faces, face_map(i));
      faces.push_back(searched<BRepExtrema_ExtPF>(face_map(i)));
      faces.back().search->Initialize(TopoDS::Face(face_map(i)), Extrema_ExtFlag_MIN);
    }
    std::vector<Searched<BRepExtrema_ExtPC>> edges;
    for (int i = 1; i <= edge_map.Extent(); ++i) {
      const TopoDS_Edge edge = TopoDS::Edge(edge_map(i));
      if (BRep_Tool::Degenerated(edge)) continue;
      edges.push_back(searched<BRepExtrema_ExtPC>(edge));
      edges.back().search->Initialize(edge);
    }
    std::vector<gp_Pnt> vertices;
    for (int i = 1; i <= vertex_map.Extent(); ++i)
      vertices.push_back(BRep_Tool::Pnt(TopoDS::Vertex(vertex_map(i))));
    if (vertices.empty()) {
      out.error = "no distance found: the file has no vertices";
      return;
    }
    for (const Vec3& p : points) {
      const gp_Pnt at(p.x(), p.y(), p.z());
      const TopoDS_Vertex vertex = BRepBuilderAPI_MakeVertex(at).Vertex();
      double least = std::numeric_limits<double>::infinity();
      for (const gp_Pnt& v : vertices) least = std::min(least, at.SquareDistance(v));
      for (const std::size_t e : nearest_first(edges, at)) {
        if (!(edges[e].box_distance2(at) < least)) break;
        BRepExtrema_ExtPC& edge = *edges[e].search;
        edge.Perform(vertex);
        if (!edge.IsDone()) continue;  // parallel or degenerate: its ends are vertices
        for (int n = 1; n <= edge.NbExt(); ++n) {
          if (edge.IsMin(n)) least = std::min(least, edge.SquareDistance(n));
        }
      }
      bool found = true;
      for (const std::size_t f : nearest_first(faces, at)) {
        if (!(faces[f].box_distance2(at) < least)) break;
        BRepExtrema_ExtPF& face = *faces[f].search;
        face.Perform(vertex, TopoDS::Face(faces[f].shape));
        if (!face.IsDone()) {
          found = false;
          break;
        }
        for (int n = 1; n <= face.NbExt(); ++n) least = std::min(least, face.SquareDistance(n));
      }
      if (!found) {  // a face's search failed: OpenCASCADE's own measure for this point
        BRepExtrema_DistShapeShape extrema(vertex, all_faces);
        if (!extrema.IsDone()) {
          out.error = "no distance found";
          return;
        }
        least = std::min(least, extrema.Value() * extrema.Value());
      }
      out.max_distance = std::max(out.max_distance, std::sqrt(least));
    }
  });
}

}  // namespace
}  // namespace fabmesh

// The loader calls this through `const void* (*)()` (io/module.h): the type it
// is defined with, so the call is well defined; the table is a StepModuleApi.
extern "C" __attribute__((visibility("default"))) const void* fabmesh_step_module() {
  static const fabmesh::StepModuleApi api{fabmesh::kStepModuleAbi, &fabmesh::write_model,
                                          &fabmesh::read_bytes, &fabmesh::distances_to};
  return &api;
}
