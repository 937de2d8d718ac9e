// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_STRIP_SEGMENT_H
#define CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_STRIP_SEGMENT_H

// The strip coordinate map of one segment of a blending region (eq. 24):
// C_i(d, gamma) = sum_j B_j(gamma) (k_j + d n_j), with the quadratic Bernstein
// polynomials B_j, and its Jacobian.

#include <Eigen/Core>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// The determinant of a 2 x 2 matrix.
inline double det2(const Eigen::Matrix2d& A) { return A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0); }

/// Segment `i` of a region's strip: the control points `k_i, k_{i(i+1)},
/// k_{i+1}` of the curve and the normals `n_i, n_{i(i+1)}, n_{i+1}` (eq. 22,
/// 23), by reference into the region's data. Scalar code: this is the inner
/// loop of every lookup, and stays fast in debug builds.
struct Strip_segment
{
  const Eigen::Vector2d &k0, &k1, &k2; ///< the curve's control points
  const Eigen::Vector2d &n0, &n1, &n2; ///< the normals at them

  /// `C_i(d, gamma)`, eq. 24.
  Eigen::Vector2d point(double d, double gamma) const
  {
    const double s = 1. - gamma, b0 = s * s, b1 = 2. * gamma * s, b2 = gamma * gamma;
    return Eigen::Vector2d(b0 * (k0.x() + d * n0.x()) + b1 * (k1.x() + d * n1.x()) + b2 * (k2.x() + d * n2.x()),
                           b0 * (k0.y() + d * n0.y()) + b1 * (k1.y() + d * n1.y()) + b2 * (k2.y() + d * n2.y()));
  }

  /// The Jacobian `[∂C_i/∂d, ∂C_i/∂gamma]`.
  Eigen::Matrix2d jacobian(double d, double gamma) const
  {
    const double s = 1. - gamma, b0 = s * s, b1 = 2. * gamma * s, b2 = gamma * gamma;
    const double e0 = -2. * s, e1 = 2. - 4. * gamma, e2 = 2. * gamma; // Bernstein derivatives
    Eigen::Matrix2d A;
    A(0, 0) = b0 * n0.x() + b1 * n1.x() + b2 * n2.x();
    A(1, 0) = b0 * n0.y() + b1 * n1.y() + b2 * n2.y();
    A(0, 1) = e0 * (k0.x() + d * n0.x()) + e1 * (k1.x() + d * n1.x()) + e2 * (k2.x() + d * n2.x());
    A(1, 1) = e0 * (k0.y() + d * n0.y()) + e1 * (k1.y() + d * n1.y()) + e2 * (k2.y() + d * n2.y());
    return A;
  }

  /// `∂/∂gamma` of the normal blend `sum_j B_j(gamma) n_j` (`∂C/∂d`).
  Eigen::Vector2d normal_blend_derivative(double gamma) const
  {
    const double e0 = -2. * (1. - gamma), e1 = 2. - 4. * gamma, e2 = 2. * gamma;
    return Eigen::Vector2d(e0 * n0.x() + e1 * n1.x() + e2 * n2.x(), e0 * n0.y() + e1 * n1.y() + e2 * n2.y());
  }
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_STRIP_SEGMENT_H
