// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_ISOLATED_POINTS_H
#define CGAL_BLENDED_SHAPE_INTERNAL_ISOLATED_POINTS_H

#include <CGAL/Blended_shape/IO/Input_error.h>
#include <CGAL/Blended_shape/internal/point_spacing.h>

#include <Eigen/Core>

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
// Where the other points could not be fitted (fewer than
// minimum_number_of_points, or all identical: one point repeated and a few
// others), none is isolated: every caller then goes on with all the points.
inline std::vector<bool> isolated_points(const std::vector<Eigen::Vector3d>& points, std::size_t k = 8,
                                         double factor = 4.)
{
  std::vector<bool> isolated(points.size(), false);
  if(points.size() <= k)
    return isolated;
  const std::vector<double> distance = kth_neighbour_distances(points, k);
  const double limit = factor * median_of(distance);
  std::size_t kept = 0;
  const Eigen::Vector3d* first_kept = nullptr;
  bool spread = false;
  for(std::size_t i = 0; i < points.size(); ++i)
  {
    isolated[i] = distance[i] > limit;
    if(isolated[i])
      continue;
    ++kept;
    if(first_kept == nullptr)
      first_kept = &points[i];
    else if(points[i] != *first_kept)
      spread = true;
  }
  if(kept < minimum_number_of_points || !spread)
    isolated.assign(points.size(), false);
  return isolated;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_INTERNAL_ISOLATED_POINTS_H
