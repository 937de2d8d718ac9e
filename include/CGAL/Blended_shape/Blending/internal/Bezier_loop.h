// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_BEZIER_LOOP_H
#define CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_BEZIER_LOOP_H

// The closed curve `kappa` of a blending region (App. A.2, eq. 19-21): a loop
// of quadratic Bézier segments in the chart plane, given by the control points
// `k_{i(i+1)}` and the ratios `mu_i`.

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// `a x b`, the signed area of the parallelogram of two chart vectors.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// `a` rotated by +90 degrees (its left normal).
inline Eigen::Vector2d perp(const Eigen::Vector2d& a) { return Eigen::Vector2d(-a.y(), a.x()); }

/// The quadratic Bézier curve of `(p0, p1, p2)` at `g` (eq. 21).
inline Eigen::Vector2d bezier(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                              double g)
{
  const double s = 1. - g;
  return (s * s) * p0 + (2. * g * s) * p1 + (g * g) * p2;
}

/// Its derivative with respect to `g`.
inline Eigen::Vector2d bezier_derivative(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                                         const Eigen::Vector2d& p2, double g)
{
  return 2. * (1. - g) * (p1 - p0) + 2. * g * (p2 - p1);
}

/// The segment end points `k_i = k_{(i-1)i}(1 - mu_i) + k_{i(i+1)} mu_i` (eq. 20).
inline std::vector<Eigen::Vector2d> loop_vertices(const std::vector<Eigen::Vector2d>& control,
                                                  const std::vector<double>& mu)
{
  const std::size_t n = control.size();
  std::vector<Eigen::Vector2d> vertex(n);
  for(std::size_t i = 0; i < n; ++i)
    vertex[i] = control[(i + n - 1) % n] * (1. - mu[i]) + control[i] * mu[i];
  return vertex;
}

/// The area enclosed by the loop, positive if counterclockwise, exact: the
/// polygon of the `k_i` plus 2/3 of each control triangle.
inline double loop_signed_area(const std::vector<Eigen::Vector2d>& vertex, const std::vector<Eigen::Vector2d>& control)
{
  const std::size_t n = control.size();
  double area = 0.;
  for(std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector2d& p0 = vertex[i];
    const Eigen::Vector2d& p2 = vertex[(i + 1 == n) ? 0 : i + 1];
    area += 0.5 * cross(p0, p2) + (2. / 3.) * 0.5 * cross(control[i] - p0, p2 - p0);
  }
  return area;
}

/// One de Casteljau step on segment `i` at `gamma` (A.2.1), in the data of
/// eq. 19-20: the two new control points `k_{is}`, `k_{s(i+1)}` and the
/// ratios at `k_i` and `k_{i+1}` that keep those end points where they are.
struct Segment_split
{
  Eigen::Vector2d first_control;  ///< `k_{is}`, replaces `k_{i(i+1)}`
  Eigen::Vector2d second_control; ///< `k_{s(i+1)}`, inserted after it
  double mu_start;                ///< the new `mu_i`
  double mu_end;                  ///< the new `mu_{i+1}`
};

/// The split of the segment `(ki, kc, kj)` with ratios `mu_i`, `mu_j` at its ends.
inline Segment_split split_segment(const Eigen::Vector2d& ki, const Eigen::Vector2d& kc, const Eigen::Vector2d& kj,
                                   double mu_i, double mu_j, double gamma)
{
  Segment_split s;
  s.first_control = (1. - gamma) * ki + gamma * kc;
  s.second_control = (1. - gamma) * kc + gamma * kj;
  // k_i = lerp(k_{(i-1)i}, k_is, mu'), k_{i+1} = lerp(k_s(i+1), k_{(i+1)(i+2)}, mu'')
  s.mu_start = mu_i / (mu_i + gamma * (1. - mu_i));
  s.mu_end = (1. - gamma) * mu_j / (1. - gamma * mu_j);
  return s;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_BEZIER_LOOP_H
