// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_SIGNED_POWER_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_SIGNED_POWER_H

#include <algorithm>
#include <cmath>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// The floor on |c| in the derivative e |c|^(e-1) of a signed power
/// sign(c) |c|^e (signed_pow_derivative()), used by the chart Jacobians:
/// within this distance of a zero of the cosine or sine, the derivative is
/// the one at |c| = floor. For e < 1 the exact derivative is infinite at 0:
/// this is a finite cap (e floor^(e-1): 4.8e3 at e = 0.3, 2.5e4 at e = 0.1,
/// 8.7e3 at e = 0.01). For e > 1 it is 0 at 0, where the chart Jacobian
/// loses rank: this is a small positive slope instead. Either way it is the
/// slope of the map over a chart step of 1e-6, the step of the central
/// differences that the foot-point projection (refine_closest_point()) used
/// before it had analytic chart Jacobians. Mesh start points often lie
/// exactly on such a locus (the chart axes, the equator, a pole), and that
/// projection needs such a slope to step off it: with the exact derivative
/// (0 for e > 1) Gauss-Newton cannot leave the locus, and with a cap at the
/// machine epsilon (2.7e10 at e = 0.3) its first step falls under its stopping
/// threshold. At |c| >= floor, and for e = 1 everywhere, the derivative is exact.
/// The parameter Jacobian, which has finite limits at c = 0, uses them instead
/// (Signed_power).
constexpr double signed_power_derivative_floor = 1e-6;

/// e |c|^(e-1), the derivative of sign(c) |c|^e with respect to c (even in
/// c, never negative), with |c| floored at signed_power_derivative_floor:
/// finite everywhere, and positive.
inline double signed_pow_derivative(double c, double e)
{
  return e * std::pow((std::max)(std::abs(c), signed_power_derivative_floor), e - 1.);
}

/// The superquadric "signed power" sign(c) |c|^e and its derivative with
/// respect to the exponent, sign(c) |c|^e log|c|.
/// At c = 0 both are 0 for every e > 0 (|c|^e log|c| -> 0), so no NaN or
/// infinity ever comes out of a superquadric map or its parameter Jacobian.
struct Signed_power
{
  double value = 0.;
  double d_exponent = 0.;

  Signed_power() = default;
  Signed_power(double c, double e)
  {
    const double a = std::abs(c);
    if(a == 0.)
      return;
    const double p = std::pow(a, e);
    value = (c < 0.) ? -p : p;
    d_exponent = value * std::log(a);
  }
};

/// sign(c) |c|^e, returned, and its derivative with respect to c, written
/// to `d`, as signed_pow_derivative() (|c| floored at
/// signed_power_derivative_floor), for the chart Jacobians: one pow for both
/// away from the zeros.
inline double signed_pow_and_derivative(double c, double e, double& d)
{
  const double a = std::abs(c);
  if(a < signed_power_derivative_floor)
  {
    d = signed_pow_derivative(c, e);
    if(a == 0.)
      return 0.;
    const double p = std::pow(a, e);
    return (c < 0.) ? -p : p;
  }
  const double p = std::pow(a, e);
  d = e * p / a; // e |c|^(e-1) without a second pow
  return (c < 0.) ? -p : p;
}

/// sign(c) |c|^e alone. With e = 0 it is sign(c), which is what the
/// superquadric normal formulas need at e = 2.
inline double signed_pow(double c, double e)
{
  if(c == 0.)
    return 0.;
  const double p = std::pow(std::abs(c), e);
  return (c < 0.) ? -p : p;
}

/// cos t and sin t with exact zeros and ones at multiples of pi/2: the angle
/// is reduced to [-pi/4, pi/4] around the nearest multiple first. Plain
/// std::cos(3 pi / 2) is about 1.8e-16, and a signed power with a small
/// exponent turns that last bit into a visible error (0.026 at e = 0.1).
inline void cos_sin(double t, double& c, double& s)
{
  const double quarter = 0.5 * M_PI;
  const double q = std::nearbyint(t / quarter);
  const double r = t - q * quarter;
  const double cr = std::cos(r), sr = std::sin(r);
  long long k = static_cast<long long>(std::fmod(q, 4.));
  if(k < 0) k += 4;
  switch(k)
  {
    case 0: c = cr; s = sr; break;
    case 1: c = -sr; s = cr; break;
    case 2: c = -cr; s = -sr; break;
    default: c = sr; s = -cr; break;
  }
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_SIGNED_POWER_H
