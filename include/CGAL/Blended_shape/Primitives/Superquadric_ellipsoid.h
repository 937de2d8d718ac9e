// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_SUPERQUADRIC_ELLIPSOID_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_SUPERQUADRIC_ELLIPSOID_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>
#include <CGAL/Blended_shape/Primitives/internal/superquadric_parameters.h>
#include <CGAL/Blended_shape/Primitives/internal/superquadric_radial_projection.h>

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

A superquadric ellipsoid: the surface of paper eq. 31 with superquadric
exponents,

    ( (|x/a1|^(2/e2) + |y/a2|^(2/e2))^(e2/e1) + |z/a3|^(2/e1) = 1 ),

the surface the classic map

    s(eta, omega) = ( a1 C(eta, e1) C(omega, e2),
                      a2 C(eta, e1) S(omega, e2),
                      a3 S(eta, e1) )

covers (`C(t, e) = sign(cos t) |cos t|^e`, `S(t, e) = sign(sin t) |sin t|^e`).
Its points are parameterized differently: a chart point gives the unit
direction `v = (cos eta cos omega, cos eta sin omega, sin eta)`, and the
surface point is `s = a (r v)` (componentwise, `a = (a1, a2, a3)`), where
`r v` is the radial projection of `v` onto the unit superquadric (`a = 1`):
`r = H(v)^(-e1/2)` with `H` the left-hand side above at `a = 1`
(internal::Superquadric_radial_projection). For `e1 = e2 = 1` this is the
classic map; for other exponents it is the same surface with its points
spread evenly. The classic map squeezes the sides of a box-like
superquadric into a thin band of latitudes: with `e1 = 0.1`, half of each
side lies within `1e-3` radians of the equator, and the top face within as
little of the pole, so that chart regions (the blending regions of sec. 3.3)
cannot follow a face's rim, foot points creep along the crease, and the chart
Jacobian is infinite at the pole and near the equator. The radial projection
maps a cube's faces to chart regions of comparable size (the top face to
`rho < 0.5` to `0.61`), and its chart Jacobian is finite and of rank 2
everywhere, the pole included.

The charts, without singularity (sec. 5.3, App. B.1):

- chart 0 (upper half): chart point `(x, y)`, `rho = |(x, y)|`,
  latitude `eta = (pi/2)(1 - rho)`, longitude `omega = atan2(y, x)`;
- chart 1 (lower half): `eta = -(pi/2)(1 - rho)`, `omega = atan2(-y, x)`.

Both charts are disks of radius `1 + margin`: each reaches `margin * 90` degrees
of latitude past the equator, so they overlap in a band around it. The pole is
the chart centre, where the map is smooth. Both
charts are oriented so that counterclockwise chart triangles give the outward
normal. The two charts share one parameter vector (the seam is geometrically
exact), and the identification of their points is explicit: to_chart() and
canonical_chart_point().

Parameters: `(a1, a2, a3, e1, e2)`; `ai > 0` and `ei` in [0.01, 2] (past 2
the surface has cusps, where the normal and the chart Jacobian are undefined). The parameter queries, `parameters()`
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
  Angles angles(const Chart_point& p) const { return angles(p, chart_radius(p)); }

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
    // Inside the unit circle by far more than rounding: the hot path (every
    // trial of a foot-point step) without the correctly rounded hypot below.
    if(p.x * p.x + p.y * p.y < 1. - 1e-9)
      return p;
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

  /// The unit direction of `p`: `(cos eta cos omega, cos eta sin omega, sin eta)`.
  Eigen::Vector3d direction(const Chart_point& p) const { return direction(angles(p)); }

  /// The surface point at `p`.
  Point_3 point(const Chart_point& p) const { return surface_point(projection(p)); }

  /// The parameter Jacobian ds/dq (3 x 5) at `p`, and the point itself.
  /// With `s = a (r u)` (componentwise), `ds/da_i = (r u)_i` and
  /// `ds/de_j = s d(ln r)/de_j`.
  Point_3 point_and_jacobian(const Chart_point& p, Jacobian& J) const
  {
    const internal::Superquadric_radial_projection rp = projection(p);
    const Eigen::Vector3d unit = rp.point();
    J.setZero();
    J(0, A1) = unit.x();
    J(1, A2) = unit.y();
    J(2, A3) = unit.z();
    double d1, d2;
    rp.d_log_radius_d_exponents(d1, d2);
    for(int i = 0; i < 3; ++i)
    {
      const double si = m_q[A1 + i] * unit[i];
      J(i, E1) = si * d1;
      J(i, E2) = si * d2;
    }
    return surface_point(rp);
  }

  /// The parameter Jacobian ds/dq at `p`.
  void jacobian(const Chart_point& p, Jacobian& J) const { point_and_jacobian(p, J); }

  /// The surface point at `p` (the same as point()), and the chart Jacobian
  /// `D = [ds/dx, ds/dy]` there, analytic: the scale `a` times the derivative
  /// of the radial projection times that of the direction. It is finite and of
  /// rank 2 everywhere, the pole included, for every exponent in bounds (the
  /// radial projection's derivative only loses continuity on the creases of
  /// exponent 2).
  Point_3 point_and_chart_jacobian(const Chart_point& p, Chart_jacobian& D) const
  {
    const double h = 0.5 * M_PI; // d eta / d rho, up to sign
    const double sigma = (p.chart == 0) ? 1. : -1.; // chart 1 mirrors y and the latitude
    const double rho = chart_radius(p);
    const Angles an = angles(p, rho);
    // The direction is (g x, sigma g y, sigma cos(h rho)) with g = sin(h rho) / rho;
    // k = g'(rho) / rho, from its series near the pole (no cancellation).
    // sin(h rho) = cos eta and cos(h rho) = sigma sin eta: the sines of angles()
    // (cos(h rho) through sin(h (1 - rho)), exact on the equator).
    const double t = h * rho;
    const double sin_t = an.cos_eta, cos_t = sigma * an.sin_eta;
    const double g = (rho > 0.) ? sin_t / rho : h;
    const double k = (rho < 1e-2) ? h * h * h * (-1. / 3. + t * t / 30.) : (t * cos_t - sin_t) / (rho * rho * rho);
    Eigen::Matrix<double, 3, 2> dv;
    dv << g + k * p.x * p.x, k * p.x * p.y,
          sigma * k * p.x * p.y, sigma * (g + k * p.y * p.y),
          -sigma * h * g * p.x, -sigma * h * g * p.y;
    const internal::Superquadric_radial_projection rp(direction(an), m_q[E1], m_q[E2]);
    const Eigen::Vector3d a(m_q[A1], m_q[A2], m_q[A3]);
    D = a.asDiagonal() * (rp.derivative() * dv);
    return surface_point(rp);
  }

  /// Unit outward normal: the gradient of the implicit function
  /// `H(x/a1, y/a2, z/a3)` (defined at the poles too, for any exponent in bounds).
  Vector_3 normal(const Chart_point& p) const
  {
    const Eigen::Vector3d G = projection(p).gradient();
    const Eigen::Vector3d n = Eigen::Vector3d(G.x() / m_q[A1], G.y() / m_q[A2], G.z() / m_q[A3]).normalized();
    return Vector_3(n.x(), n.y(), n.z());
  }
  /// @}

private:
  // |(x, y)|: the chart coordinates are at most 1 + margin < 2 in modulus
  // (no overflow), and the plain square root costs a fraction of std::hypot
  // on the hot path (every evaluation of every foot-point step).
  static double chart_radius(const Chart_point& p) { return std::sqrt(p.x * p.x + p.y * p.y); }

  // angles() at the chart radius `rho` of `p`.
  static Angles angles(const Chart_point& p, double rho)
  {
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

  static Eigen::Vector3d direction(const Angles& a)
  {
    return Eigen::Vector3d(a.cos_eta * a.cos_omega, a.cos_eta * a.sin_omega, a.sin_eta);
  }

  internal::Superquadric_radial_projection projection(const Chart_point& p) const
  {
    return internal::Superquadric_radial_projection(direction(p), m_q[E1], m_q[E2]);
  }

  Point_3 surface_point(const internal::Superquadric_radial_projection& rp) const
  {
    const Eigen::Vector3d unit = rp.point();
    return Point_3(m_q[A1] * unit.x(), m_q[A2] * unit.y(), m_q[A3] * unit.z());
  }

  double m_margin;
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_SUPERQUADRIC_ELLIPSOID_H
