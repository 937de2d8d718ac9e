// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INITIALIZE_FROM_MOMENTS_H
#define CGAL_BLENDED_SHAPE_FITTING_INITIALIZE_FROM_MOMENTS_H

#include <CGAL/Blended_shape/IO/check_points.h>
#include <CGAL/Blended_shape/internal/quaternion.h>
#include <CGAL/Blended_shape/internal/point_range_types.h>
#include <CGAL/Blended_shape/parameters.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <stdexcept>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeInitialization
/// How flat a point cloud is, as found by initialize_from_moments().
enum class Point_cloud_degeneracy
{
  None,      ///< the cloud spans 3D
  Coplanar,  ///< all points on a plane: the smallest axis was set by `minimum_axis_ratio`
  Collinear  ///< all points on a line: the two smaller axes were set by `minimum_axis_ratio`
};

/*!
\ingroup PkgBlendedShapeInitialization
The best-fit ellipsoid of a point cloud (paper sec. 5.3): the initial closed
model, placed as `x = c + R s` (eq. 5) with `s` an ellipsoid of
semi-axes `axes` (`e1 = e2 = 1`).
*/
template <class GeomTraits>
struct Ellipsoid_fit
{
  typedef typename GeomTraits::Point_3 Point_3;   ///< the point type
  typedef typename GeomTraits::Vector_3 Vector_3; ///< the vector type

  Point_3 center;                 ///< centroid of the points
  Eigen::Vector4d rotation;       ///< unit quaternion (w, x, y, z), w >= 0, of R
  std::array<double, 3> axes;     ///< semi-axes a1 >= a2 >= a3 (before refinement) along the columns of R
  std::array<double, 3> moment_axes; ///< the central-moment estimates sqrt(3 lambda_i)
  bool axes_refined = false;      ///< whether the algebraic refinement was accepted
  Point_cloud_degeneracy degeneracy = Point_cloud_degeneracy::None; ///< whether the cloud is flat
  std::size_t number_of_points = 0; ///< the number of points fitted

  /// The rotation matrix R; its columns are the principal directions.
  Eigen::Matrix3d rotation_matrix() const { return internal::rotation_matrix(rotation); }
  /// The `i`-th principal direction (column `i` of R), largest spread first.
  Vector_3 direction(int i) const
  {
    const Eigen::Matrix3d R = rotation_matrix();
    return Vector_3(R(0, i), R(1, i), R(2, i));
  }
};

/*!
\ingroup PkgBlendedShapeInitialization

Fits the initial ellipsoid to `points` from their central moments (sec. 5.3):
the centre is the centroid, the axes directions are the eigenvectors of the
covariance matrix (largest spread first; the first two are oriented so that
the third central moment along each is positive, which makes the result follow
any rotation, translation or uniform scaling of the cloud, and the third
completes a right-handed frame, so R is a rotation; a direction along which the
cloud is symmetric gets the sign that makes its largest component positive), and
the semi-axes are `sqrt(3 lambda_i)` (`lambda_i` the eigenvalues), exact for
points spread uniformly over a sphere.

For non-spherical shapes the moment estimate is biased (about 13 % short on
the long axis of a 4:1 ellipsoid surface), so by default the semi-axes are
then refined, with the centre and directions kept, by the linear least-squares
fit of `sum_i k_i y_i^2 = 1` in the principal frame; the refinement is
kept only if every `k_i > 0` and each refined axis is within a factor 2 of
its moment estimate (it is exact for points on an ellipsoid, and the guard
keeps the moment estimate for partial or noisy views where it is not).

Degenerate clouds are a documented result, never NaN: if the cloud is
coplanar (collinear), the smallest (two smallest) semi-axes are set to
`minimum_axis_ratio` times the largest, and `degeneracy` says so.

\tparam PointRange a model of `ConstRange` whose value type is the key type of the point map.

\param points the input points
\param np an optional sequence of named parameters:
  - `point_map` (CGAL::parameters): property map to `Point_3`; default identity.
  - `geom_traits` (CGAL::parameters): the kernel; default deduced from the point type.
  - `refine_axes` (Blended_shapes::parameters): `bool`, default `true`.
  - `minimum_axis_ratio` (Blended_shapes::parameters): `double` in (0, 1], default `0.01`.

\throws Input_error (see check_points()) if the range is empty, has fewer than
  `minimum_number_of_points` points, a non-finite point, or all points identical.
\throws std::invalid_argument if `minimum_axis_ratio` is not in (0, 1].
*/
template <class PointRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
auto initialize_from_moments(const PointRange& points,
                             const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  typedef internal::Point_range_types<PointRange, NamedParameters> Types;
  typedef typename Types::Point_3 Point_3;
  typedef typename Types::Geom_traits Geom_traits;

  const typename Types::Point_map point_map = Types::point_map(np);
  const bool refine = choose_parameter(get_parameter(np, internal_np::refine_axes), true);
  const double min_ratio = choose_parameter(get_parameter(np, internal_np::minimum_axis_ratio), 0.01);
  if(!(min_ratio > 0. && min_ratio <= 1.))
    throw std::invalid_argument("initialize_from_moments: minimum_axis_ratio must be in (0, 1]");

  check_points(points, point_map);

  // Centroid and covariance, accumulated relative to the first point so that
  // clouds far from the origin (scanner coordinates) lose no precision.
  auto coords = [&](const auto& item) {
    const Point_3& p = get(point_map, item);
    return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  };
  const Eigen::Vector3d origin = coords(*points.begin());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for(const auto& item : points) { sum += coords(item) - origin; ++n; }
  const Eigen::Vector3d mean = sum / double(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for(const auto& item : points)
  {
    const Eigen::Vector3d d = coords(item) - origin - mean;
    cov += d * d.transpose();
  }
  cov /= double(n);

  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Vector3d lambda;
  Eigen::Matrix3d R;
  // Third central moments along each direction: their signs orient the axes
  // the same way whatever the pose of the cloud (equivariance).
  Eigen::Vector3d skew = Eigen::Vector3d::Zero();
  for(const auto& item : points)
  {
    const Eigen::Vector3d d = eig.eigenvectors().transpose() * (coords(item) - origin - mean);
    skew += d.cwiseProduct(d).cwiseProduct(d);
  }
  for(int i = 0; i < 3; ++i) // Eigen sorts ascending; we want the largest first
  {
    lambda[i] = (std::max)(eig.eigenvalues()[2 - i], 0.);
    Eigen::Vector3d d = eig.eigenvectors().col(2 - i);
    const double m3 = skew[2 - i] / double(n);
    if(std::abs(m3) > 1e-6 * std::pow(lambda[i], 1.5))
    {
      if(m3 < 0.) d = -d;
    }
    else // symmetric along d: any sign is as good; make the largest component positive
    {
      int k = 0;
      for(int j = 1; j < 3; ++j)
        if(std::abs(d[j]) > std::abs(d[k])) k = j;
      if(d[k] < 0.) d = -d;
    }
    R.col(i) = d;
  }
  R.col(2) = R.col(0).cross(R.col(1)); // right-handed

  Ellipsoid_fit<Geom_traits> fit;
  const Eigen::Vector3d c = origin + mean;
  fit.center = Point_3(c[0], c[1], c[2]);
  fit.rotation = internal::quaternion_from_matrix(R);
  fit.number_of_points = n;
  for(int i = 0; i < 3; ++i)
    fit.moment_axes[std::size_t(i)] = std::sqrt(3. * lambda[i]);
  fit.axes = fit.moment_axes;

  const double thin = 1e-6 * fit.moment_axes[0];
  if(fit.moment_axes[1] <= thin)
    fit.degeneracy = Point_cloud_degeneracy::Collinear;
  else if(fit.moment_axes[2] <= thin)
    fit.degeneracy = Point_cloud_degeneracy::Coplanar;

  if(refine && fit.degeneracy == Point_cloud_degeneracy::None)
  {
    // min sum (k . y^2 - 1)^2 over the points, y in the principal frame
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for(const auto& item : points)
    {
      const Eigen::Vector3d y = R.transpose() * (coords(item) - c);
      const Eigen::Vector3d y2 = y.cwiseProduct(y);
      A += y2 * y2.transpose();
      b += y2;
    }
    const Eigen::Vector3d k = A.ldlt().solve(b);
    bool ok = k.allFinite();
    std::array<double, 3> refined;
    for(int i = 0; ok && i < 3; ++i)
    {
      ok = k[i] > 0.;
      if(ok)
      {
        refined[std::size_t(i)] = 1. / std::sqrt(k[i]);
        const double ratio = refined[std::size_t(i)] / fit.moment_axes[std::size_t(i)];
        ok = ratio > 0.5 && ratio < 2.;
      }
    }
    if(ok)
    {
      fit.axes = refined;
      fit.axes_refined = true;
    }
  }
  const double largest = (std::max)({fit.axes[0], fit.axes[1], fit.axes[2]});
  for(double& a : fit.axes)
    a = (std::max)(a, min_ratio * largest);
  return fit;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INITIALIZE_FROM_MOMENTS_H
