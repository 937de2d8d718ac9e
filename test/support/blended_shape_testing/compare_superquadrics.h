// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef BLENDED_SHAPE_TESTING_COMPARE_SUPERQUADRICS_H
#define BLENDED_SHAPE_TESTING_COMPARE_SUPERQUADRICS_H

#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>
#include <CGAL/Blended_shape/Fitting/Closest_point_locator.h>
#include <CGAL/Blended_shape/Primitives/check_primitive.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace CGAL {
namespace Blended_shapes {
namespace testing {

// How far a fitted superquadric ellipsoid is from a true one, modulo the
// symmetries of the representation: the frames may differ by a signed
// permutation of axes (and the quaternion by its sign). Each fitted axis is
// matched to the true axis it is most parallel to; sizes follow their axes.
// If the fitted z axis is not the true z axis, the shapes are only the same
// when the true exponents are equal, so both fitted exponents are compared
// with both true ones. For tests and benchmarks.
struct Superquadric_comparison
{
  double axis_alignment = 0.;          // smallest |cos| between matched axes
  double size_error = 0.;              // largest |a_fit / a_true - 1|
  double exponent_error = 0.;          // largest |e_fit - e_true| (see above)
  bool z_axis_exchanged = false;
};

template <class Model>
Superquadric_comparison compare_superquadrics(const Model& fit, const Model& truth)
{
  Superquadric_comparison c;
  const Eigen::Matrix3d M = truth.rotation().transpose() * fit.rotation();
  const auto qf = fit.shape().parameters(), qt = truth.shape().parameters();
  c.axis_alignment = 1.;
  int perm[3];
  for(int j = 0; j < 3; ++j)
  {
    int i = 0;
    for(int k = 1; k < 3; ++k)
      if(std::abs(M(k, j)) > std::abs(M(i, j))) i = k;
    perm[j] = i;
    c.axis_alignment = (std::min)(c.axis_alignment, std::abs(M(i, j)));
    c.size_error = (std::max)(c.size_error, std::abs(qf[j] / qt[i] - 1.));
  }
  c.z_axis_exchanged = perm[2] != 2;
  if(!c.z_axis_exchanged)
    c.exponent_error = (std::max)(std::abs(qf[3] - qt[3]), std::abs(qf[4] - qt[4]));
  else
    c.exponent_error = (std::max)({std::abs(qf[3] - qt[3]), std::abs(qf[4] - qt[4]),
                                   std::abs(qf[3] - qt[4]), std::abs(qf[4] - qt[3])});
  return c;
}

// The largest distance from points of `from` (500 random chart points of
// its shape, moved by `T`) to the surface of `to` (closest points on a fine
// tessellation, refined on the analytic surface): how far apart two fitted
// surfaces are, whatever their parameterizations (the same surface may come
// out with its axes or exponents permuted). For tests and benchmarks.
template <class Model, class Transform>
double surface_distance(const Model& from, const Transform& T, const Model& to)
{
  const auto meshes = make_chart_meshes(to, 24);
  const Closest_point_locator<typename Model::Geom_traits> locator(meshes);
  std::mt19937_64 r(3);
  double worst = 0.;
  for(int i = 0; i < 500; ++i)
  {
    const Chart_point u = random_chart_point(from.shape(), std::size_t(i % 2), r);
    const auto x = T(from.point(u));
    const Eigen::Vector3d p(CGAL::to_double(x.x()), CGAL::to_double(x.y()), CGAL::to_double(x.z()));
    const Chart_point v = refine_closest_point(to, p, locator.locate(x).chart_point, 100);
    const auto y = to.point(v);
    worst = (std::max)(worst, (p - Eigen::Vector3d(CGAL::to_double(y.x()), CGAL::to_double(y.y()),
                                                   CGAL::to_double(y.z()))).norm());
  }
  return worst;
}

} // namespace testing
} // namespace Blended_shapes
} // namespace CGAL

#endif // BLENDED_SHAPE_TESTING_COMPARE_SUPERQUADRICS_H
