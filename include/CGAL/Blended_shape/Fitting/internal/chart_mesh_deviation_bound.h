// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INTERNAL_CHART_MESH_DEVIATION_BOUND_H
#define CGAL_BLENDED_SHAPE_FITTING_INTERNAL_CHART_MESH_DEVIATION_BOUND_H

#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// How far a point of the model's surface can be from the chart meshes
/// positioned on it (`mask` as Closest_point_locator::set_face_mask(), or
/// null for every face): twice the largest distance between the model point
/// and the mesh point at the same chart point, sampled at the centroid and
/// the edge midpoints of every face (the samples on the surface). The mesh
/// interpolates the surface at its vertices; the deviation of a smooth map
/// from its linear interpolant is about quadratic over a triangle, largest
/// near those samples, and the factor 2 covers the rest. Then a surface
/// point at distance `d` from a query point has a mesh point within
/// `d + bound` of it, and a search for the closest mesh point can be
/// bounded by that.
template <class Model, class GeomTraits>
double chart_mesh_deviation_bound(const std::vector<Chart_mesh<GeomTraits>>& charts,
                                  const std::vector<std::vector<bool>>* mask, const Model& model)
{
  static const std::array<std::array<double, 3>, 4> samples = {
    {{{1. / 3., 1. / 3., 1. / 3.}}, {{0.5, 0.5, 0.}}, {{0., 0.5, 0.5}}, {{0.5, 0., 0.5}}}};
  const auto position = [](const typename GeomTraits::Point_3& q) {
    return Eigen::Vector3d(CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z()));
  };
  double largest = 0.;
  for(std::size_t i = 0; i < charts.size(); ++i)
    for(auto f : faces(charts[i].mesh()))
    {
      if(mask != nullptr && !(*mask)[i][std::size_t(f)])
        continue;
      const auto v = charts[i].face_vertices(f);
      const Eigen::Vector3d corner[3] = {position(charts[i].mesh().point(v[0])), position(charts[i].mesh().point(v[1])),
                                         position(charts[i].mesh().point(v[2]))};
      for(const auto& b : samples)
      {
        const Chart_point u = charts[i].chart_point(f, b);
        if(!model.is_on_surface(u))
          continue;
        const Eigen::Vector3d on_mesh = b[0] * corner[0] + b[1] * corner[1] + b[2] * corner[2];
        largest = (std::max)(largest, (position(model.point(u)) - on_mesh).norm());
      }
    }
  return 2. * largest;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INTERNAL_CHART_MESH_DEVIATION_BOUND_H
