// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_SUPERQUADRIC_RADIAL_PROJECTION_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_SUPERQUADRIC_RADIAL_PROJECTION_H

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The radial projection of a direction `v` onto the unit superquadric
//
//   H(u) = (|ux|^(2/e2) + |uy|^(2/e2))^(e2/e1) + |uz|^(2/e1) = 1,
//
// the point r v with r = H(v)^(-e1/2) (H is homogeneous of degree 2/e1).
// Every quantity is computed for the direction scaled so that its largest
// component has modulus 1: the projection does not depend on the scale, and
// there every power stays in range down to exponents of 0.01 (H in [1, 2^200]),
// where the powers of a unit vector's components would underflow.
//
// G below is the gradient of H over 2/e1:
//   Gx = w^(e2/e1 - 1) |ux|^(2/e2 - 1) sign(ux),   (w = |ux|^(2/e2) + |uy|^(2/e2))
//   Gz = |uz|^(2/e1 - 1) sign(uz),
// finite for exponents up to 2 (see gradient() and gxy() for how each factor
// is taken), and u . G = H (Euler's relation), which keeps H > 0 and G != 0.
struct Superquadric_radial_projection
{
  Eigen::Vector3d u;        // the direction, scaled: largest |component| is 1
  double scale = 1.;        // u = scale v
  double e1 = 1., e2 = 1.;
  double X = 0., Y = 0.;    // |ux|^(2/e2), |uy|^(2/e2)
  double w = 0.;            // X + Y
  double P = 0.;            // w^(e2/e1)
  double Z = 0.;            // |uz|^(2/e1)
  double H = 1.;            // P + Z
  double r = 1.;            // H^(-e1/2): the point on the unit superquadric is r u

  // \pre v != 0, finite; e1, e2 in (0, 2]
  Superquadric_radial_projection(const Eigen::Vector3d& v, double ee1, double ee2) : e1(ee1), e2(ee2)
  {
    scale = 1. / v.cwiseAbs().maxCoeff();
    u = scale * v;
    X = pow_unless_one(std::abs(u.x()), 2. / e2);
    Y = pow_unless_one(std::abs(u.y()), 2. / e2);
    w = X + Y;
    P = (w > 0.) ? pow_unless_one(w, e2 / e1) : 0.;
    Z = pow_unless_one(std::abs(u.z()), 2. / e1);
    H = P + Z;
    r = pow_unless_one(H, -0.5 * e1);
  }

  // The point on the unit superquadric.
  Eigen::Vector3d point() const { return r * u; }

  // The gradient of H over 2/e1, at u. Its factors are quotients of the
  // powers already taken (|c|^(2/e - 1) = |c|^(2/e) / |c|, w^(e2/e1 - 1) =
  // P / w), which saves the hot path (the chart Jacobian of every
  // closest-point step) six transcendental calls; where w is so small that
  // P / w could overflow, or a power is subnormal (few significant bits),
  // the powers are taken instead.
  Eigen::Vector3d gradient() const
  {
    double gz = 0.;
    if(u.z() != 0.)
      gz = std::copysign(Z >= min_normal_power ? Z / std::abs(u.z()) : std::pow(std::abs(u.z()), 2. / e1 - 1.), u.z());
    return Eigen::Vector3d(gxy(u.x(), X), gxy(u.y(), Y), gz);
  }

  // d(point)/dv = scale r (I - u G^T / H): the derivative of the projection
  // with respect to the direction (it annihilates v, the map being constant
  // along rays).
  Eigen::Matrix3d derivative() const
  {
    return (scale * r) * (Eigen::Matrix3d::Identity() - u * (gradient().transpose() / H));
  }

  // The derivatives of ln r with respect to the exponents, which share ln w
  // (taken once: the parameter Jacobian of every point in every sweep):
  //   d(ln r)/d e1 = -(1/2) ln H - (e1 / 2H) dH/de1,
  //     dH/de1 = -(e2/e1^2) P ln w - (2/e1^2) Z ln|uz|;
  //   d(ln r)/d e2 = -(e1 / 2H) dP/de2,
  //     dP/de2 = (P/e1) (ln w - (2/e2) (X ln|ux| + Y ln|uy|) / w).
  void d_log_radius_d_exponents(double& d_e1, double& d_e2) const
  {
    const double log_w = (P > 0.) ? std::log(w) : 0.;
    double dH = 0.;
    if(P > 0.)
      dH -= (e2 / (e1 * e1)) * P * log_w;
    if(Z > 0.)
      dH -= (2. / (e1 * e1)) * Z * std::log(std::abs(u.z()));
    d_e1 = -0.5 * std::log(H) - (0.5 * e1 / H) * dH;
    d_e2 = 0.;
    if(!(P > 0.))
      return;
    double s = 0.;
    if(X > 0.)
      s += X * std::log(std::abs(u.x()));
    if(Y > 0.)
      s += Y * std::log(std::abs(u.y()));
    const double dP = (P / e1) * (log_w - (2. / e2) * s / w);
    d_e2 = -(0.5 * e1 / H) * dP;
  }

private:
  static constexpr double min_normal_power = 1e-290; // well above the subnormals

  // std::pow(b, e), without the call where b is 1: the largest component of
  // u is 1 in most projections (and w is 1 where it is ux or uy and the other
  // is 0), and glibc's pow() computes its logarithm and exponential even
  // there. The same value, bit for bit.
  static double pow_unless_one(double b, double e) { return b == 1. ? 1. : std::pow(b, e); }

  // w^(e2/e1 - 1) |c|^(2/e2 - 1) sign(c), from the sum of the logarithms:
  // with |c|^(2/e2) <= w the sum is at most (2/e1 - 1) ln|c| + (e2/e1 - 1)^+ ln 2,
  // so the value never overflows, even where w^(e2/e1 - 1) alone would.
  // (`power` is |c|^(2/e2).)
  double gxy(double c, double power) const
  {
    if(c == 0. || !(w > 0.))
      return 0.;
    if(w >= 1e-100 && power >= min_normal_power) // w^(e2/e1 - 1) <= 1e100 for exponents in (0, 2]
      return std::copysign((P / w) * (power / std::abs(c)), c);
    return std::copysign(std::exp((e2 / e1 - 1.) * std::log(w) + (2. / e2 - 1.) * std::log(std::abs(c))), c);
  }
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_SUPERQUADRIC_RADIAL_PROJECTION_H
