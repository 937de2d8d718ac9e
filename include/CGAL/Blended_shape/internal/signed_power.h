// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_SIGNED_POWER_H
#define CGAL_BLENDED_SHAPE_INTERNAL_SIGNED_POWER_H

#include <cmath>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

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

#endif // CGAL_BLENDED_SHAPE_INTERNAL_SIGNED_POWER_H
