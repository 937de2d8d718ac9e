// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef BLENDED_SHAPE_TESTING_EQUIVARIANCE_H
#define BLENDED_SHAPE_TESTING_EQUIVARIANCE_H

#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <blended_shape_testing/compare_superquadrics.h>
#include <CGAL/Blended_shape/internal/quaternion.h>
#include <blended_shape_testing/synthetic_scans.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace testing {

// How far fit_superquadric() of a cloud and of its copy moved by a random
// similarity (rotation, translation of about 10, scale 3.7) are apart. For
// tests and benchmarks.
struct Equivariance_gap
{
  std::array<double, 3> relative_rms = {{0., 0., 0.}}; // |RMS_j(copy) - RMS_j| / RMS_j (eq. 14)
  double surface = 0.; // the fitted surfaces apart (both ways), over the copy's bounding-box diagonal
};

template <class Point_3, class RandomEngine>
Equivariance_gap equivariance_gap(const std::vector<Point_3>& points, RandomEngine& rng)
{
  std::normal_distribution<double> g(0., 1.);
  const Eigen::Matrix3d R = internal::rotation_matrix(Eigen::Vector4d(g(rng), g(rng), g(rng), g(rng)));
  const Eigen::Vector3d t(10. * g(rng), 10. * g(rng), 10. * g(rng));
  const double scale = 3.7;
  auto T = [&](const Point_3& p) {
    const Eigen::Vector3d y = scale * (R * Eigen::Vector3d(p.x(), p.y(), p.z())) + t;
    return Point_3(y[0], y[1], y[2]);
  };
  auto T_inverse = [&](const Point_3& p) {
    const Eigen::Vector3d y = R.transpose() * (Eigen::Vector3d(p.x(), p.y(), p.z()) - t) / scale;
    return Point_3(y[0], y[1], y[2]);
  };
  std::vector<Point_3> moved;
  for(const Point_3& p : points)
    moved.push_back(T(p));
  const auto a = fit_superquadric(points), b = fit_superquadric(moved);
  Equivariance_gap gap;
  for(std::size_t j = 0; j < 3; ++j)
    gap.relative_rms[j] = std::abs(a.metrics.relative_rms[j] - b.metrics.relative_rms[j]) / a.metrics.relative_rms[j];
  gap.surface = (std::max)(surface_distance(a.model, T, b.model), scale * surface_distance(b.model, T_inverse, a.model)) /
                bounding_box_diagonal(moved);
  return gap;
}

} // namespace testing
} // namespace Blended_shapes
} // namespace CGAL

#endif // BLENDED_SHAPE_TESTING_EQUIVARIANCE_H
