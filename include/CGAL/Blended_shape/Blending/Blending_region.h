// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_BLENDING_REGION_H
#define CGAL_BLENDED_SHAPE_BLENDING_BLENDING_REGION_H

#include <CGAL/Blended_shape/Blending/Blending_function.h>
#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>
#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeBlending
/// The two shapes of blending regions of the paper (sec. 3.1, 3.4, Figs. 6-8).
enum class Blending_region_kind
{
  /// Cut and glue (Fig. 6, 8a): `alpha = alpha_0(d)` in the strip, 1 on
  /// the retained side, and `h` is fixed to 0 (it is not a parameter).
  /// Points on the discarded side beyond the strip are not part of the
  /// blended surface (reported as `Region_side::Discarded`, `alpha = 0`).
  Annulus,
  /// Gradual blending (Fig. 7, 8b): the whole discarded interior of the curve
  /// belongs to the blend and carries `alpha_0 = 0`, so `alpha = h`
  /// there (DESIGN.md, "Resolved ambiguities": the paper's text says 1, but
  /// eq. 3, 4 and sec. 4.1 need 0); `h in [0,1]` is free. The discarded
  /// side is always the inside of the curve.
  Disk
};

/// \ingroup PkgBlendedShapeBlending
/// Which side of the closed curve `kappa` the base shape keeps
/// (`d > 0` there, App. A.1).
enum class Retained_side
{
  Outside, ///< the outside of the curve is kept, the inside is discarded (required for disk regions)
  Inside   ///< the inside of the curve is kept
};

/// \ingroup PkgBlendedShapeBlending
/// Where a chart point lies with respect to a blending region.
enum class Region_side
{
  Discarded, ///< beyond the strip on the discarded side (`d < -1`)
  Strip,     ///< in the strip `omega`, `|d| <= 1`
  Retained   ///< beyond the strip on the retained side (`d > 1`)
};

/// \ingroup PkgBlendedShapeBlending
/// Coordinates of a strip point: the segment `i` that holds it, the
/// segment coordinates `(d, gamma)` of eq. 24 and the strip angle
/// `theta in [0, 2 pi)` of eq. 27.
struct Strip_coordinates
{
  std::size_t segment = 0; ///< the segment `i` holding the point
  double d = 0.;           ///< signed strip coordinate, positive on the retained side, in [-1, 1] in the strip
  double gamma = 0.;       ///< segment parameter, in [0, 1]
  double theta = 0.;       ///< strip angle (eq. 27)
};

/// \ingroup PkgBlendedShapeBlending
/// The result of locating a chart point: its side, and its strip
/// coordinates when `side == Region_side::Strip`.
struct Region_location
{
  Region_side side = Region_side::Discarded; ///< where the point lies
  Strip_coordinates coordinates;             ///< its strip coordinates, if `side == Region_side::Strip`
};

/// \ingroup PkgBlendedShapeBlending
/// Strip coordinates with the gradients of `d` and `theta` with
/// respect to the parameters of the region, at a fixed chart point.
template <class Gradient>
struct Strip_coordinates_and_gradient
{
  Strip_coordinates coordinates; ///< the strip coordinates
  Gradient d_gradient;           ///< the gradient of `d`
  Gradient theta_gradient;       ///< the gradient of `theta`
};

/// \ingroup PkgBlendedShapeBlending
/// The blending function `alpha` at a chart point, where the point lies,
/// and `∂alpha/∂q_b` (eq. 30).
template <class Gradient>
struct Alpha_and_gradient
{
  double alpha = 0.;        ///< the blending function at the point
  Region_location location; ///< where the point lies
  Gradient gradient;        ///< the derivatives of `alpha` with respect to the region's parameters
};

/// \ingroup PkgBlendedShapeBlending
/// Coordinates of a point enclosed by a strip boundary curve `C(d_b, .)`:
/// the point is `c + t (C(d_b, theta) - c)`, `c` the centre of the region
/// (the "disk-shaped coordinate system" of A.1, used for the discarded
/// interior of disk regions).
struct Core_coordinates
{
  std::size_t segment = 0; ///< the segment of the boundary curve the ray from the centre meets
  double gamma = 0.;       ///< the segment parameter of that boundary point
  double theta = 0.;       ///< the strip angle of that boundary point, in [0, 2 pi)
  double t = 0.;           ///< the radial coordinate, 0 at the centre, 1 on the boundary curve
};

/*!
\ingroup PkgBlendedShapeBlending

A blending region in one chart (App. A.1, A.2): a closed curve `kappa`
made of `N` quadratic Bézier segments, the strip `omega` of
half-width `r` around it with its coordinates `C_omega(d, theta)`,
and the blending function `alpha` of `d`.

<b>Curve</b> (eq. 17-21). The data are the control points
`k_{i(i+1)}` and the ratios `mu_i in (0,1)` (eq. 19); the segment
end points are `k_i = k_{(i-1)i}(1-mu_i) + k_{i(i+1)}mu_i` (eq. 20),
so consecutive segments share their end point and their tangent there
(`kappa` is `G^1`). Segment `i` is the quadratic Bézier curve
of `(k_i, k_{i(i+1)}, k_{i+1})` (eq. 21). Indices wrap modulo `N`.

<b>Strip</b> (eq. 22-24). The normals `n_i` at the `k_i` have length
`r` and point toward the retained side. The middle normal
`n_{i(i+1)}` makes the control polygon `{k + d n}` parallel to the
curve's one (its legs at distance `|d| r` from the legs of
`{k_i, k_{i(i+1)}, k_{i+1}}`). Eq. 23 computes it as
`r(hat(p)_i + hat(p)_{i+1})/|hat(n)_i x hat(n)_{i+1}|`, which is 0/0
when the normals are parallel, and whose sign is that of the convex side
rather than of the retained one. We use the equivalent form, the
intersection of the two offset legs:

    n_{i(i+1)} = (n_i + n_{i+1}) / (1 + n_i . n_{i+1} / r^2),

which satisfies `n_{i(i+1)} . hat(n)_i = n_{i(i+1)} . hat(n)_{i+1} = r`,
has the same length `r/cos(phi/2)` (`phi` the turn of the segment),
is exactly `n_i` when `n_i = n_{i+1}` (the first case of eq. 23), is
smooth in the data, and degenerates only for a U-turn
(`n_{i+1} = -n_i`), which is rejected. The coordinate map of segment
`i` is eq. 24,
`C_i(d,gamma) = sum_j B_j(gamma)(k_j + d n_j)` with the quadratic
Bernstein polynomials `B_j`; `theta = theta_i + gamma(theta_{i+1} - theta_i)` (eq. 26-27), `theta_i = 2 pi i/N` by default.

<b>Inverse</b>. Eq. 24 is the exact coordinate map. A chart point is looked
up in the segments whose convex hull of the extremal control polygons
`d = +- 1` contains it (the convex hull property, end of A.2); in such a
segment the closest point on `kappa_{i(i+1)}` and the projected signed
distance (eq. 25) give a first guess, and Newton's method on
`C_i(d,gamma) = u` makes `C_i(d,gamma) = u` hold to rounding
(`10^-12` of the region's size). The point is in the strip when
`|d| <= 1` and `gamma in [0,1]`.

<b>Sides</b>. Away from the strip, the side is the winding number of
`kappa` around the point, computed exactly: a segment contributes the
winding of its control polygon when the point is outside its control
triangle (the curve lies in the triangle, so both are homotopic there), and
is split by de Casteljau otherwise, which amounts to an adaptively refined
polyline of `kappa`. The flag `Retained_side` says which side is kept;
for a `Blending_region_kind::Disk` region it must be `Outside` (the
discarded part is the disk inside the curve, where `alpha_0 = 0`).

<b>Validity</b>. `N >= 3`, finite data, `mu_i in (0,1)`, `r > 0`,
strictly increasing `theta_i` spanning less than `2 pi`, a curve
that encloses a nonzero area, and a strip without folds: the Jacobian
determinant of `C_i`, which is affine in `d`, must keep the sign it
has on `kappa` and at least 10% of its value there at `d = +- 1` (at 33
values of `gamma` per segment). Roughly: `r` below 90% of the
smallest radius of curvature of `kappa`. Overlaps between strips of
segments far apart along the curve (a thin neck) are not detected; the
curve must be simple. Violations throw `std::invalid_argument` and leave
the object unchanged.

<b>Parameters</b> (eq. 28): the vector
`(k_{01}, mu_0, k_{12}, mu_1, ..., w, h)` of `3N + 2` numbers
(index `3i`, `3i+1`: `k_{i(i+1)}`; `3i+2`: `mu_i`; `3N`: `w`;
`3N+1`: `h`). `r`, `theta_i`, the kind and the side are
constants of the region.

Chart coordinates are plain doubles (`Eigen::Vector2d`): the region is
kernel independent. The loop lives in the plane of the chart (no periodic
wrap-around).
*/
class Blending_region
{
public:
  typedef Eigen::Vector2d Vector_2;         ///< a chart point or vector
  typedef Eigen::VectorXd Parameter_vector; ///< the 3N + 2 parameters (eq. 28)
  typedef Eigen::Matrix2d Matrix_2;         ///< a 2 x 2 matrix
  /// Gradient of (d, gamma) with respect to the local data of a segment:
  /// columns `k_{(i-1)i}` (x, y), `k_{i(i+1)}` (x, y),
  /// `k_{(i+1)(i+2)}` (x, y), `mu_i`, `mu_{i+1}`.
  typedef Eigen::Matrix<double, 2, 8> Local_gradient;

  /*!
  A region with control points `k_{i(i+1)}` = `control_points[i]`,
  ratios `mu`, strip half-width `half_width` (`r`, chart units), the
  given kind and retained side, blending function (`w`, `h`) and
  strip angles `theta_i` (empty: `2 pi i/N`).
  \throws std::invalid_argument on invalid data (see Validity above).
  */
  Blending_region(std::vector<Vector_2> control_points, std::vector<double> mu, double half_width,
                  Blending_region_kind kind = Blending_region_kind::Annulus,
                  Retained_side retained = Retained_side::Outside,
                  const Blending_function& blending = Blending_function(),
                  std::vector<double> theta = std::vector<double>())
    : m_control(std::move(control_points)), m_mu(std::move(mu)), m_theta(std::move(theta)),
      m_r(half_width), m_kind(kind), m_retained(retained), m_blending(blending)
  {
    if(m_theta.empty())
      m_theta = uniform_theta(m_control.size());
    rebuild();
  }

  /// `theta_i = 2 pi i / N` (eq. 26).
  static std::vector<double> uniform_theta(std::size_t n)
  {
    std::vector<double> t(n);
    for(std::size_t i = 0; i < n; ++i)
      t[i] = 2. * M_PI * double(i) / double(n);
    return t;
  }

  /// \name Data
  /// @{

  /// `N`, the number of Bézier segments.
  std::size_t number_of_segments() const { return m_control.size(); }
  /// `k_{i(i+1)}` (eq. 19)
  const Vector_2& control_point(std::size_t i) const { return m_control[i]; }
  /// `mu_i` (eq. 19)
  double mu(std::size_t i) const { return m_mu[i]; }
  /// `k_i` (eq. 20), the start of segment `i`
  const Vector_2& vertex(std::size_t i) const { return m_vertex[i]; }
  /// `n_i`: length `r`, toward the retained side
  const Vector_2& normal(std::size_t i) const { return m_normal[i]; }
  /// `n_{i(i+1)}` (eq. 23, in the robust form above)
  const Vector_2& middle_normal(std::size_t i) const { return m_middle_normal[i]; }
  /// `theta_i` (eq. 26)
  double theta(std::size_t i) const { return m_theta[i]; }
  /// All the strip angles.
  const std::vector<double>& thetas() const { return m_theta; }
  /// The strip half-width `r`, in chart units.
  double half_width() const { return m_r; }
  /// Annulus (cut and glue) or disk (gradual blending).
  Blending_region_kind kind() const { return m_kind; }
  /// Which side of the curve the base shape keeps.
  Retained_side retained_side() const { return m_retained; }
  /// The blending function (`w`, `h`).
  const Blending_function& blending_function() const { return m_blending; }
  /// The steepness `w` of the blending function.
  double w() const { return m_blending.w(); }
  /// The blending parameter `h`.
  double h() const { return m_blending.h(); }
  /// +1 if the control points run counterclockwise around the enclosed area, -1 otherwise.
  int orientation() const { return m_orientation; }
  /// Signed area enclosed by `kappa` (positive if counterclockwise), exact for the Bézier loop.
  double signed_area() const { return m_area; }
  /// The chart the region lives in (bookkeeping only).
  std::size_t chart() const { return m_chart; }
  /// Sets the chart the region lives in.
  void set_chart(std::size_t c) { m_chart = c; }
  /// @}

  /// \name Modification
  /// Every modifier validates, and leaves the region unchanged when it throws.
  /// @{

  /// Sets the kind of region.
  void set_kind(Blending_region_kind kind)
  {
    Blending_region tmp(*this);
    tmp.m_kind = kind;
    tmp.rebuild();
    *this = std::move(tmp);
  }
  /// Sets the side of the curve that is kept.
  void set_retained_side(Retained_side side)
  {
    Blending_region tmp(*this);
    tmp.m_retained = side;
    tmp.rebuild();
    *this = std::move(tmp);
  }
  /// Sets the strip half-width `r`.
  void set_half_width(double r)
  {
    Blending_region tmp(*this);
    tmp.m_r = r;
    tmp.rebuild();
    *this = std::move(tmp);
  }
  /// Sets the steepness `w` of the blending function.
  void set_w(double w) { m_blending.set_w(w); }
  /// \throws std::invalid_argument if `h` is not in [0, 1], or nonzero for an annulus region.
  void set_h(double h)
  {
    check_h(m_kind, h);
    m_blending.set_h(h);
  }
  /// Sets the strip angles (one per segment, strictly increasing, spanning less than 2 pi).
  void set_thetas(std::vector<double> theta)
  {
    Blending_region tmp(*this);
    tmp.m_theta = std::move(theta);
    tmp.rebuild();
    *this = std::move(tmp);
  }
  /// @}

  /// \name Parameter vector (eq. 28)
  /// @{

  /// `3N + 2`.
  std::size_t number_of_parameters() const { return 3 * number_of_segments() + 2; }
  /// The index of the x coordinate of control point `i` (y follows).
  static std::size_t control_point_index(std::size_t i) { return 3 * i; }
  /// The index of `mu_i`.
  static std::size_t mu_index(std::size_t i) { return 3 * i + 2; }
  /// The index of `w`.
  std::size_t w_index() const { return 3 * number_of_segments(); }
  /// The index of `h`.
  std::size_t h_index() const { return 3 * number_of_segments() + 1; }

  /// The parameter vector.
  Parameter_vector parameters() const
  {
    const std::size_t n = number_of_segments();
    Parameter_vector q(Eigen::Index(3 * n + 2));
    for(std::size_t i = 0; i < n; ++i)
    {
      q[Eigen::Index(3 * i)] = m_control[i].x();
      q[Eigen::Index(3 * i + 1)] = m_control[i].y();
      q[Eigen::Index(3 * i + 2)] = m_mu[i];
    }
    q[Eigen::Index(3 * n)] = w();
    q[Eigen::Index(3 * n + 1)] = h();
    return q;
  }

  /// \throws std::invalid_argument on a wrong size or invalid values.
  void set_parameters(const Parameter_vector& q)
  {
    const std::size_t n = number_of_segments();
    if(std::size_t(q.size()) != 3 * n + 2)
    {
      std::ostringstream msg;
      msg << "Blending_region: parameter vector has " << q.size() << " entries, expected 3 N + 2 = "
          << 3 * n + 2;
      throw std::invalid_argument(msg.str());
    }
    Blending_region tmp(*this);
    for(std::size_t i = 0; i < n; ++i)
    {
      tmp.m_control[i] = Vector_2(q[Eigen::Index(3 * i)], q[Eigen::Index(3 * i + 1)]);
      tmp.m_mu[i] = q[Eigen::Index(3 * i + 2)];
    }
    tmp.m_blending = Blending_function(q[Eigen::Index(3 * n)], q[Eigen::Index(3 * n + 1)]);
    tmp.rebuild();
    *this = std::move(tmp);
  }
  /// @}

  /// \name Curve and strip maps
  /// @{

  /// `kappa_{i(i+1)}(gamma)`, eq. 21.
  Vector_2 curve_point(std::size_t i, double gamma) const
  {
    return bezier(m_vertex[i], m_control[i], m_vertex[next(i)], gamma);
  }

  /// `d kappa_{i(i+1)}/d gamma`.
  Vector_2 curve_tangent(std::size_t i, double gamma) const
  {
    return bezier_derivative(m_vertex[i], m_control[i], m_vertex[next(i)], gamma);
  }

  /// `C_{omega_{i(i+1)}}(d, gamma)`, eq. 24.
  Vector_2 strip_point(std::size_t i, double d, double gamma) const
  {
    // Scalar code: this is the inner loop of every lookup, and stays fast in debug builds.
    const std::size_t j = next(i);
    const Vector_2 &k0 = m_vertex[i], &k1 = m_control[i], &k2 = m_vertex[j];
    const Vector_2 &n0 = m_normal[i], &n1 = m_middle_normal[i], &n2 = m_normal[j];
    const double s = 1. - gamma, b0 = s * s, b1 = 2. * gamma * s, b2 = gamma * gamma;
    return Vector_2(b0 * (k0.x() + d * n0.x()) + b1 * (k1.x() + d * n1.x()) + b2 * (k2.x() + d * n2.x()),
                    b0 * (k0.y() + d * n0.y()) + b1 * (k1.y() + d * n1.y()) + b2 * (k2.y() + d * n2.y()));
  }

  /// `C_omega(d, theta)`, eq. 27 (any `theta`, taken modulo `2 pi`).
  Vector_2 strip_point_at_theta(double d, double theta) const
  {
    double gamma;
    const std::size_t i = segment_of_theta(theta, gamma);
    return strip_point(i, d, gamma);
  }

  /// The segment holding angle `theta` and the segment parameter `gamma` there (eq. 27).
  std::size_t segment_of_theta(double theta, double& gamma) const
  {
    const double two_pi = 2. * M_PI;
    double t = std::fmod(theta - m_theta.front(), two_pi);
    if(t < 0.)
      t += two_pi;
    t += m_theta.front();
    const std::size_t n = number_of_segments();
    std::size_t i = std::size_t(std::upper_bound(m_theta.begin(), m_theta.end(), t) - m_theta.begin());
    i = (i == 0) ? n - 1 : i - 1;
    gamma = (t - m_theta[i]) / (theta_end(i) - m_theta[i]);
    return i;
  }

  /// The Jacobian `[∂C_i/∂d, ∂C_i/∂gamma]` of eq. 24.
  Matrix_2 strip_jacobian(std::size_t i, double d, double gamma) const
  {
    const std::size_t j = next(i);
    const Vector_2 &k0 = m_vertex[i], &k1 = m_control[i], &k2 = m_vertex[j];
    const Vector_2 &n0 = m_normal[i], &n1 = m_middle_normal[i], &n2 = m_normal[j];
    const double s = 1. - gamma, b0 = s * s, b1 = 2. * gamma * s, b2 = gamma * gamma;
    const double e0 = -2. * s, e1 = 2. - 4. * gamma, e2 = 2. * gamma; // Bernstein derivatives
    Matrix_2 A;
    A(0, 0) = b0 * n0.x() + b1 * n1.x() + b2 * n2.x();
    A(1, 0) = b0 * n0.y() + b1 * n1.y() + b2 * n2.y();
    A(0, 1) = e0 * (k0.x() + d * n0.x()) + e1 * (k1.x() + d * n1.x()) + e2 * (k2.x() + d * n2.x());
    A(1, 1) = e0 * (k0.y() + d * n0.y()) + e1 * (k1.y() + d * n1.y()) + e2 * (k2.y() + d * n2.y());
    return A;
  }
  /// @}

  /// \name Strip coordinates (inverse of eq. 24, 27)
  /// @{

  /// Whether `u` lies in the convex hull of the extremal control polygons
  /// `d = +- 1` of segment `i` (a tiny tolerance included): a necessary
  /// condition for the segment to hold `u` (convex hull property).
  bool segment_may_contain(std::size_t i, const Vector_2& u) const
  {
    const Hull& hull = m_hull[i];
    const double eps = 1e-9 * m_scale;
    if(u.x() < hull.lo.x() - eps || u.y() < hull.lo.y() - eps || u.x() > hull.hi.x() + eps ||
       u.y() > hull.hi.y() + eps)
      return false;
    const std::size_t m = hull.points.size();
    for(std::size_t a = 0; a < m; ++a)
    {
      const Vector_2& p = hull.points[a];
      const Vector_2 e = hull.points[(a + 1) % m] - p;
      if(cross(e, u - p) < -eps * e.norm())
        return false;
    }
    return true;
  }

  /*!
  Solves `C_i(d,gamma) = u` in segment `i` by Newton's method from the
  closest point of `kappa_{i(i+1)}` (eq. 25 as the first guess), with
  no range check on the result. Returns false if Newton does not converge
  (`u` far outside the segment's strip).
  */
  bool solve_in_segment(std::size_t i, const Vector_2& u, double& d, double& gamma) const
  {
    const std::size_t j = next(i);
    const Vector_2& p0 = m_vertex[i];
    const Vector_2& p1 = m_control[i];
    const Vector_2& p2 = m_vertex[j];

    // Closest point on the curve (eq. 25): coarse samples, then Newton on
    // (K - u) . K' = 0 clamped to the segment. Scalar code, as in strip_point().
    const double ax = p0.x() - 2. * p1.x() + p2.x(), ay = p0.y() - 2. * p1.y() + p2.y(); // K = p0 + 2 g b + g^2 a
    const double bx = p1.x() - p0.x(), by = p1.y() - p0.y();
    const double cx = p0.x() - u.x(), cy = p0.y() - u.y();
    double g = 0., best = std::numeric_limits<double>::infinity();
    for(int s = 0; s <= 8; ++s)
    {
      const double t = s / 8.;
      const double ex = cx + t * (2. * bx + t * ax), ey = cy + t * (2. * by + t * ay);
      if(ex * ex + ey * ey < best)
      {
        best = ex * ex + ey * ey;
        g = t;
      }
    }
    for(int it = 0; it < 20; ++it)
    {
      const double ex = cx + g * (2. * bx + g * ax), ey = cy + g * (2. * by + g * ay);
      const double tx = 2. * (bx + g * ax), ty = 2. * (by + g * ay);
      const double f = ex * tx + ey * ty, fp = tx * tx + ty * ty + 2. * (ex * ax + ey * ay);
      if(!(fp > 0.))
        break;
      const double gn = (std::min)(1., (std::max)(0., g - f / fp));
      const bool done = std::abs(gn - g) < 1e-14;
      g = gn;
      if(done)
        break;
    }
    const Vector_2 N = strip_jacobian(i, 0., g).col(0);
    d = (u - curve_point(i, g)).dot(N) / N.squaredNorm();
    gamma = g;

    // Newton on the exact map, with backtracking so that the residual never grows.
    Vector_2 F = strip_point(i, d, gamma) - u;
    double res = F.norm();
    for(int it = 0; it < 60 && res > 0.; ++it)
    {
      const Matrix_2 A = strip_jacobian(i, d, gamma);
      const double det = det2(A);
      if(!(std::abs(det) > 0.) || !std::isfinite(det))
        return false;
      const Vector_2 step = -solve_2x2(A, det, F);
      double t = 1.;
      bool improved = false;
      for(int ls = 0; ls < 30; ++ls, t *= 0.5)
      {
        const double nd = d + t * step.x(), ng = gamma + t * step.y();
        const Vector_2 Fn = strip_point(i, nd, ng) - u;
        const double rn = Fn.norm();
        if(rn < res)
        {
          d = nd;
          gamma = ng;
          F = Fn;
          res = rn;
          improved = true;
          break;
        }
      }
      if(!improved)
        break; // at the rounding floor
      if(!(std::abs(gamma) < 4.) || !(std::abs(d) < 1e3))
        return false; // left the segment's neighbourhood: the point is elsewhere
    }
    return res <= newton_tolerance(u);
  }

  /*!
  The strip coordinates of chart point `u`, or nothing when `u` is not in
  the strip (`|d| > 1`, or no segment holds it). At a junction between
  two segments, either may be reported (`d` agrees, `theta` too).
  \throws std::invalid_argument if `u` is not finite (so does every query built on this one).
  */
  std::optional<Strip_coordinates> strip_coordinates(const Vector_2& u) const
  {
    if(!u.allFinite())
      throw std::invalid_argument("Blending_region: the chart point to locate is not finite");
    const std::size_t n = number_of_segments();
    std::optional<Strip_coordinates> near_miss;
    double near_miss_excess = std::numeric_limits<double>::infinity();
    for(std::size_t i = 0; i < n; ++i)
    {
      if(!segment_may_contain(i, u))
        continue;
      double d, gamma;
      // Points on the strip's edges (|d| = 1, e.g. made by strip_point(+-1, theta))
      // come out a rounding error beyond: they belong to the strip, where
      // alpha and beta are continuous, not to the side beyond it.
      if(!solve_in_segment(i, u, d, gamma) || !(std::abs(d) <= 1. + 1e-12))
        continue;
      d = (std::max)(-1., (std::min)(1., d));
      // A point on a junction may come out a rounding error beyond [0, 1] in
      // both neighbours: accept the smallest such excess.
      const double excess = (std::max)({0., -gamma, gamma - 1.});
      if(excess == 0.)
        return make_coordinates(i, d, gamma);
      if(excess <= 1e-12 && excess < near_miss_excess)
      {
        near_miss_excess = excess;
        near_miss = make_coordinates(i, d, gamma);
      }
    }
    return near_miss;
  }

  /// The strip coordinates of `u` over the strip extended to `|d| <= max_abs_d`
  /// (eq. 24 with `d` beyond `[-1, 1]`: the offsets of `kappa` past the
  /// strip's edges), the one of smallest `|d|` if several segments hold it, or nothing.
  std::optional<Strip_coordinates> extended_strip_coordinates(const Vector_2& u, double max_abs_d) const
  {
    if(!u.allFinite())
      throw std::invalid_argument("Blending_region: the chart point to locate is not finite");
    std::optional<Strip_coordinates> best;
    for(std::size_t i = 0; i < number_of_segments(); ++i)
    {
      double d, gamma;
      if(!solve_in_segment(i, u, d, gamma) || !(std::abs(d) <= max_abs_d) || gamma < -1e-12 || gamma > 1. + 1e-12)
        continue;
      if(!best || std::abs(d) < std::abs(best->d))
        best = make_coordinates(i, d, (std::max)(0., (std::min)(1., gamma)));
    }
    return best;
  }

  /// \pre `p.chart == chart()`
  std::optional<Strip_coordinates> strip_coordinates(const Chart_point& p) const
  {
    CGAL_precondition(p.chart == m_chart);
    return strip_coordinates(Vector_2(p.x, p.y));
  }

  /// The strip coordinates of segment `i` at `(d, gamma)` (θ from eq. 27, in [0, 2π)).
  Strip_coordinates make_coordinates(std::size_t i, double d, double gamma) const
  {
    Strip_coordinates c;
    c.segment = i;
    c.d = d;
    c.gamma = gamma;
    double t = m_theta[i] + gamma * (theta_end(i) - m_theta[i]);
    const double two_pi = 2. * M_PI;
    t = std::fmod(t, two_pi);
    if(t < 0.)
      t += two_pi;
    if(t >= two_pi)
      t = 0.;
    c.theta = t;
    return c;
  }

  /// `∂(d, gamma)/∂u` at a strip point: the inverse of strip_jacobian().
  Matrix_2 coordinate_derivatives_u(std::size_t i, double d, double gamma) const
  {
    return strip_jacobian(i, d, gamma).inverse();
  }

  /// `∂(d, theta)/∂u` at the strip point `c` (rows: `d`, `theta`; eq. 24 and
  /// 27 inverted): the chart derivatives of the blending function and of `beta`.
  Matrix_2 strip_coordinate_derivatives(const Strip_coordinates& c) const
  {
    Matrix_2 M = coordinate_derivatives_u(c.segment, c.d, c.gamma);
    M.row(1) *= theta_end(c.segment) - m_theta[c.segment];
    return M;
  }
  /// @}

  /// \name Sides
  /// @{

  /// Winding number of `kappa` around `u` (0 outside; `+- 1` inside,
  /// with the sign of orientation()). Ambiguous only for points on `kappa`.
  int winding_number(const Vector_2& u) const
  {
    int wn = 0;
    const double eps = 1e-14 * m_scale * m_scale;
    for(std::size_t i = 0; i < number_of_segments(); ++i)
      wn += segment_winding(u, m_vertex[i], m_control[i], m_vertex[next(i)], eps, 0);
    return wn;
  }

  /// Whether `u` is enclosed by the curve (nonzero winding number).
  bool is_inside_curve(const Vector_2& u) const { return winding_number(u) != 0; }

  /// Which side of the region `u` is on, with its strip coordinates in the strip.
  Region_location locate(const Vector_2& u) const
  {
    Region_location loc;
    if(std::optional<Strip_coordinates> c = strip_coordinates(u))
    {
      loc.side = Region_side::Strip;
      loc.coordinates = *c;
      return loc;
    }
    const bool inside = is_inside_curve(u);
    const bool retained = (m_retained == Retained_side::Inside) ? inside : !inside;
    loc.side = retained ? Region_side::Retained : Region_side::Discarded;
    return loc;
  }

  /// \pre `p.chart == chart()`
  Region_location locate(const Chart_point& p) const
  {
    CGAL_precondition(p.chart == m_chart);
    return locate(Vector_2(p.x, p.y));
  }
  /// @}

  /// \name Blending function and derivatives (eq. 4, 15, 30)
  /// @{

  /// `alpha` at a located point: `alpha(d)` in the strip, 1 on the
  /// retained side, `h` on the discarded side (`alpha_0 = 0`; `h = 0` for an annulus).
  double alpha(const Region_location& loc) const
  {
    switch(loc.side)
    {
    case Region_side::Strip: return m_blending.alpha(loc.coordinates.d);
    case Region_side::Retained: return 1.;
    default: return m_blending.h();
    }
  }

  /// The blending function at chart point `u`.
  double alpha(const Vector_2& u) const { return alpha(locate(u)); }

  /*!
  The gradient of `d` and `gamma` at strip point `(d,gamma)` of
  segment `i` with respect to the data the segment depends on, at a fixed
  chart point: implicit differentiation of `C_i(d,gamma) = u`,

      [ ∂C/∂d  ∂C/∂gamma ] (delta d, delta gamma)^T = -delta C,

  where `delta C` collects the variations of `k_i, k_{i(i+1)}, k_{i+1}` (eq. 20) and of the normals `n_i, n_{i(i+1)}, n_{i+1}`
  (which depend on the tangents `k_{i(i+1)} - k_{(i-1)i}`). Columns: see
  `Local_gradient`.
  */
  Local_gradient local_coordinate_gradient(std::size_t i, double d, double gamma) const
  {
    return -strip_jacobian(i, d, gamma).inverse() * strip_point_local_derivative(i, d, gamma);
  }

  /// `∂C_i(d,gamma)/∂(data)` at fixed `(d, gamma)`: how the strip point of
  /// eq. 24 moves with the data of segment `i` (columns as in `Local_gradient`).
  Local_gradient strip_point_local_derivative(std::size_t i, double d, double gamma) const
  {
    const std::size_t n = number_of_segments();
    const std::size_t ip = next(i), im = (i + n - 1) % n;
    const Vector_2& a = m_control[im];
    const Vector_2& b = m_control[i];
    const Vector_2& c = m_control[ip];
    const double mu_i = m_mu[i], mu_j = m_mu[ip];
    const double B0 = (1. - gamma) * (1. - gamma), B1 = 2. * gamma * (1. - gamma), B2 = gamma * gamma;

    // dC / d(k_i, k_c, k_{i+1}, n_i, n_c, n_{i+1}), 2 x 12.
    Eigen::Matrix<double, 2, 12> dC_dG;
    const Matrix_2 I = Matrix_2::Identity();
    dC_dG << B0 * I, B1 * I, B2 * I, d * B0 * I, d * B1 * I, d * B2 * I;

    // d(k_i, k_c, k_{i+1}, n_i, n_c, n_{i+1}) / d(a, b, c, mu_i, mu_{i+1}), 12 x 8.
    Eigen::Matrix<double, 12, 8> dG_dP = Eigen::Matrix<double, 12, 8>::Zero();
    // k_i = a (1 - mu_i) + b mu_i   (eq. 20)
    dG_dP.block<2, 2>(0, 0) = (1. - mu_i) * I;
    dG_dP.block<2, 2>(0, 2) = mu_i * I;
    dG_dP.block<2, 1>(0, 6) = b - a;
    // k_c = b
    dG_dP.block<2, 2>(2, 2) = I;
    // k_{i+1} = b (1 - mu_{i+1}) + c mu_{i+1}
    dG_dP.block<2, 2>(4, 2) = (1. - mu_j) * I;
    dG_dP.block<2, 2>(4, 4) = mu_j * I;
    dG_dP.block<2, 1>(4, 7) = c - b;
    // n_i = s r J (b - a)/|b - a|, n_{i+1} = s r J (c - b)/|c - b|
    const Matrix_2 Ui = normal_derivative(b - a), Uj = normal_derivative(c - b);
    dG_dP.block<2, 2>(6, 0) = -Ui;
    dG_dP.block<2, 2>(6, 2) = Ui;
    dG_dP.block<2, 2>(10, 2) = -Uj;
    dG_dP.block<2, 2>(10, 4) = Uj;
    // n_c = (n_i + n_{i+1}) / (1 + n_i . n_{i+1} / r^2)
    const Vector_2& ni = m_normal[i];
    const Vector_2& nj = m_normal[ip];
    const double r2 = m_r * m_r;
    const double beta = 1. + ni.dot(nj) / r2;
    const Vector_2 sum = ni + nj;
    const Matrix_2 Mi = I / beta - sum * nj.transpose() / (r2 * beta * beta);
    const Matrix_2 Mj = I / beta - sum * ni.transpose() / (r2 * beta * beta);
    dG_dP.block<2, 2>(8, 0) = -Mi * Ui;
    dG_dP.block<2, 2>(8, 2) = Mi * Ui - Mj * Uj;
    dG_dP.block<2, 2>(8, 4) = Mj * Uj;

    return dC_dG * dG_dP;
  }

  /// Strip coordinates at `u` with the gradients of `d` and `theta`
  /// with respect to the `3N+2` parameters (zero for `w`, `h`);
  /// nothing outside the strip. `theta` is only `C^0` across segment
  /// junctions (its gradient jumps there); `d` is `C^1`.
  std::optional<Strip_coordinates_and_gradient<Parameter_vector>>
  strip_coordinates_and_gradient(const Vector_2& u) const
  {
    const std::optional<Strip_coordinates> c = strip_coordinates(u);
    if(!c)
      return std::nullopt;
    Strip_coordinates_and_gradient<Parameter_vector> r;
    r.coordinates = *c;
    r.d_gradient = Parameter_vector::Zero(Eigen::Index(number_of_parameters()));
    r.theta_gradient = r.d_gradient;
    const Local_gradient L = local_coordinate_gradient(c->segment, c->d, c->gamma);
    const double dtheta = theta_end(c->segment) - m_theta[c->segment];
    scatter(c->segment, L.row(0), 1., r.d_gradient);
    scatter(c->segment, L.row(1), dtheta, r.theta_gradient);
    return r;
  }

  /// `alpha(u)` and `∂alpha/∂q_b` for the
  /// `3N+2` parameters, by eq. 30. For an annulus the `h` entry is 0
  /// (`h` is not a parameter there).
  Alpha_and_gradient<Parameter_vector> alpha_and_gradient(const Vector_2& u) const
  {
    Alpha_and_gradient<Parameter_vector> r;
    r.location = locate(u);
    r.alpha = alpha(r.location);
    r.gradient = Parameter_vector::Zero(Eigen::Index(number_of_parameters()));
    const Blending_function::Derivatives D = blending_derivatives(r.location);
    if(r.location.side == Region_side::Strip && D.d_d != 0.)
    {
      const Strip_coordinates& c = r.location.coordinates;
      const Local_gradient L = local_coordinate_gradient(c.segment, c.d, c.gamma);
      scatter(c.segment, L.row(0), D.d_d, r.gradient);
    }
    r.gradient[Eigen::Index(w_index())] = D.d_w;
    r.gradient[Eigen::Index(h_index())] = D.d_h;
    return r;
  }

  /// `∂alpha/∂d`, `∂alpha/∂w` and
  /// `∂alpha/∂h` at a located point (0 for `h` on an annulus).
  Blending_function::Derivatives blending_derivatives(const Region_location& loc) const
  {
    Blending_function::Derivatives D;
    if(loc.side == Region_side::Strip)
      D = m_blending.derivatives(loc.coordinates.d);
    else
    {
      D.alpha0 = (loc.side == Region_side::Retained) ? 1. : 0.;
      D.alpha = (loc.side == Region_side::Retained) ? 1. : m_blending.h();
      D.d_d = D.d_w = 0.;
      D.d_h = 1. - D.alpha0;
    }
    if(m_kind == Blending_region_kind::Annulus)
      D.d_h = 0.;
    return D;
  }
  /// @}

  /// \name Subdivision (A.2.1)
  /// @{

  /*!
  Splits segment `i` at `gamma in (0,1)` by one step of de Casteljau:
  control polygon `{k_i, k_{i(i+1)}, k_{i+1}}` becomes
  `{k_i, k_{is}, k_s}` and `{k_s, k_{s(i+1)}, k_{i+1}}`. The curve
  is unchanged: the pieces are exactly the restrictions of the segment to
  `[0,gamma]` and `[gamma,1]`. In the region's data,
  `k_{i(i+1)}` is replaced by `k_{is}, k_{s(i+1)}`, the new vertex has
  `mu_s = gamma` and `theta_s = theta_i + gamma(theta_{i+1} - theta_i)` (so `theta` on the curve is unchanged), and
  `mu_i, mu_{i+1}` are updated so that eq. 20 still gives
  `k_i, k_{i+1}`. Segment `i` becomes the first piece, `i+1` the second;
  later segments shift by one.

  The strip off the curve changes slightly: the normal at `k_s` is the
  unit normal times `r` (as in A.2 for every vertex), while the
  de Casteljau point of the normal polygon is not, so `d` of a point
  off the curve moves by a small fraction of its value.

  \throws std::invalid_argument if `i` or `gamma` is out of range.
  */
  void split_segment_at(std::size_t i, double gamma)
  {
    const std::size_t n = number_of_segments();
    if(i >= n || !(gamma > 0. && gamma < 1.))
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "Blending_region::split_segment_at: segment " << i << " of " << n << ", gamma = " << gamma
          << "; need a segment index below N and gamma in the open interval (0, 1)";
      throw std::invalid_argument(msg.str());
    }
    const std::size_t ip = next(i);
    const Vector_2 ki = m_vertex[i], kc = m_control[i], kj = m_vertex[ip];
    const Vector_2 kis = (1. - gamma) * ki + gamma * kc;
    const Vector_2 ksj = (1. - gamma) * kc + gamma * kj;
    const double mu_i = m_mu[i], mu_j = m_mu[ip];
    // k_i = lerp(k_{(i-1)i}, k_is, mu'), k_{i+1} = lerp(k_s(i+1), k_{(i+1)(i+2)}, mu'')
    const double new_mu_i = mu_i / (mu_i + gamma * (1. - mu_i));
    const double new_mu_j = (1. - gamma) * mu_j / (1. - gamma * mu_j);
    const double theta_s = m_theta[i] + gamma * (theta_end(i) - m_theta[i]);

    Blending_region tmp(*this);
    tmp.m_control[i] = kis;
    tmp.m_control.insert(tmp.m_control.begin() + std::ptrdiff_t(i + 1), ksj);
    tmp.m_mu[i] = new_mu_i;
    tmp.m_mu[ip] = new_mu_j; // index of the old vertex i+1 before the insertion
    tmp.m_mu.insert(tmp.m_mu.begin() + std::ptrdiff_t(i + 1), gamma);
    tmp.m_theta.insert(tmp.m_theta.begin() + std::ptrdiff_t(i + 1), theta_s);
    tmp.rebuild();
    // k_s must be the de Casteljau point; it is, up to rounding, by construction.
    *this = std::move(tmp);
  }

  /*!
  Splits the segments of `kappa` where `label` (any function from a
  chart point, `Vector_2`, to an equality-comparable value, e.g. the
  component domain or chart a point belongs to) changes along the curve
  (A.2.1). Each segment is sampled at `samples_per_segment + 1` values of
  `gamma`; in every sample interval whose end labels differ, a binary
  search on `gamma` with de Casteljau points halves the bracket until it
  is shorter than `gamma_tolerance`, and the segment is split at its middle.
  Crossings closer than the sample spacing to each other, or than the
  tolerance to a segment end, are not split. Afterwards every piece is
  labelled uniformly at the samples. The paper stops the search as soon as
  `k_s` falls in the overlap of the two domains; with an overlap of
  width `delta` a tolerance of about `delta` over the segment's
  length gives the same effect.

  \returns the number of splits.
  */
  template <class LabelFunction>
  std::size_t subdivide_where(const LabelFunction& label, double gamma_tolerance = 1e-9,
                              std::size_t samples_per_segment = 16)
  {
    if(!(gamma_tolerance > 0. && gamma_tolerance < 0.5) || samples_per_segment == 0)
      throw std::invalid_argument("Blending_region::subdivide_where: need a gamma tolerance in (0, 0.5) "
                                  "and at least one sample interval per segment");
    std::size_t splits = 0;
    for(std::size_t i = 0; i < number_of_segments(); ++i)
    {
      // Crossings of this segment, in its own parameter.
      std::vector<double> cuts;
      auto previous = label(curve_point(i, 0.));
      for(std::size_t s = 1; s <= samples_per_segment; ++s)
      {
        double lo = double(s - 1) / double(samples_per_segment), hi = double(s) / double(samples_per_segment);
        auto current = label(curve_point(i, hi));
        if(!(current == previous))
        {
          while(hi - lo > gamma_tolerance)
          {
            const double mid = 0.5 * (lo + hi);
            if(label(curve_point(i, mid)) == previous)
              lo = mid;
            else
              hi = mid;
          }
          const double g = 0.5 * (lo + hi);
          if(g > gamma_tolerance && g < 1. - gamma_tolerance)
            cuts.push_back(g);
        }
        previous = current;
      }
      // Split successively; the remainder [g_prev, 1] is reparameterized affinely.
      double start = 0.;
      for(double g : cuts)
      {
        split_segment_at(i, (g - start) / (1. - start));
        start = g;
        ++i;
        ++splits;
      }
    }
    return splits;
  }
  /// @}

private:
  struct Hull
  {
    std::vector<Vector_2> points; // counterclockwise
    Vector_2 lo, hi;
  };

  std::size_t next(std::size_t i) const { return (i + 1 == number_of_segments()) ? 0 : i + 1; }
  double theta_end(std::size_t i) const
  {
    return (i + 1 == number_of_segments()) ? m_theta.front() + 2. * M_PI : m_theta[i + 1];
  }

  static double cross(const Vector_2& a, const Vector_2& b) { return a.x() * b.y() - a.y() * b.x(); }
  static Vector_2 perp(const Vector_2& a) { return Vector_2(-a.y(), a.x()); } // rotation by +90 degrees

  static Vector_2 bezier(const Vector_2& p0, const Vector_2& p1, const Vector_2& p2, double g)
  {
    const double s = 1. - g;
    return (s * s) * p0 + (2. * g * s) * p1 + (g * g) * p2;
  }
  static Vector_2 bezier_derivative(const Vector_2& p0, const Vector_2& p1, const Vector_2& p2, double g)
  {
    return 2. * (1. - g) * (p1 - p0) + 2. * g * (p2 - p1);
  }
  static double det2(const Matrix_2& A) { return A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0); }
  static Vector_2 solve_2x2(const Matrix_2& A, double det, const Vector_2& b)
  {
    return Vector_2(A(1, 1) * b.x() - A(0, 1) * b.y(), -A(1, 0) * b.x() + A(0, 0) * b.y()) / det;
  }

  double newton_tolerance(const Vector_2& u) const
  {
    return 1e-12 * (std::max)({1., m_scale, std::abs(u.x()), std::abs(u.y())});
  }

  // Sign that turns the left normal of the tangent into the retained-side normal.
  double normal_sign() const
  {
    const double s = double(m_orientation); // left normal points inside a ccw curve
    return (m_retained == Retained_side::Inside) ? s : -s;
  }

  // d n / d t for n = s r J t / |t|.
  Matrix_2 normal_derivative(const Vector_2& t) const
  {
    const double len = t.norm();
    const Vector_2 that = t / len;
    Matrix_2 J;
    J << 0., -1., 1., 0.;
    return (normal_sign() * m_r / len) * J * (Matrix_2::Identity() - that * that.transpose());
  }

  // Adds factor * row (columns of Local_gradient) into the 3N+2 gradient.
  void scatter(std::size_t i, const Eigen::Matrix<double, 1, 8>& row, double factor, Parameter_vector& g) const
  {
    const std::size_t n = number_of_segments();
    const std::size_t idx[3] = {(i + n - 1) % n, i, next(i)};
    for(int k = 0; k < 3; ++k)
    {
      g[Eigen::Index(3 * idx[k])] += factor * row[2 * k];
      g[Eigen::Index(3 * idx[k] + 1)] += factor * row[2 * k + 1];
    }
    g[Eigen::Index(3 * i + 2)] += factor * row[6];
    g[Eigen::Index(3 * next(i) + 2)] += factor * row[7];
  }

  static int edge_crossing(const Vector_2& a, const Vector_2& b, const Vector_2& u)
  {
    const double left = cross(b - a, u - a);
    if(a.y() <= u.y())
    {
      if(b.y() > u.y() && left > 0.)
        return 1;
    }
    else if(b.y() <= u.y() && left < 0.)
      return -1;
    return 0;
  }

  static bool in_closed_triangle(const Vector_2& u, const Vector_2& p0, const Vector_2& p1, const Vector_2& p2,
                                 double eps)
  {
    const double o0 = cross(p1 - p0, u - p0), o1 = cross(p2 - p1, u - p1), o2 = cross(p0 - p2, u - p2);
    return (o0 >= -eps && o1 >= -eps && o2 >= -eps) || (o0 <= eps && o1 <= eps && o2 <= eps);
  }

  // Winding contribution of one quadratic segment: its control polygon's when
  // u is outside the control triangle (curve and polygon are homotopic in the
  // triangle), otherwise the two de Casteljau halves'.
  static int segment_winding(const Vector_2& u, const Vector_2& p0, const Vector_2& p1, const Vector_2& p2,
                             double eps, int depth)
  {
    if(depth >= 52 || !in_closed_triangle(u, p0, p1, p2, eps))
      return edge_crossing(p0, p1, u) + edge_crossing(p1, p2, u);
    const Vector_2 q0 = 0.5 * (p0 + p1), q1 = 0.5 * (p1 + p2), m = 0.5 * (q0 + q1);
    return segment_winding(u, p0, q0, m, eps, depth + 1) + segment_winding(u, m, q1, p2, eps, depth + 1);
  }

  static void check_h(Blending_region_kind kind, double h)
  {
    if(kind == Blending_region_kind::Annulus && h != 0.)
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "Blending_region: h = " << h
          << " on an annulus region; h is fixed to 0 there (use a disk region for gradual blending)";
      throw std::invalid_argument(msg.str());
    }
  }

  [[noreturn]] static void fail(const std::string& what)
  {
    throw std::invalid_argument("Blending_region: " + what);
  }

  // Derived data and validation.
  void rebuild()
  {
    const std::size_t n = m_control.size();
    if(n < 3)
      fail("a closed curve needs at least 3 segments, got " + std::to_string(n));
    if(m_mu.size() != n || m_theta.size() != n)
      fail("need one mu and one theta per control point (" + std::to_string(n) + "), got " +
           std::to_string(m_mu.size()) + " and " + std::to_string(m_theta.size()));
    if(!(m_r > 0.) || !std::isfinite(m_r))
      fail("the strip half-width r must be a finite positive number");
    for(std::size_t i = 0; i < n; ++i)
    {
      if(!m_control[i].allFinite())
        fail("control point " + std::to_string(i) + " is not finite");
      if(!(m_mu[i] > 0. && m_mu[i] < 1.))
        fail("mu_" + std::to_string(i) + " is not in the open interval (0, 1)");
      if(!std::isfinite(m_theta[i]))
        fail("theta_" + std::to_string(i) + " is not finite");
      if(i > 0 && !(m_theta[i] > m_theta[i - 1]))
        fail("the theta_i must increase strictly");
    }
    if(!(m_theta.front() >= 0. && m_theta.front() < 2. * M_PI) || !(m_theta.back() < m_theta.front() + 2. * M_PI))
      fail("the theta_i must start in [0, 2 pi) and span less than 2 pi");
    if(m_kind == Blending_region_kind::Disk && m_retained != Retained_side::Outside)
      fail("a disk region discards the inside of its curve: use Retained_side::Outside");
    check_h(m_kind, m_blending.h());

    Vector_2 lo = m_control[0], hi = m_control[0];
    for(const Vector_2& p : m_control)
    {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double extent = (hi - lo).maxCoeff();
    m_scale = (std::max)(extent, m_r);

    m_vertex.resize(n);
    for(std::size_t i = 0; i < n; ++i)
      m_vertex[i] = m_control[(i + n - 1) % n] * (1. - m_mu[i]) + m_control[i] * m_mu[i]; // eq. 20

    // Exact enclosed area: polygon of the k_i plus 2/3 of each control triangle.
    double area = 0.;
    for(std::size_t i = 0; i < n; ++i)
    {
      const Vector_2& p0 = m_vertex[i];
      const Vector_2& p2 = m_vertex[next(i)];
      area += 0.5 * cross(p0, p2) + (2. / 3.) * 0.5 * cross(m_control[i] - p0, p2 - p0);
    }
    if(!(std::abs(area) > 1e-12 * extent * extent))
      fail("the curve encloses no area");
    m_area = area;
    m_orientation = area > 0. ? 1 : -1;

    // Normals at the k_i: the tangent there is k_{i(i+1)} - k_{(i-1)i}.
    m_normal.resize(n);
    const double s = normal_sign();
    for(std::size_t i = 0; i < n; ++i)
    {
      const Vector_2 t = m_control[i] - m_control[(i + n - 1) % n];
      const double len = t.norm();
      if(!(len > 1e-12 * extent))
        fail("control points " + std::to_string((i + n - 1) % n) + " and " + std::to_string(i) + " coincide");
      m_normal[i] = (s * m_r / len) * perp(t);
    }
    // Middle normals, eq. 23 in the form that survives parallel normals.
    m_middle_normal.resize(n);
    for(std::size_t i = 0; i < n; ++i)
    {
      const Vector_2& ni = m_normal[i];
      const Vector_2& nj = m_normal[next(i)];
      const double beta = 1. + ni.dot(nj) / (m_r * m_r);
      if(!(beta > 1e-6))
        fail("segment " + std::to_string(i) + " turns back on itself (its end normals are opposite)");
      m_middle_normal[i] = (ni + nj) / beta;
    }

    // No folds: det[dC/dd, dC/dgamma] is affine in d; compare d = +-1 with d = 0.
    double reference_sign = 0.;
    for(std::size_t i = 0; i < n; ++i)
      for(int k = 0; k <= 32; ++k)
      {
        const double g = k / 32.;
        // det(d) = N x K' + d N x N', with N the normal blend and K' the curve tangent.
        const Matrix_2 A0 = strip_jacobian(i, 0., g);
        const double e0 = -2. * (1. - g), e1 = 2. - 4. * g, e2 = 2. * g;
        const Vector_2 &n0 = m_normal[i], &n1 = m_middle_normal[i], &n2 = m_normal[next(i)];
        const double npx = e0 * n0.x() + e1 * n1.x() + e2 * n2.x(), npy = e0 * n0.y() + e1 * n1.y() + e2 * n2.y();
        const double det0 = det2(A0), det1 = A0(0, 0) * npy - A0(1, 0) * npx;
        const double detp = det0 + det1, detm = det0 - det1;
        if(reference_sign == 0.)
          reference_sign = det0 > 0. ? 1. : -1.;
        if(!(det0 * reference_sign > 0.) || !(detp / det0 >= 0.1) || !(detm / det0 >= 0.1))
        {
          std::ostringstream msg;
          msg.precision(6);
          msg << "the strip folds over near segment " << i << ", gamma = " << g << ": the half-width r = " << m_r
              << " is too large for the curvature of the curve there; use a smaller r or a rounder curve";
          fail(msg.str());
        }
      }

    // Convex hulls of the extremal control polygons d = +-1 (monotone chain).
    m_hull.assign(n, Hull());
    for(std::size_t i = 0; i < n; ++i)
    {
      const std::size_t j = next(i);
      std::vector<Vector_2> pts = {m_vertex[i] + m_normal[i],       m_vertex[i] - m_normal[i],
                                   m_control[i] + m_middle_normal[i], m_control[i] - m_middle_normal[i],
                                   m_vertex[j] + m_normal[j],       m_vertex[j] - m_normal[j]};
      std::sort(pts.begin(), pts.end(), [](const Vector_2& a, const Vector_2& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
      });
      std::vector<Vector_2> h(2 * pts.size());
      std::size_t k = 0;
      for(std::size_t p = 0; p < pts.size(); ++p)
      {
        while(k >= 2 && cross(h[k - 1] - h[k - 2], pts[p] - h[k - 2]) <= 0.)
          --k;
        h[k++] = pts[p];
      }
      for(std::size_t p = pts.size() - 1, t = k + 1; p-- > 0;)
      {
        while(k >= t && cross(h[k - 1] - h[k - 2], pts[p] - h[k - 2]) <= 0.)
          --k;
        h[k++] = pts[p];
      }
      h.resize(k - 1);
      Hull& H = m_hull[i];
      H.points = h;
      H.lo = pts.front();
      H.hi = pts.front();
      for(const Vector_2& p : pts)
      {
        H.lo = H.lo.cwiseMin(p);
        H.hi = H.hi.cwiseMax(p);
      }
    }
  }

  // Data (eq. 19, 26) and constants.
  std::vector<Vector_2> m_control; // k_{i(i+1)}
  std::vector<double> m_mu;
  std::vector<double> m_theta;
  double m_r;
  Blending_region_kind m_kind;
  Retained_side m_retained;
  Blending_function m_blending;
  std::size_t m_chart = 0;
  // Derived.
  std::vector<Vector_2> m_vertex;        // k_i, eq. 20
  std::vector<Vector_2> m_normal;        // n_i
  std::vector<Vector_2> m_middle_normal; // n_{i(i+1)}, eq. 23
  std::vector<Hull> m_hull;
  double m_area = 0.;
  int m_orientation = 1;
  double m_scale = 1.;
};

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
      const double f0 = cross(P0, v), f1 = cross(P1, v), f2 = cross(P2, v);
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
    Alpha_and_gradient<Parameter_vector> r;
    r.location = m_region->locate(u);
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

  static double cross(const Vector_2& a, const Vector_2& b) { return a.x() * b.y() - a.y() * b.x(); }

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
      {"w", std::numeric_limits<double>::min(), 1., 1., Parameter_kind::Dimensionless},
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

#endif // CGAL_BLENDED_SHAPE_BLENDING_BLENDING_REGION_H
