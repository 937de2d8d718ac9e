// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INTERNAL_STRAY_SURFACE_POINTS_H
#define CGAL_BLENDED_SHAPE_FITTING_INTERNAL_STRAY_SURFACE_POINTS_H

#include <CGAL/Blended_shape/internal/nearest_points.h>

#include <Eigen/Eigenvalues>

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// How many of the points judged stray (`stray`) lie on a surface of their
// own, as the part of a scan that a wrong rest of a robust fit leaves out
// does: not isolated (`isolated`, internal::isolated_points()), with at
// least `share` of their `k` nearest other points judged stray too, and
// those neighbours (with the point) flat: the smallest eigenvalue of their
// covariance at most `flatness` of its trace. Strays spread through a
// volume are isolated or have neighbours spread in all directions (for a
// point and its 16 nearest among points spread uniformly, the smallest
// eigenvalue is about a fifth of the trace; `test_fitting strays` checks
// that at most 1 % of such points count); strays next to the fitted
// surface have most of their neighbours on it, where no point is judged stray.
inline std::size_t count_stray_surface_points(const std::vector<Eigen::Vector3d>& points,
                                              const std::vector<bool>& stray, const std::vector<bool>& isolated,
                                              std::size_t k = 16, double share = 0.75, double flatness = 0.03)
{
  std::vector<Eigen::Vector3d> queries;
  for(std::size_t i = 0; i < points.size(); ++i)
    if(stray[i] && !isolated[i])
      queries.push_back(points[i]);
  if(queries.empty() || points.size() <= k)
    return 0;
  // k + 1: each query is a point of the cloud, its own nearest one
  const std::vector<std::size_t> nearest = k_nearest_points(points, queries, k + 1);
  std::size_t count = 0;
  for(std::size_t q = 0; q < queries.size(); ++q)
  {
    const std::size_t* neighbours = &nearest[q * (k + 1)];
    std::size_t stray_neighbours = 0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for(std::size_t j = 0; j <= k; ++j)
    {
      stray_neighbours += stray[neighbours[j]] ? 1 : 0;
      mean += points[neighbours[j]];
    }
    if(double(stray_neighbours - 1) < share * double(k)) // (the query itself is stray)
      continue;
    mean /= double(k + 1);
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for(std::size_t j = 0; j <= k; ++j)
    {
      const Eigen::Vector3d d = points[neighbours[j]] - mean;
      covariance += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance, Eigen::EigenvaluesOnly);
    if(eigen.eigenvalues()[0] <= flatness * covariance.trace())
      ++count;
  }
  return count;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INTERNAL_STRAY_SURFACE_POINTS_H
