// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_SUPERQUADRIC_ELLIPSOID_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_SUPERQUADRIC_ELLIPSOID_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>
#include <CGAL/Blended_shape/Primitives/internal/signed_power.h>
#include <CGAL/Blended_shape/Primitives/internal/superquadric_parameters.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapePrimitives

A superquadric ellipsoid (paper eq. 31 with superquadric exponents):

    s(eta, omega) = ( a1 C(eta, e1) C(omega, e2),
                      a2 C(eta, e1) S(omega, e2),
                      a3 S(eta, e1) )

with the signed powers `C(t, e) = sign(cos t) |cos t|^e` and
`S(t, e) = sign(sin t) |sin t|^e`, over two disk charts without singularity
(sec. 5.3, App. B.1):

- chart 0 (upper half): chart point `(x, y)`, `rho = |(x, y)|`,
  latitude `eta = (pi/2)(1 - rho)`, longitude `omega = atan2(y, x)`;
- chart 1 (lower half): `eta = -(pi/2)(1 - rho)`, `omega = atan2(-y, x)`.

Both charts are disks of radius `1 + margin`: each reaches `margin * 90` degrees
of latitude past the equator, so they overlap in a band around it. The pole is
the chart centre, where the azimuthal map is smooth (for `e1 = 1`). Both
charts are oriented so that counterclockwise chart triangles give the outward
normal. The two charts share one parameter vector (the seam is geometrically
exact), and the identification of their points is explicit: to_chart() and
canonical_chart_point().

Parameters: `(a1, a2, a3, e1, e2)`; `ai > 0` and `ei` in [0.01, 2] (the
closed-form normal needs `e <= 2`). The parameter queries, `parameters()`
and `set_parameters()` are those of the concept, with these names and bounds.

\tparam GeomTraits a CGAL kernel whose `FT` is `double`.

\cgalModels{BlendedShapePrimitive}
*/
template <class GeomTraits>
class Superquadric_ellipsoid : public internal::Checked_parameters<5, internal::superquadric_ellipsoid_parameters>
{
public:
  typedef GeomTraits Geom_traits;                  ///< the kernel
  typedef typename Geom_traits::FT FT;             ///< the number type of the kernel
  typedef typename Geom_traits::Point_3 Point_3;   ///< the point type
  typedef typename Geom_traits::Vector_3 Vector_3; ///< the vector type (normals)

  /// Indices into the parameter vector.
  enum Parameter_index { A1 = 0, A2, A3, E1, E2 };

  /// The default `chart_margin` of the constructor.
  static constexpr double default_chart_margin = 0.2;

  /// An ellipsoid with the given parameters; `chart_margin` in (0, 1) is how
  /// far past the equator each chart reaches, in units of the chart radius.
  /// \throws std::invalid_argument on out-of-bound parameters or margin.
  explicit Superquadric_ellipsoid(double a1 = 1., double a2 = 1., double a3 = 1.,
                                  double e1 = 1., double e2 = 1.,
                                  double chart_margin = default_chart_margin)
    : m_margin(chart_margin)
  {
    if(!(chart_margin > 0. && chart_margin < 1.))
    {
      std::ostringstream msg;
      msg << "Superquadric_ellipsoid: chart margin " << chart_margin
          << " is not in (0, 1); use a small positive value such as 0.2";
      throw std::invalid_argument(msg.str());
    }
    Parameter_vector q;
    q << a1, a2, a3, e1, e2;
    set_parameters(q);
  }

  /// \name Charts
  /// @{

  /// 2: the upper (0) and the lower (1) half.
  std::size_t number_of_charts() const { return 2; }
  /// How far past the equator each chart reaches, in units of the chart radius.
  double chart_margin() const { return m_margin; }
  /// Both charts: the disk of radius `1 + chart_margin()`.
  Chart_domain chart_domain(std::size_t) const { return Chart_domain::disk(1. + m_margin); }

  /// Latitude and longitude of a chart point, as cosines and sines computed
  /// without going through the angles (exact zeros at the pole and on the axes).
  struct Angles
  {
    /// The cosine of the latitude `eta`.
    double cos_eta, sin_eta, cos_omega, sin_omega;
    /// \var sin_eta
    /// The sine of the latitude `eta`.
    /// \var cos_omega
    /// The cosine of the longitude `omega`.
    /// \var sin_omega
    /// The sine of the longitude `omega`.
  };

  /// The latitude and longitude of `p` (longitude 0 at the pole).
  Angles angles(const Chart_point& p) const
  {
    const double rho = std::hypot(p.x, p.y);
    const double half_pi = 0.5 * M_PI;
    Angles a;
    // eta = +-(pi/2)(1 - rho): cos eta = sin(pi rho / 2), sin eta = +-sin((pi/2)(1 - rho)).
    a.cos_eta = std::sin(half_pi * rho);
    const double s = std::sin(half_pi * (1. - rho));
    const double ys = (p.chart == 0) ? p.y : -p.y;
    a.sin_eta = (p.chart == 0) ? s : -s;
    if(rho > 0.)
    {
      a.cos_omega = p.x / rho;
      a.sin_omega = ys / rho;
    }
    else
    {
      a.cos_omega = 1.;
      a.sin_omega = 0.;
    }
    return a;
  }

  /// The same surface point expressed in chart `target`, if that chart
  /// contains it. The two charts overlap where `rho` is in [1 - m, 1 + m]
  /// (m the chart margin); there the other chart's radius is `2 - rho` and the
  /// longitude is kept.
  bool to_chart(const Chart_point& p, std::size_t target, Chart_point& q) const
  {
    if(target == p.chart)
    {
      q = p;
      return true;
    }
    const double rho = std::hypot(p.x, p.y);
    const double other_rho = 2. - rho;
    // Chart-mesh vertices on the domain's rim have rho = 1 + margin up to
    // rounding (hypot of cos/sin products): accept them.
    const double limit = 1. + m_margin + 1e-12;
    if(rho > limit || other_rho > limit)
      return false;
    const double f = other_rho / rho; // rho >= 1 - m > 0 here
    q = Chart_point(target, f * p.x, -f * p.y);
    return true;
  }

  /// The representative of a surface point in the chart of its own
  /// hemisphere (chart 0 for the equator itself).
  /// \throws std::invalid_argument if `p` is outside its chart domain
  Chart_point canonical_chart_point(const Chart_point& p) const
  {
    const double rho = std::hypot(p.x, p.y);
    if(rho < 1. || (rho == 1. && p.chart == 0))
      return p;
    Chart_point q;
    if(!to_chart(p, 1 - p.chart, q))
      throw std::invalid_argument("Superquadric_ellipsoid::canonical_chart_point: the point (" + std::to_string(p.x) +
                                  ", " + std::to_string(p.y) + ") is outside its chart's domain (radius 1 + chart margin)");
    return q;
  }
  /// @}

  /// \name Evaluation
  /// @{

  /// The surface point at `p`.
  Point_3 point(const Chart_point& p) const
  {
    const Angles a = angles(p);
    const double ce = internal::signed_pow(a.cos_eta, m_q[E1]);
    return Point_3(m_q[A1] * ce * internal::signed_pow(a.cos_omega, m_q[E2]),
                   m_q[A2] * ce * internal::signed_pow(a.sin_omega, m_q[E2]),
                   m_q[A3] * internal::signed_pow(a.sin_eta, m_q[E1]));
  }

  /// The parameter Jacobian ds/dq (3 x 5) at `p`, and the point itself.
  Point_3 point_and_jacobian(const Chart_point& p, Jacobian& J) const
  {
    const Angles a = angles(p);
    const internal::Signed_power ce(a.cos_eta, m_q[E1]), se(a.sin_eta, m_q[E1]);
    const internal::Signed_power cw(a.cos_omega, m_q[E2]), sw(a.sin_omega, m_q[E2]);
    const double a1 = m_q[A1], a2 = m_q[A2], a3 = m_q[A3];
    J.setZero();
    J(0, A1) = ce.value * cw.value;
    J(1, A2) = ce.value * sw.value;
    J(2, A3) = se.value;
    J(0, E1) = a1 * ce.d_exponent * cw.value;
    J(1, E1) = a2 * ce.d_exponent * sw.value;
    J(2, E1) = a3 * se.d_exponent;
    J(0, E2) = a1 * ce.value * cw.d_exponent;
    J(1, E2) = a2 * ce.value * sw.d_exponent;
    return Point_3(a1 * J(0, A1), a2 * J(1, A2), a3 * J(2, A3));
  }

  /// The parameter Jacobian ds/dq at `p`.
  void jacobian(const Chart_point& p, Jacobian& J) const { point_and_jacobian(p, J); }

  /// The surface point at `p` (the same as point()), and the chart Jacobian
  /// `D = [ds/dx, ds/dy]` there, analytic. Within 1e-6 of a zero of a cosine
  /// or sine that a signed power is applied to, the power's derivative is
  /// taken at 1e-6 (internal::signed_power_derivative_floor: a finite cap for
  /// an exponent below 1, a small non-zero slope above 1), so `D` is always
  /// finite. At the pole (`rho = 0`), where the map is differentiable only for
  /// `e1 > 1` or `e1 = e2 = 1`, the columns are the partial derivatives along
  /// the chart axes (`+x` and `+y`), with that same floor.
  Point_3 point_and_chart_jacobian(const Chart_point& p, Chart_jacobian& D) const
  {
    const double h = 0.5 * M_PI; // d eta / d rho, up to sign
    const double sigma = (p.chart == 0) ? 1. : -1.; // chart 1 mirrors y and the latitude
    const Angles a = angles(p);
    const double rho = std::hypot(p.x, p.y);
    const double e1 = m_q[E1], e2 = m_q[E2], a1 = m_q[A1], a2 = m_q[A2], a3 = m_q[A3];
    double dA, dB, dC, dT;
    const double A = internal::signed_pow_and_derivative(a.cos_eta, e1, dA);
    const double B = internal::signed_pow_and_derivative(a.cos_omega, e2, dB);
    const double C = internal::signed_pow_and_derivative(a.sin_omega, e2, dC);
    const double T = internal::signed_pow_and_derivative(a.sin_eta, e1, dT);
    // g = A / rho, the factor of the longitude terms, from the smooth ratio
    // sin(pi rho / 2) / rho (pi/2 at the pole) so that it stays finite at
    // the pole: A / rho = |cos eta|^(e1 - 1) (cos eta / rho).
    const double g = (dA / e1) * (rho > 0. ? a.cos_eta / rho : h);
    if(rho == 0.)
    {
      // Partial derivatives along +x (longitude 0) and +y: the latitude
      // terms vanish (d sin(eta)/d rho = 0 at the pole) and the longitude
      // is constant along each axis.
      D << a1 * g, 0.,
           0., sigma * a2 * g,
           0., 0.;
    }
    else
    {
      // rho, omega as functions of (x, y): d rho = (ux, uy), d omega = sigma (-uy, ux) / rho,
      // with (ux, uy) = (x, y) / rho; cos omega = ux, sin omega = sigma uy.
      const double ux = a.cos_omega, uy = sigma * a.sin_omega;
      // d cos(eta) / d rho = (pi/2) cos(pi rho / 2), d sin(eta) / d rho = -sigma (pi/2) sin(pi rho / 2)
      const double dA_drho = dA * h * a.sin_eta * sigma;
      const double dT_drho = -sigma * dT * h * a.cos_eta;
      D(0, 0) = a1 * (dA_drho * ux * B + g * dB * uy * uy);
      D(0, 1) = a1 * (dA_drho * uy * B - g * dB * ux * uy);
      D(1, 0) = a2 * (dA_drho * ux * C - sigma * g * dC * ux * uy);
      D(1, 1) = a2 * (dA_drho * uy * C + sigma * g * dC * ux * ux);
      D(2, 0) = a3 * dT_drho * ux;
      D(2, 1) = a3 * dT_drho * uy;
    }
    return Point_3(a1 * A * B, a2 * A * C, a3 * T); // rounded as in point()
  }

  /// Unit outward normal, from the closed form of the superquadric's
  /// implicit gradient (defined at the poles too, for any exponent in bounds).
  Vector_3 normal(const Chart_point& p) const
  {
    const Angles a = angles(p);
    const double k1 = 2. - m_q[E1], k2 = 2. - m_q[E2];
    const double ce = internal::signed_pow(a.cos_eta, k1);
    const double nx = ce * internal::signed_pow(a.cos_omega, k2) / m_q[A1];
    const double ny = ce * internal::signed_pow(a.sin_omega, k2) / m_q[A2];
    const double nz = internal::signed_pow(a.sin_eta, k1) / m_q[A3];
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    return Vector_3(nx / len, ny / len, nz / len);
  }
  /// @}

private:
  double m_margin;
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_SUPERQUADRIC_ELLIPSOID_H
