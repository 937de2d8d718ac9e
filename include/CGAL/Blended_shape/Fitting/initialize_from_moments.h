// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INITIALIZE_FROM_MOMENTS_H
#define CGAL_BLENDED_SHAPE_FITTING_INITIALIZE_FROM_MOMENTS_H

#include <CGAL/Blended_shape/IO/check_points.h>
#include <CGAL/Blended_shape/internal/isolated_points.h>
#include <CGAL/Blended_shape/internal/point_range_types.h>
#include <CGAL/Blended_shape/internal/quaternion.h>
#include <CGAL/Blended_shape/parameters.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

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

namespace internal {

// Mean and covariance of the points `kept` of `points` (all if `kept` is
// empty), accumulated relative to `origin` and in two passes so that clouds
// far from the origin (scanner coordinates) lose no precision.
inline std::pair<Eigen::Vector3d, Eigen::Matrix3d> mean_and_covariance(const std::vector<Eigen::Vector3d>& points,
                                                                     const std::vector<bool>& kept,
                                                                     const Eigen::Vector3d& origin)
{
  auto is_kept = [&](std::size_t i) { return kept.empty() || kept[i]; };
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double n = 0.;
  for(std::size_t i = 0; i < points.size(); ++i)
    if(is_kept(i))
    {
      sum += points[i] - origin;
      n += 1.;
    }
  const Eigen::Vector3d mean = sum / n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for(std::size_t i = 0; i < points.size(); ++i)
    if(is_kept(i))
    {
      const Eigen::Vector3d d = points[i] - origin - mean;
      cov += d * d.transpose();
    }
  return {origin + mean, cov / n};
}

// The principal directions of the covariance `cov` of `points` about their
// centroid `c`, largest spread first, as the columns of a rotation, with the
// eigenvalues in `lambda`. The first two are oriented by the sign of the third
// central moment along them, so that the frame follows the pose of the cloud
// (equivariance); a direction of symmetry gets the sign that makes its largest
// component positive.
inline Eigen::Matrix3d oriented_principal_frame(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& c,
                                                const Eigen::Matrix3d& cov, Eigen::Vector3d& lambda)
{
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Vector3d skew = Eigen::Vector3d::Zero();
  for(const Eigen::Vector3d& p : points)
  {
    const Eigen::Vector3d d = eig.eigenvectors().transpose() * (p - c);
    skew += d.cwiseProduct(d).cwiseProduct(d);
  }
  Eigen::Matrix3d R;
  for(int i = 0; i < 3; ++i) // Eigen sorts ascending; we want the largest first
  {
    lambda[i] = (std::max)(eig.eigenvalues()[2 - i], 0.);
    Eigen::Vector3d d = eig.eigenvectors().col(2 - i);
    const double m3 = skew[2 - i] / double(points.size());
    if(std::abs(m3) > 1e-6 * std::pow(lambda[i], 1.5))
    {
      if(m3 < 0.) d = -d;
    }
    else
    {
      int k = 0;
      for(int j = 1; j < 3; ++j)
        if(std::abs(d[j]) > std::abs(d[k])) k = j;
      if(d[k] < 0.) d = -d;
    }
    R.col(i) = d;
  }
  R.col(2) = R.col(0).cross(R.col(1)); // right-handed
  return R;
}

// The semi-axes of the algebraic fit min sum_i (k . y_i^2 - 1)^2, y_i the
// points in the frame (c, R), if every k_i > 0 and each axis is within a
// factor 2 of `moment_axes` (see initialize_from_moments()).
inline std::optional<std::array<double, 3>> refined_semi_axes(const std::vector<Eigen::Vector3d>& points,
                                                             const Eigen::Vector3d& c, const Eigen::Matrix3d& R,
                                                             const std::array<double, 3>& moment_axes)
{
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for(const Eigen::Vector3d& p : points)
  {
    const Eigen::Vector3d y = R.transpose() * (p - c);
    const Eigen::Vector3d y2 = y.cwiseProduct(y);
    A += y2 * y2.transpose();
    b += y2;
  }
  const Eigen::Vector3d k = A.ldlt().solve(b);
  std::array<double, 3> refined;
  for(std::size_t i = 0; i < 3; ++i)
  {
    if(!(k[Eigen::Index(i)] > 0.) || !std::isfinite(k[Eigen::Index(i)]))
      return std::nullopt;
    refined[i] = 1. / std::sqrt(k[Eigen::Index(i)]);
    const double ratio = refined[i] / moment_axes[i];
    if(!(ratio > 0.5 && ratio < 2.))
      return std::nullopt;
  }
  return refined;
}

// The ellipsoid of the moments of `points` (see initialize_from_moments()).
template <class Geom_traits>
Ellipsoid_fit<Geom_traits> ellipsoid_from_moments(const std::vector<Eigen::Vector3d>& points, bool refine,
                                                  double min_ratio)
{
  typedef typename Geom_traits::Point_3 Point_3;
  const auto [c, cov] = mean_and_covariance(points, {}, points.front());
  Eigen::Vector3d lambda;
  const Eigen::Matrix3d R = oriented_principal_frame(points, c, cov, lambda);

  Ellipsoid_fit<Geom_traits> fit;
  fit.center = Point_3(c[0], c[1], c[2]);
  fit.rotation = internal::quaternion_from_matrix(R);
  fit.number_of_points = points.size();
  for(int i = 0; i < 3; ++i)
    fit.moment_axes[std::size_t(i)] = std::sqrt(3. * lambda[i]);
  fit.axes = fit.moment_axes;

  const double thin = 1e-6 * fit.moment_axes[0];
  if(fit.moment_axes[1] <= thin)
    fit.degeneracy = Point_cloud_degeneracy::Collinear;
  else if(fit.moment_axes[2] <= thin)
    fit.degeneracy = Point_cloud_degeneracy::Coplanar;
  if(refine && fit.degeneracy == Point_cloud_degeneracy::None)
    if(const auto refined = refined_semi_axes(points, c, R, fit.moment_axes))
    {
      fit.axes = *refined;
      fit.axes_refined = true;
    }
  const double largest = (std::max)({fit.axes[0], fit.axes[1], fit.axes[2]});
  for(double& a : fit.axes)
    a = (std::max)(a, min_ratio * largest);
  return fit;
}

// The coordinates of the points, checked (check_points()).
template <class PointRange, class NamedParameters>
std::vector<Eigen::Vector3d> checked_point_coordinates(const PointRange& points, const NamedParameters& np)
{
  const auto point_map = Point_range_types<PointRange, NamedParameters>::point_map(np);
  check_points(points, point_map);
  std::vector<Eigen::Vector3d> result;
  for(const auto& item : points)
  {
    const auto& p = get(point_map, item);
    result.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  }
  return result;
}

} // namespace internal

namespace internal {

struct Moment_options
{
  bool refine;
  double minimum_axis_ratio;
};

// The named parameters of initialize_from_moments().
template <class NamedParameters>
Moment_options moment_options(const NamedParameters& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const Moment_options options{choose_parameter(get_parameter(np, internal_np::refine_axes), true),
                               choose_parameter(get_parameter(np, internal_np::minimum_axis_ratio), 0.01)};
  if(!(options.minimum_axis_ratio > 0. && options.minimum_axis_ratio <= 1.))
    throw std::invalid_argument("initialize_from_moments: minimum_axis_ratio must be in (0, 1]");
  return options;
}

} // namespace internal

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
  typedef typename internal::Point_range_types<PointRange, NamedParameters>::Geom_traits Geom_traits;
  const internal::Moment_options options = internal::moment_options(np);
  return internal::ellipsoid_from_moments<Geom_traits>(internal::checked_point_coordinates(points, np),
                                                      options.refine, options.minimum_axis_ratio);
}

namespace internal {

// The geometric median (Weiszfeld's iteration from the centroid): a centre
// that half the points, wherever they are, cannot move far, and that follows
// rotations, translations and scalings of the cloud.
inline Eigen::Vector3d geometric_median(const std::vector<Eigen::Vector3d>& points)
{
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for(const Eigen::Vector3d& p : points) c += p - points.front();
  c = points.front() + c / double(points.size());
  for(int iteration = 0; iteration < 100; ++iteration)
  {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double weights = 0.;
    for(const Eigen::Vector3d& p : points)
    {
      const double d = (p - c).norm();
      if(d > 0.)
      {
        sum += (p - c) / d;
        weights += 1. / d;
      }
    }
    if(!(weights > 0.))
      break;
    const Eigen::Vector3d step = sum / weights;
    c += step;
    if(step.norm() <= 1e-12 * (std::sqrt(1. / weights) + c.norm()))
      break;
  }
  return c;
}

} // namespace internal

/// \ingroup PkgBlendedShapeInitialization
/// A point is kept by initialize_from_trimmed_moments() if its Mahalanobis
/// distance is at most this factor times that of a sphere's points,
/// `sqrt(3)`: with room for boxy superellipsoids, whose corners are
/// farther (those of a flat box, about 1.53 times).
constexpr double trimmed_moments_cutoff = 1.75;

/// \ingroup PkgBlendedShapeInitialization
/// initialize_from_trimmed_moments() leaves out the points whose distance to
/// their 8th nearest neighbour is over this factor times the median of that
/// distance: stray points spread through a volume around the object.
constexpr double isolated_point_factor = 3.;

/// \ingroup PkgBlendedShapeInitialization
/// initialize_from_trimmed_moments() looks at every `k`-th point of a larger
/// cloud, `k` the smallest that leaves at most this many.
constexpr std::size_t trimmed_moments_sample_size = 20000;

/*!
\ingroup PkgBlendedShapeInitialization

The best-fit ellipsoid of initialize_from_moments() fitted to the points of
`points` that are not stray: the moments of many stray points spread over
a box around the object give an ellipsoid the size of the box. The points
kept are found by isolation, then iterative trimming:

0. the isolated points are left out: those whose distance to their 8th
   nearest neighbour is over isolated_point_factor (3) times the median of
   that distance. The points of a scanned surface lie at about the sampling
   spacing from their neighbours; strays spread through a volume are much
   farther from theirs (with 40 % of the points spread over twice the
   object's bounding box, about four times as far). This needs the strays
   to be fewer than the points of the surface (the median is a surface
   point's); a surface point left out costs the moments little;
1. start: the points within twice the median distance `m` of the geometric
   median `c` (`|p_i - c| <= 2 m`);
2. repeat with the mean `mu` and covariance `Sigma` of the points kept: keep
   the points whose Mahalanobis distance
   `d_i^2 = (p_i - mu)^T Sigma^-1 (p_i - mu)` is at most
   `3 k^2`, `k` = trimmed_moments_cutoff (points spread over a sphere are all at `d_i^2 = 3`),
   until the set no longer changes (at most 50 times);
3. the result is initialize_from_moments() of the points kept.

A cloud without strays and without isolated points whose points are
spread evenly keeps every point, and the result is that of
initialize_from_moments(). One of uneven density may lose its sparse part
(a scanned cylinder's dense cap and sparse side keep 952 of 1325 points:
the trimming shrinks onto the dense part; see the user manual, Robust
Weights). Strays that are not
isolated and lie inside the ellipsoid of step 2 are kept. Without step 0,
over a box twice the object's size they made the ellipsoid too large (up to
twice along its short axes for a flat object), and a fit with robust weights
could settle among the strays (two of five clouds of 40 % strays over twice
the box, in `fit_single_superquadric --outliers 0.4 --outlier-box 2`).

A cloud of more than trimmed_moments_sample_size points is looked at
through every `k`-th point (the order of the input): enough for an
ellipsoid, and the nearest-neighbour search stays a small part of a fit.
`number_of_points` is the number of points kept (of those looked at).

Named parameters, exceptions: as for initialize_from_moments().
*/
template <class PointRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
auto initialize_from_trimmed_moments(const PointRange& points,
                                     const NamedParameters& np = CGAL::parameters::default_values())
{
  typedef typename internal::Point_range_types<PointRange, NamedParameters>::Geom_traits Geom_traits;
  const internal::Moment_options options = internal::moment_options(np);
  std::vector<Eigen::Vector3d> all = internal::checked_point_coordinates(points, np);
  if(all.size() > trimmed_moments_sample_size)
  {
    const std::size_t stride = (all.size() + trimmed_moments_sample_size - 1) / trimmed_moments_sample_size;
    std::size_t n = 0;
    for(std::size_t i = 0; i < all.size(); i += stride)
      all[n++] = all[i];
    all.resize(n);
  }

  // Step 0: the isolated points cannot be kept.
  std::vector<bool> allowed = internal::isolated_points(all, 8, isolated_point_factor);
  allowed.flip();
  const Eigen::Vector3d c = internal::geometric_median(all);
  std::vector<double> distance(all.size());
  for(std::size_t i = 0; i < all.size(); ++i) distance[i] = (all[i] - c).norm();
  std::vector<double> sorted = distance;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
  const double start_radius = 2. * sorted[sorted.size() / 2];
  std::vector<bool> kept(all.size());
  for(std::size_t i = 0; i < all.size(); ++i) kept[i] = allowed[i] && distance[i] <= start_radius;

  const double cutoff = 3. * CGAL::square(trimmed_moments_cutoff);
  for(int iteration = 0; iteration < 50; ++iteration)
  {
    const auto [mean, cov] = internal::mean_and_covariance(all, kept, c);
    // a tiny ridge: flat clouds have a singular covariance
    const Eigen::Matrix3d inverse = (cov + 1e-12 * cov.trace() * Eigen::Matrix3d::Identity()).inverse();
    std::vector<bool> next(all.size());
    for(std::size_t i = 0; i < all.size(); ++i)
      next[i] = allowed[i] && (all[i] - mean).dot(inverse * (all[i] - mean)) <= cutoff;
    if(next == kept)
      break;
    kept = std::move(next);
  }
  auto kept_points = [&] {
    std::vector<Eigen::Vector3d> inliers;
    for(std::size_t i = 0; i < all.size(); ++i)
      if(kept[i]) inliers.push_back(all[i]);
    return inliers.size() < minimum_number_of_points ? all : inliers; // nothing sensible to trim to
  };
  return internal::ellipsoid_from_moments<Geom_traits>(kept_points(), options.refine, options.minimum_axis_ratio);
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INITIALIZE_FROM_MOMENTS_H
