// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_ELLIPSE_BLENDING_REGION_H
#define CGAL_BLENDED_SHAPE_BLENDING_ELLIPSE_BLENDING_REGION_H

#include <CGAL/Blended_shape/Blending/Blending_region.h>
#include <CGAL/Blended_shape/Blending/Blending_function.h>
#include <CGAL/Blended_shape/Blending/internal/Bezier_loop.h>
#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>

#include <Eigen/Core>
#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeBlending

An ellipse-shaped blending region (App. A.3, eq. 29, Fig. 29): seven
parameters `q_b = (e_u, e_v, e_1, e_2, e_theta, w, h)`, the ellipse
`E(t) = (e_u, e_v) + R(e_theta) (e_1 cos t, e_2 sin t)` in the chart,
and the blending function's `w` and `h`. The underlying
`Blending_region` (eq. 28) is computed from them for `N >= 4`
segments (default 8):

- `k_i = E(theta_i)`, on the ellipse, at the strip angles `theta_i`
  (uniform by default);
- `k_{i(i+1)}` is the intersection of the ellipse's tangents at
  `k_i` and `k_{i+1}`: with `Delta_i = theta_{i+1} - theta_i`,
  `k_{i(i+1)} = (e_u, e_v) + R(e_theta) diag(e_1, e_2) (cos m_i, sin m_i)/cos(Delta_i/2)`, `m_i = theta_i + Delta_i/2`
  (the circle's construction mapped by the affine map of the ellipse);
- `mu_i = tan(Delta_{i-1}/2)/(tan(Delta_{i-1}/2) + tan(Delta_i/2))`
  (`1/2` for uniform angles), so that eq. 20 reproduces
  `k_i = E(theta_i)` exactly. `mu_i` does not depend on `q_b`.

Each segment is tangent to the ellipse at both ends; for `N = 8` the
loop stays within about 0.3% of `max(e_1, e_2)` of the ellipse
(0.31% of the radius for a circle). The curve runs counterclockwise in the
chart. `r` (the strip half-width), `N`, the `theta_i`, the kind
and the retained side are constants.

The derivatives are the chain rule of A.4 (eq. 30) through the control
points: `∂d/∂q_b = sum_j ∂d/∂k_{j(j+1)} ∂k_{j(j+1)}/∂q_b` with the implicit differentiation of
eq. 24 done by `Blending_region::local_coordinate_gradient()`.
*/
class Ellipse_blending_region
{
public:
  typedef Eigen::Vector2d Vector_2;              ///< a chart point or vector
  static constexpr int number_of_parameters = 7; ///< the parameters of eq. 29
  typedef Eigen::Matrix<double, number_of_parameters, 1> Parameter_vector; ///< the seven parameters
  /// `∂k_{j(j+1)}/∂(e_u, e_v, e_1, e_2, e_theta)`
  typedef Eigen::Matrix<double, 2, 5> Control_point_jacobian;

  /// Indices into the parameter vector (eq. 29).
  enum Parameter_index { E_U = 0, E_V, E_1, E_2, E_THETA, W, H };

  /*!
  \param q the seven parameters, see `Parameter_index`
  \param half_width `r`, the strip half-width in chart units
  \param segments `N >= 4`
  \param kind annulus or disk region
  \param retained the side of the ellipse the base shape keeps
  \param theta the `theta_i` (empty: uniform); consecutive gaps at most `pi/2`
  \throws std::invalid_argument on invalid values (including a strip that folds, see `Blending_region`)
  */
  Ellipse_blending_region(const Parameter_vector& q, double half_width, std::size_t segments = 8,
                          Blending_region_kind kind = Blending_region_kind::Disk,
                          Retained_side retained = Retained_side::Outside,
                          std::vector<double> theta = std::vector<double>())
    : m_q(q), m_r(half_width), m_kind(kind), m_retained(retained), m_theta(std::move(theta))
  {
    if(segments < 4)
      throw std::invalid_argument("Ellipse_blending_region: need at least 4 segments, got " +
                                  std::to_string(segments));
    if(m_theta.empty())
      m_theta = Blending_region::uniform_theta(segments);
    if(m_theta.size() != segments)
      throw std::invalid_argument("Ellipse_blending_region: need one theta per segment");
    for(std::size_t i = 0; i < segments; ++i)
    {
      const double gap = (i + 1 < segments ? m_theta[i + 1] : m_theta[0] + 2. * M_PI) - m_theta[i];
      if(!(gap > 0. && gap <= 0.5 * M_PI + 1e-12))
        throw std::invalid_argument("Ellipse_blending_region: consecutive theta_i must increase by at most pi/2");
    }
    m_region = build(m_q);
  }

  /// Convenience: parameters one by one.
  static Parameter_vector make_parameters(double e_u, double e_v, double e_1, double e_2, double e_theta,
                                          double w = 1., double h = 0.)
  {
    Parameter_vector q;
    q << e_u, e_v, e_1, e_2, e_theta, w, h;
    return q;
  }

  /// \name Parameters
  /// @{

  /// Name, bounds, default value and kind of parameter `i`.
  static const Parameter_info& parameter_info(int i) { return table()[std::size_t(i)]; }
  /// The name of parameter `i`.
  static const char* parameter_name(int i) { return parameter_info(i).name; }
  /// The smallest allowed value of parameter `i`.
  static double parameter_lower_bound(int i) { return parameter_info(i).lower_bound; }
  /// The largest allowed value of parameter `i`.
  static double parameter_upper_bound(int i) { return parameter_info(i).upper_bound; }

  /// The current parameters.
  const Parameter_vector& parameters() const { return m_q; }

  /// \throws std::invalid_argument on invalid values; the region is then unchanged.
  void set_parameters(const Parameter_vector& q)
  {
    Blending_region r = build(q);
    m_q = q;
    m_region = std::move(r);
  }

  /// The strip half-width `r`, in chart units.
  double half_width() const { return m_r; }
  /// `N`, the number of Bézier segments.
  std::size_t number_of_segments() const { return m_theta.size(); }
  /// Annulus (cut and glue) or disk (gradual blending).
  Blending_region_kind kind() const { return m_kind; }
  /// Which side of the ellipse the base shape keeps.
  Retained_side retained_side() const { return m_retained; }
  /// The chart the region lives in (bookkeeping only).
  std::size_t chart() const { return m_chart; }
  /// Sets the chart the region lives in.
  void set_chart(std::size_t c)
  {
    m_chart = c;
    m_region->set_chart(c);
  }
  /// @}

  /// The Bézier loop and strip built from the parameters (eq. 28 form).
  const Blending_region& region() const { return *m_region; }

  /// `E(t)`, the point of the ellipse at parametric angle `t`.
  Vector_2 ellipse_point(double t) const
  {
    return Vector_2(m_q[E_U], m_q[E_V]) + rotation(m_q[E_THETA]) * Vector_2(m_q[E_1] * std::cos(t), m_q[E_2] * std::sin(t));
  }

  /// `∂k_{j(j+1)}/∂(e_u, e_v, e_1, e_2, e_theta)`.
  Control_point_jacobian control_point_jacobian(std::size_t j) const
  {
    const Vector_2 v = local_control_point(j);
    const Eigen::Matrix2d R = rotation(m_q[E_THETA]);
    const Vector_2 Dv(m_q[E_1] * v.x(), m_q[E_2] * v.y());
    Control_point_jacobian J;
    J.col(0) = Vector_2(1., 0.);
    J.col(1) = Vector_2(0., 1.);
    J.col(2) = R.col(0) * v.x();
    J.col(3) = R.col(1) * v.y();
    J.col(4) = Vector_2(-(R * Dv).y(), (R * Dv).x()); // dR/dtheta = J R
    return J;
  }

  /// The centre `(e_u, e_v)` of the ellipse.
  Vector_2 center() const { return Vector_2(m_q[E_U], m_q[E_V]); }

  /// `C(d, theta)` (eq. 24, 27) and its Jacobian `[∂C/∂d, ∂C/∂theta]`.
  Vector_2 strip_point(double d, double theta, Eigen::Matrix2d* jacobian = nullptr) const
  {
    double gamma;
    const std::size_t i = m_region->segment_of_theta(theta, gamma);
    if(jacobian)
    {
      *jacobian = m_region->strip_jacobian(i, d, gamma);
      jacobian->col(1) /= segment_theta_span(i);
    }
    return m_region->strip_point(i, d, gamma);
  }

  /// `∂C_i(d,gamma)/∂(e_u, e_v, e_1, e_2, e_theta)` at fixed `(d, gamma)`.
  Eigen::Matrix<double, 2, 5> strip_point_shape_derivative(std::size_t i, double d, double gamma) const
  {
    return chain_to_shape(i, m_region->strip_point_local_derivative(i, d, gamma));
  }

  /// \name Disk coordinates (A.1: a disk-shaped coordinate system)
  /// The inside of the strip boundary curve `C(d_b, .)` is covered by the
  /// curves of constant `theta` from the centre `c`:
  ///
  ///     u(t, theta) = c + t P + b(t) (E - P),   t in [0, 1),
  ///
  /// with `P = C(d_b, theta) - c`, `E = -d_b k ∂C/∂d (d_b, theta)` and the
  /// bend `b(t) = t^4 (t - 1)`. At `t = 1` the curve reaches `C(d_b, theta)`
  /// with velocity `E`: the strip's own transversal direction, scaled by the
  /// blend's *core stretch* `k`. With `d_b = -1` this parameterizes the
  /// discarded interior of a disk region of the base shape; with `d_b = +1`
  /// the retained interior of the matching region of the added shape, and
  /// the correspondence beta extends from the strip (eq. 16) to the whole
  /// disk (Fig. 7) by equal `(t, theta)`. Because both sides end with
  /// velocities that beta's strip part maps onto each other (`∂C_1/∂d` to
  /// `-∂C_2/∂d`, the same `k`), beta is C1 across the disk boundary, and so
  /// is the blended surface for every `h`. Near the centre `b` is
  /// negligible (the straight rays `c + t P`). The boundary curve must be
  /// star-shaped from the centre (true for ellipses whose strip half-width is
  /// below the smaller radius of curvature), and `k` must keep the bend mild:
  /// `k |∂C/∂d| / |P|` below about 5 (see `Blend::default_core_stretch()`).
  /// @{

  /// The straight-ray coordinates of `u`: `u = c + t (C(d_b, theta) - c)`, if
  /// `u` lies inside `C(d_b, .)` (`t < 1`); the starting guess of core_coordinates().
  std::optional<Core_coordinates> ray_coordinates(const Vector_2& u, double d_b) const
  {
    const Vector_2 c = center(), v = u - c;
    const double vn = v.norm();
    const std::size_t n = number_of_segments();
    if(vn == 0.)
    {
      Core_coordinates k;
      k.theta = m_theta[0];
      return k;
    }
    std::optional<Core_coordinates> best;
    for(std::size_t i = 0; i < n; ++i)
    {
      // cross(C_i(d_b, g) - c, v) is quadratic in g: Bernstein coefficients f0, f1, f2.
      const Vector_2 P0 = m_region->strip_point(i, d_b, 0.) - c, P2 = m_region->strip_point(i, d_b, 1.) - c;
      const Vector_2 Pm = m_region->strip_point(i, d_b, 0.5) - c;
      const Vector_2 P1 = 2. * Pm - 0.5 * (P0 + P2); // middle control point of the quadratic
      const double f0 = internal::cross(P0, v), f1 = internal::cross(P1, v), f2 = internal::cross(P2, v);
      const double a = f0 - 2. * f1 + f2, b = 2. * (f1 - f0), cc = f0;
      double roots[2];
      int count = 0;
      if(std::abs(a) <= 1e-14 * (std::abs(b) + std::abs(cc)))
      {
        if(b != 0.)
          roots[count++] = -cc / b;
      }
      else
      {
        const double disc = b * b - 4. * a * cc;
        if(disc >= 0.)
        {
          const double sq = std::sqrt(disc), qq = -0.5 * (b + (b >= 0. ? sq : -sq));
          roots[count++] = qq / a;
          if(qq != 0.)
            roots[count++] = cc / qq;
        }
      }
      for(int k = 0; k < count; ++k)
      {
        const double g = roots[k];
        if(!(g >= -1e-12 && g <= 1. + 1e-12))
          continue;
        const double gc = (std::min)(1., (std::max)(0., g));
        const Vector_2 P = m_region->strip_point(i, d_b, gc) - c;
        if(!(P.dot(v) > 0.))
          continue;
        Core_coordinates kc;
        kc.segment = i;
        kc.gamma = gc;
        kc.t = vn / P.norm();
        kc.theta = internal::wrap_angle(theta_at(i) + gc * segment_theta_span(i));
        if(!best || std::abs(kc.gamma - 0.5) < std::abs(best->gamma - 0.5))
          best = kc;
      }
    }
    if(best && best->t < 1.)
      return best;
    return std::nullopt;
  }

  /// The bend `b(t) = t^4 (t - 1)` of the disk coordinates and its derivative.
  static double core_bend(double t) { return t * t * t * t * (t - 1.); }
  /// `b'(t) = t^3 (5 t - 4)`.
  static double core_bend_derivative(double t) { return t * t * t * (5. * t - 4.); }

  /// The point with disk coordinates `(t, theta)` (see above) and its
  /// Jacobian `[∂/∂t, ∂/∂theta]`; `k` is the core stretch.
  Vector_2 core_point(double t, double theta, double d_b, double k, Eigen::Matrix2d* jacobian = nullptr) const
  {
    double gamma;
    const std::size_t i = m_region->segment_of_theta(theta, gamma);
    Eigen::Matrix2d J;
    const Vector_2 p = core_point_in_segment(i, gamma, t, d_b, k, &J);
    if(jacobian)
    {
      *jacobian = J;
      jacobian->col(1) /= segment_theta_span(i);
    }
    return p;
  }

  /// The disk coordinates of `u`, if `u` lies inside `C(d_b, .)` (`t < 1`):
  /// the straight-ray coordinates, refined by Newton's method on the bent
  /// curves; `k` is the core stretch.
  std::optional<Core_coordinates> core_coordinates(const Vector_2& u, double d_b, double k) const
  {
    std::optional<Core_coordinates> c = ray_coordinates(u, d_b);
    if(!c || c->t == 0.)
      return c;
    const double scale = (std::max)(1., u.norm());
    for(int it = 0; it < 40; ++it)
    {
      Eigen::Matrix2d J;
      const Vector_2 r = core_point_in_segment(c->segment, c->gamma, c->t, d_b, k, &J) - u;
      if(r.norm() <= 4e-16 * scale)
        break;
      const Vector_2 step = J.fullPivLu().solve(-r);
      if(!step.allFinite())
        break;
      c->t += step.x();
      double theta = theta_at(c->segment) + (c->gamma + step.y()) * segment_theta_span(c->segment);
      theta = internal::wrap_angle(theta);
      c->segment = m_region->segment_of_theta(theta, c->gamma);
      c->theta = theta;
    }
    return c;
  }

  /// The gradients of `t` (row 0) and `theta` (row 1) with respect to the
  /// seven parameters at the fixed chart point `u` with disk coordinates `c`
  /// (implicit differentiation of `u(t, theta) = u`, the stretch `k` fixed).
  Eigen::Matrix<double, 2, number_of_parameters> core_gradient(const Core_coordinates& c, double d_b, double k) const
  {
    const std::size_t i = c.segment;
    Eigen::Matrix2d A;
    core_point_in_segment(i, c.gamma, c.t, d_b, k, &A);
    // u = c (1 - t + b) + C(d_b) (t - b) - b d_b k (C(1) - C(0)), all at fixed (segment, gamma).
    const double b = core_bend(c.t);
    Eigen::Matrix<double, 2, 5> dU = (c.t - b) * strip_point_shape_derivative(i, d_b, c.gamma) -
                                     (b * d_b * k) * (strip_point_shape_derivative(i, 1., c.gamma) -
                                                      strip_point_shape_derivative(i, 0., c.gamma));
    dU.leftCols<2>() += (1. - c.t + b) * Eigen::Matrix2d::Identity();
    Eigen::Matrix<double, 2, number_of_parameters> g = Eigen::Matrix<double, 2, number_of_parameters>::Zero();
    g.leftCols<5>() = -A.inverse() * dU;
    g.row(1) *= segment_theta_span(i);
    return g;
  }
  /// @}

private:
  // u(t, gamma) in segment i and [∂u/∂t, ∂u/∂gamma].
  Vector_2 core_point_in_segment(std::size_t i, double gamma, double t, double d_b, double k,
                                 Eigen::Matrix2d* J) const
  {
    const Vector_2 c = center(), C = m_region->strip_point(i, d_b, gamma);
    const Eigen::Matrix2d Jc = m_region->strip_jacobian(i, d_b, gamma);
    // C is affine in d (eq. 24): ∂C/∂d = N(gamma) and ∂N/∂gamma = d_b (∂C/∂gamma(d_b) - ∂C/∂gamma(0)).
    const Vector_2 N = Jc.col(0), P = C - c, E = (-d_b * k) * N;
    const double b = core_bend(t);
    if(J)
    {
      const Vector_2 Ng = d_b * (Jc.col(1) - m_region->strip_jacobian(i, 0., gamma).col(1));
      J->col(0) = P + core_bend_derivative(t) * (E - P);
      J->col(1) = t * Jc.col(1) + b * ((-d_b * k) * Ng - Jc.col(1));
    }
    return c + t * P + b * (E - P);
  }

public:
  /// \name Evaluation (forwarded to region())
  /// @{

  /// The strip coordinates of `u`, if it lies in the strip.
  std::optional<Strip_coordinates> strip_coordinates(const Vector_2& u) const { return m_region->strip_coordinates(u); }
  /// See Blending_region::extended_strip_coordinates().
  std::optional<Strip_coordinates> extended_strip_coordinates(const Vector_2& u, double max_abs_d) const
  {
    return m_region->extended_strip_coordinates(u, max_abs_d);
  }
  /// `∂(d, theta)/∂u` at the strip point `c` (Blending_region::strip_coordinate_derivatives()).
  Eigen::Matrix2d strip_coordinate_derivatives(const Strip_coordinates& c) const
  {
    return m_region->strip_coordinate_derivatives(c);
  }
  /// Which side of the region `u` is on, with its strip coordinates in the strip.
  Region_location locate(const Vector_2& u) const { return m_region->locate(u); }
  /// The blending function at chart point `u`.
  double alpha(const Vector_2& u) const { return m_region->alpha(u); }
  /// @}

  /// \name Derivatives with respect to q_b (eq. 30)
  /// @{

  /// Strip coordinates at `u` and the gradients of `d` and `theta`
  /// with respect to the seven parameters (the `w`, `h` entries are 0);
  /// nothing outside the strip. `theta` is only `C^0` across segment junctions.
  std::optional<Strip_coordinates_and_gradient<Parameter_vector>>
  strip_coordinates_and_gradient(const Vector_2& u) const
  {
    const std::optional<Strip_coordinates> c = m_region->strip_coordinates(u);
    if(!c)
      return std::nullopt;
    return strip_coordinates_and_gradient(*c);
  }

  /// The same from strip coordinates already found (e.g. by locate()), without locating again.
  Strip_coordinates_and_gradient<Parameter_vector> strip_coordinates_and_gradient(const Strip_coordinates& c) const
  {
    Strip_coordinates_and_gradient<Parameter_vector> r;
    r.coordinates = c;
    const Eigen::Matrix<double, 2, 5> G = shape_gradient(c);
    const double dtheta = segment_theta_span(c.segment);
    r.d_gradient.setZero();
    r.theta_gradient.setZero();
    r.d_gradient.head<5>() = G.row(0).transpose();
    r.theta_gradient.head<5>() = dtheta * G.row(1).transpose();
    return r;
  }

  /// `alpha(u)` and `∂alpha/∂q_b` (7 entries), eq. 30:
  /// `∂alpha/∂alpha_0 ∂alpha_0/∂d ∂d/∂q`
  /// for the shape parameters, and the direct `w`, `h` terms (0 for
  /// `h` on an annulus).
  Alpha_and_gradient<Parameter_vector> alpha_and_gradient(const Vector_2& u) const
  {
    return alpha_and_gradient(m_region->locate(u));
  }

  /// The same at a point already located (locate()), without locating it again.
  Alpha_and_gradient<Parameter_vector> alpha_and_gradient(const Region_location& location) const
  {
    Alpha_and_gradient<Parameter_vector> r;
    r.location = location;
    r.alpha = m_region->alpha(r.location);
    r.gradient.setZero();
    const Blending_function::Derivatives D = m_region->blending_derivatives(r.location);
    if(r.location.side == Region_side::Strip && D.d_d != 0.)
      r.gradient.head<5>() = D.d_d * shape_gradient(r.location.coordinates).row(0).transpose();
    r.gradient[W] = D.d_w;
    r.gradient[H] = D.d_h;
    return r;
  }
  /// @}

private:
  static Eigen::Matrix2d rotation(double t)
  {
    Eigen::Matrix2d R;
    R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
    return R;
  }

  double theta_at(std::size_t i) const
  {
    const std::size_t n = m_theta.size();
    return i < n ? m_theta[i] : m_theta[i - n] + 2. * M_PI;
  }
  double segment_theta_span(std::size_t i) const { return theta_at(i + 1) - theta_at(i); }

  // (cos m, sin m) / cos(Delta / 2): the tangent intersection on the unit circle.
  Vector_2 local_control_point(std::size_t j) const
  {
    const double delta = segment_theta_span(j), m = theta_at(j) + 0.5 * delta;
    return Vector_2(std::cos(m), std::sin(m)) / std::cos(0.5 * delta);
  }

  // Rows d, gamma; columns e_u, e_v, e_1, e_2, e_theta.
  Eigen::Matrix<double, 2, 5> shape_gradient(const Strip_coordinates& c) const
  {
    return chain_to_shape(c.segment, m_region->local_coordinate_gradient(c.segment, c.d, c.gamma));
  }

  // A derivative with respect to the local data of segment i, chained to the
  // ellipse parameters (mu_i does not depend on them: columns 6, 7 drop out).
  Eigen::Matrix<double, 2, 5> chain_to_shape(std::size_t i, const Blending_region::Local_gradient& L) const
  {
    const std::size_t n = m_theta.size();
    return L.block<2, 2>(0, 0) * control_point_jacobian((i + n - 1) % n) +
           L.block<2, 2>(0, 2) * control_point_jacobian(i) + L.block<2, 2>(0, 4) * control_point_jacobian((i + 1) % n);
  }

  Blending_region build(const Parameter_vector& q) const
  {
    internal::validate_parameters<number_of_parameters>("Ellipse_blending_region", table(), q);
    if(!(q[E_1] > 0. && q[E_2] > 0.))
      throw std::invalid_argument("Ellipse_blending_region: the axis lengths e1, e2 must be positive");
    const std::size_t n = m_theta.size();
    const Eigen::Matrix2d R = rotation(q[E_THETA]);
    const Vector_2 center(q[E_U], q[E_V]);
    std::vector<Vector_2> control(n);
    std::vector<double> mu(n);
    for(std::size_t j = 0; j < n; ++j)
    {
      const Vector_2 v = local_control_point(j);
      control[j] = center + R * Vector_2(q[E_1] * v.x(), q[E_2] * v.y());
      const double tp = std::tan(0.5 * segment_theta_span((j + n - 1) % n)), tn = std::tan(0.5 * segment_theta_span(j));
      mu[j] = tp / (tp + tn);
    }
    Blending_region r(std::move(control), std::move(mu), m_r, m_kind, m_retained, Blending_function(q[W], q[H]),
                      m_theta);
    r.set_chart(m_chart);
    return r;
  }

  static const std::array<Parameter_info, number_of_parameters>& table()
  {
    static const std::array<Parameter_info, number_of_parameters> t = {{
      {"e_u", -HUGE_VAL, HUGE_VAL, 0., Parameter_kind::Length},
      {"e_v", -HUGE_VAL, HUGE_VAL, 0., Parameter_kind::Length},
      {"e_1", 1e-9, HUGE_VAL, 0.5, Parameter_kind::Length},
      {"e_2", 1e-9, HUGE_VAL, 0.5, Parameter_kind::Length},
      {"e_theta", -HUGE_VAL, HUGE_VAL, 0., Parameter_kind::Dimensionless},
      {"w", Blending_function::minimum_w, 1., 1., Parameter_kind::Dimensionless},
      {"h", 0., 1., 0., Parameter_kind::Dimensionless}}};
    return t;
  }

  Parameter_vector m_q;
  double m_r;
  Blending_region_kind m_kind;
  Retained_side m_retained;
  std::vector<double> m_theta;
  std::size_t m_chart = 0;
  std::optional<Blending_region> m_region; // always engaged after construction
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_ELLIPSE_BLENDING_REGION_H
