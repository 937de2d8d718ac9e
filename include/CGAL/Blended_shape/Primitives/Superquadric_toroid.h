// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_SUPERQUADRIC_TOROID_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_SUPERQUADRIC_TOROID_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>
#include <CGAL/Blended_shape/Primitives/internal/signed_power.h>
#include <CGAL/Blended_shape/Primitives/internal/superquadric_parameters.h>

#include <Eigen/Core>

#include <array>
#include <cmath>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapePrimitives

A superquadric toroid (paper eq. 32 with superquadric exponents):

    s(u, v) = ( a1 (a4 + C(u, e1)) C(v, e2),
                a2 (a5 + C(u, e1)) S(v, e2),
                a3 S(u, e1) )

(signed powers `C` and `S` as in Superquadric_ellipsoid), `u` around the
tube, `v` around the axis. One chart, the torus `[0, 2 pi)^2` periodic in both
coordinates, which has no singularity: chart point `(x, y) = (v, u)`, ordered
so that counterclockwise chart triangles give the outward normal.

Parameters `(a1, a2, a3, a4, a5, e1, e2)`: `a1, a2, a3 > 0`, `a4, a5 >= 1`
(at 1 the inner wall reaches the axis: the pinched shape of the hole blend,
sec. 4.2), `ei` in [0.01, 2]. The parameter queries, `parameters()` and
`set_parameters()` are those of the concept, with these names and bounds.

\tparam GeomTraits a CGAL kernel whose `FT` is `double`.

\cgalModels{BlendedShapePrimitive}
*/
template <class GeomTraits>
class Superquadric_toroid : public internal::Checked_parameters<7, internal::toroid_parameters<false>>
{
public:
  typedef GeomTraits Geom_traits;                  ///< the kernel
  typedef typename Geom_traits::FT FT;             ///< the number type of the kernel
  typedef typename Geom_traits::Point_3 Point_3;   ///< the point type
  typedef typename Geom_traits::Vector_3 Vector_3; ///< the vector type (normals)

  /// Indices into the parameter vector.
  enum Parameter_index { A1 = 0, A2, A3, A4, A5, E1, E2 };

  /// \throws std::invalid_argument on out-of-bound parameters.
  explicit Superquadric_toroid(double a1 = 1., double a2 = 1., double a3 = 1.,
                               double a4 = 2., double a5 = 2.,
                               double e1 = 1., double e2 = 1.)
  {
    Parameter_vector q;
    q << a1, a2, a3, a4, a5, e1, e2;
    set_parameters(q);
  }

  /// \name Charts
  /// @{

  /// 1: the torus.
  std::size_t number_of_charts() const { return 1; }
  /// The periodic square `[0, 2 pi)^2`.
  Chart_domain chart_domain(std::size_t) const { return Chart_domain::torus(); }

  /// The single chart is periodic: the same point with both coordinates
  /// reduced to [0, 2 pi). Any other target chart does not exist.
  bool to_chart(const Chart_point& p, std::size_t target, Chart_point& q) const
  {
    if(target != 0)
      return false;
    q = canonical_chart_point(p);
    return true;
  }

  /// `p` with both coordinates reduced to [0, 2 pi).
  Chart_point canonical_chart_point(const Chart_point& p) const
  {
    return Chart_point(0, internal::wrap_angle(p.x), internal::wrap_angle(p.y));
  }
  /// @}

  /// \name Evaluation
  /// @{

  /// The surface point at `p`.
  Point_3 point(const Chart_point& p) const
  {
    Jacobian J;
    return point_and_jacobian(p, J);
  }

  /// The parameter Jacobian ds/dq (3 x 7) at `p`, and the point itself.
  Point_3 point_and_jacobian(const Chart_point& p, Jacobian& J) const
  {
    double cu, su, cv, sv;
    internal::cos_sin(p.y, cu, su);
    internal::cos_sin(p.x, cv, sv);
    const internal::Signed_power Cu(cu, m_q[E1]), Su(su, m_q[E1]);
    const internal::Signed_power Cv(cv, m_q[E2]), Sv(sv, m_q[E2]);
    const double a1 = m_q[A1], a2 = m_q[A2], a3 = m_q[A3];
    const double r1 = m_q[A4] + Cu.value, r2 = m_q[A5] + Cu.value;
    J.setZero();
    J(0, A1) = r1 * Cv.value;
    J(1, A2) = r2 * Sv.value;
    J(2, A3) = Su.value;
    J(0, A4) = a1 * Cv.value;
    J(1, A5) = a2 * Sv.value;
    J(0, E1) = a1 * Cu.d_exponent * Cv.value;
    J(1, E1) = a2 * Cu.d_exponent * Sv.value;
    J(2, E1) = a3 * Su.d_exponent;
    J(0, E2) = a1 * r1 * Cv.d_exponent;
    J(1, E2) = a2 * r2 * Sv.d_exponent;
    return Point_3(a1 * J(0, A1), a2 * J(1, A2), a3 * J(2, A3));
  }

  /// The parameter Jacobian ds/dq at `p`.
  void jacobian(const Chart_point& p, Jacobian& J) const { point_and_jacobian(p, J); }

  /// The surface point at `p` (the same as point()), and the chart Jacobian
  /// `D = [ds/dx, ds/dy] = [ds/dv, ds/du]` there, analytic. Within 1e-6 of a
  /// zero of a cosine or sine that a signed power is applied to, the power's
  /// derivative is taken at 1e-6 (internal::signed_power_derivative_floor: a
  /// finite cap for an exponent below 1, a small non-zero slope above 1), so
  /// `D` is always finite.
  Point_3 point_and_chart_jacobian(const Chart_point& p, Chart_jacobian& D) const
  {
    double cu, su, cv, sv;
    internal::cos_sin(p.y, cu, su);
    internal::cos_sin(p.x, cv, sv);
    const double e1 = m_q[E1], e2 = m_q[E2], a1 = m_q[A1], a2 = m_q[A2], a3 = m_q[A3];
    double dCu, dSu, dCv, dSv; // derivatives of the signed powers with respect to their base
    const double Cu = internal::signed_pow_and_derivative(cu, e1, dCu);
    const double Su = internal::signed_pow_and_derivative(su, e1, dSu);
    const double Cv = internal::signed_pow_and_derivative(cv, e2, dCv);
    const double Sv = internal::signed_pow_and_derivative(sv, e2, dSv);
    const double r1 = m_q[A4] + Cu, r2 = m_q[A5] + Cu;
    // d/dv (around the axis), then d/du (around the tube)
    D << -a1 * r1 * dCv * sv, -a1 * dCu * su * Cv,
          a2 * r2 * dSv * cv, -a2 * dCu * su * Sv,
          0.,                  a3 * dSu * cu;
    return Point_3(a1 * (r1 * Cv), a2 * (r2 * Sv), a3 * Su); // rounded as in point()
  }

  /// Unit outward normal: cross product of the two chart tangents, each
  /// rescaled by a positive factor that removes the |cos|^(e-1) and
  /// |sin|^(e-1) singularities of the signed powers.
  Vector_3 normal(const Chart_point& p) const
  {
    double cu, su, cv, sv;
    internal::cos_sin(p.y, cu, su);
    internal::cos_sin(p.x, cv, sv);
    const double k1 = 2. - m_q[E1], k2 = 2. - m_q[E2];
    const double a1 = m_q[A1], a2 = m_q[A2], a3 = m_q[A3];
    const double cu_e = internal::signed_pow(cu, m_q[E1]);
    const double cv_e = internal::signed_pow(cv, m_q[E2]);
    const double sv_e = internal::signed_pow(sv, m_q[E2]);
    // d/du, rescaled
    const double tu[3] = {-a1 * internal::signed_pow(su, k1) * cv_e,
                          -a2 * internal::signed_pow(su, k1) * sv_e,
                          a3 * internal::signed_pow(cu, k1)};
    double r1 = m_q[A4] + cu_e, r2 = m_q[A5] + cu_e;
    const double rmax = (std::max)(r1, r2);
    // d/dv divided by max(r1, r2) > 0; where the tube radius vanishes
    // (a4 = a5 = 1 on the inner equator) use the limit ratio r1 / r2 = 1.
    if(rmax > 1e-300) { r1 /= rmax; r2 /= rmax; } else { r1 = r2 = 1.; }
    double n[3];
    for(int attempt = 0; attempt < 2; ++attempt)
    {
      const double tv[3] = {-a1 * r1 * internal::signed_pow(sv, k2),
                            a2 * r2 * internal::signed_pow(cv, k2), 0.};
      n[0] = tv[1] * tu[2] - tv[2] * tu[1];
      n[1] = tv[2] * tu[0] - tv[0] * tu[2];
      n[2] = tv[0] * tu[1] - tv[1] * tu[0];
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if(len > 1e-300)
        return Vector_3(n[0] / len, n[1] / len, n[2] / len);
      r1 = r2 = 1.; // one tube radius is 0 here (a4 or a5 = 1): take the limit
    }
    return Vector_3(0., 0., 1.); // not reached for parameters in bounds
  }
  /// @}

};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_SUPERQUADRIC_TOROID_H
