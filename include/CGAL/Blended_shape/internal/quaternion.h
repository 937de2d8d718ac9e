// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_QUATERNION_H
#define CGAL_BLENDED_SHAPE_INTERNAL_QUATERNION_H

#include <Eigen/Core>

#include <array>
#include <cmath>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// Quaternions are stored (w, x, y, z). The rotation of a non-unit quaternion
// is that of q / |q|, so the model parameters need no unit-norm constraint
// and the Jacobian below accounts for the normalization.

/// Rotation matrix of q / |q|.
inline Eigen::Matrix3d rotation_matrix(const Eigen::Vector4d& q)
{
  const Eigen::Vector4d u = q / q.norm();
  const double w = u[0], x = u[1], y = u[2], z = u[3];
  Eigen::Matrix3d R;
  R << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
       2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
       2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return R;
}

/// The unit quaternion with w >= 0 of a rotation matrix (Shepperd's method:
/// divide by the largest of the four candidate magnitudes for accuracy).
inline Eigen::Vector4d quaternion_from_matrix(const Eigen::Matrix3d& R)
{
  const double t = R.trace();
  Eigen::Vector4d q;
  if(t >= R(0, 0) && t >= R(1, 1) && t >= R(2, 2))
  {
    const double s = 2. * std::sqrt(1. + t);
    q << 0.25 * s, (R(2, 1) - R(1, 2)) / s, (R(0, 2) - R(2, 0)) / s, (R(1, 0) - R(0, 1)) / s;
  }
  else if(R(0, 0) >= R(1, 1) && R(0, 0) >= R(2, 2))
  {
    const double s = 2. * std::sqrt(1. + R(0, 0) - R(1, 1) - R(2, 2));
    q << (R(2, 1) - R(1, 2)) / s, 0.25 * s, (R(0, 1) + R(1, 0)) / s, (R(0, 2) + R(2, 0)) / s;
  }
  else if(R(1, 1) >= R(2, 2))
  {
    const double s = 2. * std::sqrt(1. + R(1, 1) - R(0, 0) - R(2, 2));
    q << (R(0, 2) - R(2, 0)) / s, (R(0, 1) + R(1, 0)) / s, 0.25 * s, (R(1, 2) + R(2, 1)) / s;
  }
  else
  {
    const double s = 2. * std::sqrt(1. + R(2, 2) - R(0, 0) - R(1, 1));
    q << (R(1, 0) - R(0, 1)) / s, (R(0, 2) + R(2, 0)) / s, (R(1, 2) + R(2, 1)) / s, 0.25 * s;
  }
  if(q[0] < 0.)
    q = -q;
  return q / q.norm();
}

/// dR/dq_k for R = rotation_matrix(q), k = 0..3 (w, x, y, z), including the
/// normalization: dR/dq = (dR/du)(I - u u^T) / |q| with u = q / |q|.
inline std::array<Eigen::Matrix3d, 4> rotation_matrix_derivatives(const Eigen::Vector4d& q)
{
  const double n = q.norm();
  const Eigen::Vector4d u = q / n;
  const double w = u[0], x = u[1], y = u[2], z = u[3];
  // derivatives of the unit-quaternion formula with respect to u
  std::array<Eigen::Matrix3d, 4> dU;
  dU[0] << 0, -2 * z, 2 * y,   2 * z, 0, -2 * x,   -2 * y, 2 * x, 0;
  dU[1] << 0, 2 * y, 2 * z,   2 * y, -4 * x, -2 * w,   2 * z, 2 * w, -4 * x;
  dU[2] << -4 * y, 2 * x, 2 * w,   2 * x, 0, 2 * z,   -2 * w, 2 * z, -4 * y;
  dU[3] << -4 * z, -2 * w, 2 * x,   2 * w, -4 * z, 2 * y,   2 * x, 2 * y, 0;
  std::array<Eigen::Matrix3d, 4> dQ;
  for(int k = 0; k < 4; ++k)
  {
    dQ[std::size_t(k)].setZero();
    for(int m = 0; m < 4; ++m)
    {
      const double p = ((m == k) ? 1. : 0.) - u[m] * u[k]; // (I - u u^T)_{mk}
      dQ[std::size_t(k)] += dU[std::size_t(m)] * (p / n);
    }
  }
  return dQ;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_INTERNAL_QUATERNION_H
