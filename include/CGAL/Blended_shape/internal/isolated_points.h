// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_ISOLATED_POINTS_H
#define CGAL_BLENDED_SHAPE_INTERNAL_ISOLATED_POINTS_H

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

// Whether each point is isolated: its distance to its `k`-th nearest
// neighbour exceeds `factor` times the median of that distance over all
// points. Points of a scanned surface lie at the sampling spacing from
// their neighbours; stray points spread through a volume are much farther
// from theirs (with 40 % of the points spread over twice the bounding box,
// about four times). Unlike a robust fit's weights, this does not depend on
// the model: the points of a part that the model does not reach yet are not
// isolated, so they pull the model towards the part (sec. 5.4).
inline std::vector<bool> isolated_points(const std::vector<Eigen::Vector3d>& points, std::size_t k = 8,
                                         double factor = 4.)
{
  typedef CGAL::Simple_cartesian<double> K;
  typedef CGAL::Search_traits_3<K> Traits;
  typedef CGAL::Orthogonal_k_neighbor_search<Traits> Search;
  std::vector<bool> isolated(points.size(), false);
  if(points.size() <= k)
    return isolated;
  std::vector<K::Point_3> copy;
  copy.reserve(points.size());
  for(const Eigen::Vector3d& p : points)
    copy.emplace_back(p.x(), p.y(), p.z());
  const Search::Tree tree(copy.begin(), copy.end());
  std::vector<double> distance(points.size());
  for(std::size_t i = 0; i < copy.size(); ++i)
  {
    // k + 1: the point itself is its own nearest neighbour.
    const Search search(tree, copy[i], unsigned(k + 1));
    double farthest = 0.;
    for(const auto& neighbour : search)
      farthest = (std::max)(farthest, neighbour.second); // squared distances
    distance[i] = std::sqrt(farthest);
  }
  std::vector<double> sorted = distance;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
  const double limit = factor * sorted[sorted.size() / 2];
  for(std::size_t i = 0; i < points.size(); ++i)
    isolated[i] = distance[i] > limit;
  return isolated;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_INTERNAL_ISOLATED_POINTS_H
