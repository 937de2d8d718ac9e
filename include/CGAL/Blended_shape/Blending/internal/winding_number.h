// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_WINDING_NUMBER_H
#define CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_WINDING_NUMBER_H

// The winding number of a loop of quadratic Bézier segments around a chart
// point, exact: which side of a blending region's curve a point is on.

#include <CGAL/Blended_shape/Blending/internal/Bezier_loop.h>

#include <Eigen/Core>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// The signed crossing of the edge `a b` with the ray from `u` toward +x:
/// +1 upward with `u` on its left, -1 downward with `u` on its right.
inline int edge_crossing(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& u)
{
  const double left = cross(b - a, u - a);
  if(a.y() <= u.y())
  {
    if(b.y() > u.y() && left > 0.)
      return 1;
  }
  else if(b.y() <= u.y() && left < 0.)
    return -1;
  return 0;
}

/// Whether `u` is in the closed triangle `(p0, p1, p2)`, `eps` included.
inline bool in_closed_triangle(const Eigen::Vector2d& u, const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                               const Eigen::Vector2d& p2, double eps)
{
  const double o0 = cross(p1 - p0, u - p0), o1 = cross(p2 - p1, u - p1), o2 = cross(p0 - p2, u - p2);
  return (o0 >= -eps && o1 >= -eps && o2 >= -eps) || (o0 <= eps && o1 <= eps && o2 <= eps);
}

/// The winding contribution of one quadratic segment: its control polygon's
/// when `u` is outside the control triangle (curve and polygon are homotopic
/// in the triangle), otherwise the two de Casteljau halves'. Amounts to an
/// adaptively refined polyline of the curve.
inline int segment_winding(const Eigen::Vector2d& u, const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                           const Eigen::Vector2d& p2, double eps, int depth = 0)
{
  if(depth >= 52 || !in_closed_triangle(u, p0, p1, p2, eps))
    return edge_crossing(p0, p1, u) + edge_crossing(p1, p2, u);
  const Eigen::Vector2d q0 = 0.5 * (p0 + p1), q1 = 0.5 * (p1 + p2), m = 0.5 * (q0 + q1);
  return segment_winding(u, p0, q0, m, eps, depth + 1) + segment_winding(u, m, q1, p2, eps, depth + 1);
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_WINDING_NUMBER_H
