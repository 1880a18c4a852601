// Plane curves of the three families, evaluated exactly, sampled within a
// proven bound, composed and faired as in design files.

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "python/bind.h"

namespace fabmesh_python {
namespace {

// Curves: parameters as a float or an array of them.
template <class F>
py::object per_parameter(const py::handle& t, F&& f) {
  if (py::isinstance<py::float_>(t) || py::isinstance<py::int_>(t)) {
    const auto p = f(t.cast<double>());
    return py::array_t<double>(2, p.data());
  }
  const auto ts = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(t);
  if (!ts || ts.ndim() != 1) bad_argument("t", "must be a number or a 1-D array of numbers");
  py::array_t<double> out({ts.shape(0), py::ssize_t{2}});
  double* o = out.mutable_data();
  for (py::ssize_t i = 0; i < ts.shape(0); ++i) {
    const auto p = f(ts.data()[i]);
    o[2 * i] = p[0];
    o[2 * i + 1] = p[1];
  }
  return out;
}

std::vector<fabmesh::Point2> plane_points(const py::handle& points, const std::string& argument = "points") {
  py::array_t<double, py::array::c_style | py::array::forcecast> a =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if (!a || a.ndim() != 2 || a.shape(1) != 2) bad_argument(argument, "must have shape (N, 2)");
  std::vector<fabmesh::Point2> out(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {a.data()[2 * i], a.data()[2 * i + 1]};
  return out;
}

const char* continuity_name(fabmesh::Continuity c) {
  switch (c) {
    case fabmesh::Continuity::G0:
      return "G0";
    case fabmesh::Continuity::G1:
      return "G1";
    case fabmesh::Continuity::G2:
      return "G2";
    case fabmesh::Continuity::None:
      break;
  }
  return "none";
}

fabmesh::Continuity continuity_of(const py::handle& value, const std::string& argument) {
  if (py::isinstance<py::str>(value)) {
    const std::string name = value.cast<std::string>();
    if (name == "G0") return fabmesh::Continuity::G0;
    if (name == "G1") return fabmesh::Continuity::G1;
    if (name == "G2") return fabmesh::Continuity::G2;
  }
  bad_argument(argument, "must be 'G0', 'G1' or 'G2', got " + py::repr(value).cast<std::string>());
}

double number_of(const py::handle& value, const std::string& argument) {
  PyObject* number = nullptr;
  if (!py::isinstance<py::bool_>(value) && !py::isinstance<py::str>(value))
    number = PyNumber_Float(value.ptr());
  if (number == nullptr) {
    PyErr_Clear();
    bad_argument(argument, "must be a number, got " + py::repr(value).cast<std::string>());
  }
  const double v = PyFloat_AsDouble(number);
  Py_DECREF(number);
  return v;
}

// Each key of `dict` is one of `known`, or an InputError naming it.
void require_known_keys(const py::dict& dict, const std::vector<std::string>& known,
                        const std::string& where) {
  for (const auto& item : dict) {
    const std::string key = py::str(item.first).cast<std::string>();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      bad_argument(where + "." + key, "unknown key (known: " + list + ")");
    }
  }
}

py::dict dict_of(const py::handle& value, const std::string& argument) {
  if (!py::isinstance<py::dict>(value)) bad_argument(argument, "must be a dict");
  return py::reinterpret_borrow<py::dict>(value);
}

// One segment of fabmesh.composite, given with a design file's keys.
fabmesh::Segment segment_of(const py::handle& value, std::size_t i) {
  const std::string at = "segments[" + std::to_string(i) + "]";
  const py::dict d = dict_of(value, at);
  require_known_keys(d, {"family", "points", "lambda", "mu", "alpha", "join", "continuity"}, at);
  fabmesh::Segment s;
  if (d.contains("family")) {
    const std::string family = py::str(d["family"]).cast<std::string>();
    if (family == "tbezier") {
      s.family = fabmesh::SegmentFamily::TBezier;
    } else if (family == "hbezier") {
      s.family = fabmesh::SegmentFamily::HBezier;
    } else if (family == "line") {
      s.family = fabmesh::SegmentFamily::Line;
    } else {
      bad_argument(at + ".family", "must be 'tbezier', 'hbezier' or 'line', got '" + family + "'");
    }
  }
  if (!d.contains("points")) bad_argument(at + ".points", "is required");
  s.points = plane_points(d["points"], at + ".points");
  if (d.contains("lambda")) s.lambda = number_of(d["lambda"], at + ".lambda");
  if (d.contains("mu")) s.mu = number_of(d["mu"], at + ".mu");
  if (d.contains("alpha")) s.alpha = number_of(d["alpha"], at + ".alpha");
  if (d.contains("continuity")) s.continuity = continuity_of(d["continuity"], at + ".continuity");
  if (d.contains("join")) {
    const std::string where = at + ".join";
    const py::dict j = dict_of(d["join"], where);
    require_known_keys(j, {"continuity", "alpha", "beta", "k", "m"}, where);
    if (!j.contains("continuity")) bad_argument(where + ".continuity", "is required");
    fabmesh::Join join;
    join.continuity = continuity_of(j["continuity"], where + ".continuity");
    if (j.contains("alpha")) join.alpha = number_of(j["alpha"], where + ".alpha");
    if (j.contains("beta")) join.beta = number_of(j["beta"], where + ".beta");
    if (j.contains("k")) join.k = number_of(j["k"], where + ".k");
    if (j.contains("m")) join.m = number_of(j["m"], where + ".m");
    s.join = join;
  }
  return s;
}

fabmesh::Energy energy_of(const std::string& name) {
  if (name == "strain") return fabmesh::Energy::Strain;
  if (name == "curvature_variation") return fabmesh::Energy::CurvatureVariation;
  bad_argument("energy", "must be 'strain' or 'curvature_variation', got '" + name + "'");
}

py::list joints_of(const fabmesh::Curve& c) {
  py::list out;
  for (const fabmesh::Joint& j : c.joints()) {
    py::dict d;
    d["before"] = j.before;
    d["after"] = j.after;
    d["closing"] = j.closing;
    d["gap"] = j.gap;
    d["tangent_angle"] = j.tangent_angle;
    d["curvature_before"] = j.curvature_before;
    d["curvature_after"] = j.curvature_after;
    d["curvature_jump"] = j.curvature_jump;
    d["declared"] = continuity_name(j.declared);
    d["achieved"] = continuity_name(j.achieved);
    out.append(d);
  }
  return out;
}

py::object fairing_of(const fabmesh::Curve& c) {
  const std::optional<fabmesh::Fairing> f = c.fairing();
  if (!f) return py::none();
  py::dict d;
  d["energy"] = f->energy == fabmesh::Energy::Strain ? "strain" : "curvature_variation";
  d["before"] = f->energy_before;
  d["after"] = f->energy_after;
  return std::move(d);
}

py::object through_of(const fabmesh::Curve& c) {
  const std::optional<fabmesh::Through> t = c.through();
  if (!t) return py::none();
  py::dict d;
  d["points"] = matrix<2>(t->points);
  d["control_points"] = matrix<2>(t->control_points);
  d["deviation"] = t->deviation;
  return std::move(d);
}

}  // namespace

void bind_curves(py::module_& m) {
  py::class_<fabmesh::Curve>(
      m, "Curve",
      "A composite plane curve of n segments, parameter t in [0, n]: segment floor(t) at "
      "t - floor(t)")
      .def_property_readonly("segments", &fabmesh::Curve::segments)
      .def_property_readonly("closed", &fabmesh::Curve::closed)
      .def(
          "evaluate",
          [](const fabmesh::Curve& c, const py::handle& t) {
            return per_parameter(t, [&](double s) { return c.point(s); });
          },
          py::arg("t"), "The point at t (a float: shape (2,); an array of K parameters: shape (K, 2))")
      .def(
          "derivative",
          [](const fabmesh::Curve& c, const py::handle& t, int order) {
            return per_parameter(t, [&](double s) { return c.derivative(s, order); });
          },
          py::arg("t"), py::arg("order") = 1, "The derivative of order 1, 2 or 3 with respect to t")
      .def(
          "curvature",
          [](const fabmesh::Curve& c, const py::handle& t) -> py::object {
            if (py::isinstance<py::float_>(t) || py::isinstance<py::int_>(t))
              return py::float_(c.curvature(t.cast<double>()));
            const auto ts = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(t);
            if (!ts || ts.ndim() != 1) bad_argument("t", "must be a number or a 1-D array of numbers");
            py::array_t<double> out(ts.shape(0));
            for (py::ssize_t i = 0; i < ts.shape(0); ++i) out.mutable_data()[i] = c.curvature(ts.data()[i]);
            return std::move(out);
          },
          py::arg("t"), "Signed curvature at t (positive turning left), 1 / model units")
      .def(
          "sample",
          [](const fabmesh::Curve& c, double tolerance) {
            fabmesh::SampledCurve s;
            {
              py::gil_scoped_release free;
              s = c.sample(tolerance);
            }
            return py::make_tuple(matrix<2>(s.points), s.max_deviation);
          },
          py::arg("tolerance"),
          "Samples the curve within tolerance: returns (points of shape (K, 2), the proven bound achieved)")
      .def_property_readonly("joints", &joints_of,
                             "Every joint, measured on the exact curve: a list of dicts with before, after "
                             "(segment indices), closing, gap (model units), tangent_angle (radians), "
                             "curvature_before, curvature_after, curvature_jump (relative), declared and "
                             "achieved ('G0', 'G1', 'G2' or 'none')")
      .def_property_readonly("fairing", &fairing_of,
                             "For a curve made by fabmesh.fair (or faired by its design): {'energy': "
                             "'strain' or 'curvature_variation', 'before': ..., 'after': ...}; else None")
      .def_property_readonly("through", &through_of,
                             "For a curve made to pass through points (fabmesh.quasi_bspline_through, or a "
                             "design's through:): {'points': (K, 2) the points q0..qn, 'control_points': (K, "
                             "2) the control points solved from them, 'deviation': the proven largest "
                             "distance from a point to its joint}; else None")
      .def("__repr__", [](const fabmesh::Curve& c) {
        return "<fabmesh.Curve of " + std::to_string(c.segments()) + " segment" +
               (c.segments() == 1 ? "" : "s") + ">";
      });

  m.def(
      "tbezier",
      [](const py::handle& points, double lam, double mu) {
        return fabmesh::tbezier(plane_points(points), lam, mu);
      },
      py::arg("points"), py::arg("lam") = 0.0, py::arg("mu") = 0.0,
      "Cubic T-Bezier segments through 3n + 1 control points (shape (3n + 1, 2)), shape parameters lam, mu "
      "in "
      "[-2, 1]. Raises InputError.");
  m.def(
      "quasi_bspline",
      [](const py::handle& points, const std::optional<std::vector<double>>& lambdas) {
        return fabmesh::quasi_bspline(plane_points(points), lambdas.value_or(std::vector<double>{}));
      },
      py::arg("points"), py::arg("lambdas") = py::none(),
      "A quasi-cubic B-spline with control points p0..pn (shape (n + 1, 2), n >= 2) and shape parameters "
      "lambda_1..lambda_{n-1} in [-8, 1] (None: all 0). Raises InputError.");
  m.def(
      "quasi_bspline_through",
      [](const py::handle& points, const std::optional<std::vector<double>>& lambdas) {
        const std::vector<fabmesh::Point2> through = plane_points(points);
        py::gil_scoped_release free;
        return fabmesh::quasi_bspline_through(through, lambdas.value_or(std::vector<double>{}));
      },
      py::arg("points"), py::arg("lambdas") = py::none(),
      "The quasi-cubic B-spline that passes through points q0..qn (shape (n + 1, 2), n >= 2) at its "
      "joints, for shape parameters lambda_1..lambda_{n-1} in [-8, 1] (None: all 0): its control points "
      "solved exactly (docs/math/curves.md 2.3), given with the proven deviation by the result's .through. "
      "Raises InputError (key 'through': too few points, a singular system; 'lambdas').");
  m.def(
      "hbezier",
      [](const py::handle& points, double alpha, double lam, double mu) {
        return fabmesh::hbezier(plane_points(points), alpha, lam, mu);
      },
      py::arg("points"), py::arg("alpha") = 1.0, py::arg("lam") = 0.0, py::arg("mu") = 0.0,
      "Generalized cubic H-Bezier segments through 3n + 1 control points, alpha in (0, 10]. Raises "
      "InputError.");
  m.def(
      "composite",
      [](const py::sequence& segments, bool closed, const std::string& closing) {
        std::vector<fabmesh::Segment> list;
        for (std::size_t i = 0; i < segments.size(); ++i) list.push_back(segment_of(segments[i], i));
        const fabmesh::Continuity close = continuity_of(py::str(closing), "closing");
        py::gil_scoped_release free;
        return fabmesh::composite(list, closed, close);
      },
      py::arg("segments"), py::arg("closed") = false, py::arg("closing") = "G0",
      R"(A composite curve of T-Bezier, H-Bezier and line segments, each starting where the
previous one ends: the segments of a design file's composite curve, as dicts with
the same keys (docs/design-files.md):

  family      'tbezier' (default), 'hbezier' or 'line'
  points      (K, 2): a cubic's 4 control points, or after a join only the free ones
              (G0: 3, G1: 2, G2: 1); a line's [from, to] when first, else [to]
  lambda, mu  shape parameters (T-Bezier in [-2, 1])
  alpha       H-Bezier's hyperbolic parameter in (0, 10]
  join        {'continuity': 'G0'/'G1'/'G2', 'alpha', 'beta' (T-Bezier), 'k', 'm' (H-Bezier)}:
              the leading control points computed from the previous segment
  continuity  without a join: the continuity declared with the previous segment, verified

closed: the curve must end where it starts (a join on the first segment joins it to
the last); closing: the continuity declared for the closing joint. Raises InputError
naming the segment ('segments[1].join.k').)");
  m.def(
      "fair",
      [](const fabmesh::Curve& curve, const std::string& energy, const std::optional<std::string>& keeps) {
        const fabmesh::Energy e = energy_of(energy);
        std::optional<fabmesh::Continuity> k;
        if (keeps) k = continuity_of(py::str(*keeps), "keeps");
        py::gil_scoped_release free;
        return fabmesh::fair(curve, e, k);
      },
      py::arg("curve"), py::arg("energy") = "curvature_variation", py::arg("keeps") = py::none(),
      "The curve with the shape parameters that minimise the energy ('strain' or 'curvature_variation'), "
      "its control points kept: a quasi-cubic B-spline's lambdas, or each T-Bezier segment's lambda and mu "
      "(curvature_variation only). A joint may not fall below its declared continuity, or below keeps "
      "('G0', 'G1', 'G2') when given. The result's .fairing gives the energy before and after. Raises "
      "InputError (key 'energy' or 'keeps').");
  py::class_<fabmesh::BuiltCurve>(m, "BuiltCurve", "One of a design's curves as built")
      .def_readonly("key", &fabmesh::BuiltCurve::key,
                    "The design key: 'curve', 'profile', 'outline', 'holes[0]'")
      .def_property_readonly(
          "points", [](const fabmesh::BuiltCurve& c) { return matrix<2>(c.points); },
          "The sampled polyline, shape (K, 2), model units")
      .def_readonly("closed", &fabmesh::BuiltCurve::closed)
      .def_readonly("max_deviation", &fabmesh::BuiltCurve::max_deviation,
                    "Proven bound of the polyline against the exact curve, model units")
      .def_readonly("curve", &fabmesh::BuiltCurve::curve, "The exact curve, to evaluate");
}

}  // namespace fabmesh_python
