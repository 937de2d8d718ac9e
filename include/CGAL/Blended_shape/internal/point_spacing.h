// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_POINT_SPACING_H
#define CGAL_BLENDED_SHAPE_INTERNAL_POINT_SPACING_H

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The distance of each point to its `k`-th nearest other point (a k-d
// tree); all 0 if there are no more than `k` points.
inline std::vector<double> kth_neighbour_distances(const std::vector<Eigen::Vector3d>& points, std::size_t k)
{
  typedef CGAL::Simple_cartesian<double> K;
  typedef CGAL::Search_traits_3<K> Traits;
  typedef CGAL::Orthogonal_k_neighbor_search<Traits> Search;
  std::vector<double> distance(points.size(), 0.);
  if(points.size() <= k)
    return distance;
  std::vector<K::Point_3> copy;
  copy.reserve(points.size());
  for(const Eigen::Vector3d& p : points)
    copy.emplace_back(p.x(), p.y(), p.z());
  const Search::Tree tree(copy.begin(), copy.end());
  for(std::size_t i = 0; i < copy.size(); ++i)
  {
    // k + 1: the point itself is its own nearest neighbour
    const Search search(tree, copy[i], unsigned(k + 1));
    double farthest = 0.;
    for(const auto& neighbour : search)
      farthest = (std::max)(farthest, neighbour.second); // squared distances
    distance[i] = std::sqrt(farthest);
  }
  return distance;
}

// The median of `values` (not empty).
inline double median_of(std::vector<double> values)
{
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(values.size() / 2), values.end());
  return values[values.size() / 2];
}

// The median distance of the points to their nearest other point; 0 for
// fewer than two points. Duplicated points count with distance 0.
inline double median_spacing(const std::vector<Eigen::Vector3d>& points)
{
  return points.size() < 2 ? 0. : median_of(kth_neighbour_distances(points, 1));
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_INTERNAL_POINT_SPACING_H
