#include "geometry/surfaces/bspline_face.h"

namespace fabmesh {

std::vector<double> full_knots(const std::vector<double>& knots, const std::vector<int>& multiplicities) {
  std::vector<double> out;
  for (std::size_t k = 0; k < knots.size(); ++k)
    out.insert(out.end(), static_cast<std::size_t>(multiplicities[k]), knots[k]);
  return out;
}

namespace {

// The curve of `poles` (degree p, full clamped knots) at x: de Boor.
Vec3 de_boor(const std::vector<double>& knots, int p, const Vec3* poles, std::size_t count, double x) {
  std::size_t span = static_cast<std::size_t>(p);
  while (span + 1 < count && knots[span + 1] <= x) ++span;
  std::vector<Vec3> d(poles + (span - static_cast<std::size_t>(p)), poles + span + 1);
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const std::size_t i = span - static_cast<std::size_t>(p) + static_cast<std::size_t>(j);
      const double lo = knots[i], hi = knots[i + static_cast<std::size_t>(p + 1 - r)];
      const double a = hi > lo ? (x - lo) / (hi - lo) : 0.0;
      d[static_cast<std::size_t>(j)] =
          (1.0 - a) * d[static_cast<std::size_t>(j) - 1] + a * d[static_cast<std::size_t>(j)];
    }
  }
  return d[static_cast<std::size_t>(p)];
}

}  // namespace

Vec3 face_point(const BSplineFace& face, double u, double v) {
  const std::vector<double> ku = full_knots(face.u_knots, face.u_multiplicities),
                            kv = full_knots(face.v_knots, face.v_multiplicities);
  std::vector<Vec3> column;
  column.reserve(face.u_poles);
  for (std::size_t k = 0; k < face.u_poles; ++k)
    column.push_back(de_boor(kv, face.v_degree, &face.poles[k * face.v_poles], face.v_poles, v));
  return de_boor(ku, face.u_degree, column.data(), column.size(), u);
}

}  // namespace fabmesh
