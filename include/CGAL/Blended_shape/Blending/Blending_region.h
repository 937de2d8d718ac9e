// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_BLENDING_REGION_H
#define CGAL_BLENDED_SHAPE_BLENDING_BLENDING_REGION_H

#include <CGAL/Blended_shape/Blending/Blending_function.h>
#include <CGAL/Blended_shape/Blending/internal/Bezier_loop.h>
#include <CGAL/Blended_shape/Blending/internal/Strip_segment.h>
#include <CGAL/Blended_shape/Blending/internal/label_crossings.h>
#include <CGAL/Blended_shape/Blending/internal/strip_inverse.h>
#include <CGAL/Blended_shape/Blending/internal/winding_number.h>
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
    return internal::bezier(m_vertex[i], m_control[i], m_vertex[next(i)], gamma);
  }

  /// `d kappa_{i(i+1)}/d gamma`.
  Vector_2 curve_tangent(std::size_t i, double gamma) const
  {
    return internal::bezier_derivative(m_vertex[i], m_control[i], m_vertex[next(i)], gamma);
  }

  /// `C_{omega_{i(i+1)}}(d, gamma)`, eq. 24.
  Vector_2 strip_point(std::size_t i, double d, double gamma) const { return segment(i).point(d, gamma); }

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
  Matrix_2 strip_jacobian(std::size_t i, double d, double gamma) const { return segment(i).jacobian(d, gamma); }
  /// @}

  /// \name Strip coordinates (inverse of eq. 24, 27)
  /// @{

  /// Whether `u` lies in the convex hull of the extremal control polygons
  /// `d = +- 1` of segment `i` (a tiny tolerance included): a necessary
  /// condition for the segment to hold `u` (convex hull property).
  bool segment_may_contain(std::size_t i, const Vector_2& u) const { return m_hull[i].contains(u, 1e-9 * m_scale); }

  /// Whether `u` lies in the bounding box of the segments' hulls (the same
  /// tolerance included): a necessary condition for `u` to be in the strip or
  /// on the curve. Most points that the blended shape locates are far from a
  /// given region: this one test settles them.
  bool strip_box_may_contain(const Vector_2& u) const
  {
    const double eps = 1e-9 * m_scale;
    return !(u.x() < m_strip_lo.x() - eps || u.y() < m_strip_lo.y() - eps || u.x() > m_strip_hi.x() + eps ||
             u.y() > m_strip_hi.y() + eps);
  }

  /*!
  Solves `C_i(d,gamma) = u` in segment `i` by Newton's method from the
  closest point of `kappa_{i(i+1)}` (eq. 25 as the first guess), with
  no range check on the result. Returns false if Newton does not converge
  (`u` far outside the segment's strip).
  */
  bool solve_in_segment(std::size_t i, const Vector_2& u, double& d, double& gamma) const
  {
    return internal::solve_strip_coordinates(segment(i), u, newton_tolerance(u), d, gamma);
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
    if(!strip_box_may_contain(u))
      return std::nullopt;
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
    if(!strip_box_may_contain(u))
      return 0; // outside the bounding box of the curve's control polygon
    int wn = 0;
    const double eps = 1e-14 * m_scale * m_scale;
    for(std::size_t i = 0; i < number_of_segments(); ++i)
      wn += internal::segment_winding(u, m_vertex[i], m_control[i], m_vertex[next(i)], eps);
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
    const internal::Segment_split split =
      internal::split_segment(m_vertex[i], m_control[i], m_vertex[ip], m_mu[i], m_mu[ip], gamma);
    const double theta_s = m_theta[i] + gamma * (theta_end(i) - m_theta[i]);

    Blending_region tmp(*this);
    tmp.m_control[i] = split.first_control;
    tmp.m_control.insert(tmp.m_control.begin() + std::ptrdiff_t(i + 1), split.second_control);
    tmp.m_mu[i] = split.mu_start;
    tmp.m_mu[ip] = split.mu_end; // index of the old vertex i+1 before the insertion
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
      const std::size_t segment = i;
      const std::vector<double> cuts = internal::label_crossings(
        [this, segment](double gamma) { return curve_point(segment, gamma); }, label, gamma_tolerance,
        samples_per_segment);
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
  std::size_t next(std::size_t i) const { return (i + 1 == number_of_segments()) ? 0 : i + 1; }
  double theta_end(std::size_t i) const
  {
    return (i + 1 == number_of_segments()) ? m_theta.front() + 2. * M_PI : m_theta[i + 1];
  }

  // The strip coordinate map of segment i (eq. 24), on the region's data.
  internal::Strip_segment segment(std::size_t i) const
  {
    const std::size_t j = next(i);
    return internal::Strip_segment{m_vertex[i], m_control[i], m_vertex[j], m_normal[i], m_middle_normal[i], m_normal[j]};
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

  // Derived data and validation (see Validity in the class description), in
  // the order each step needs the previous ones.
  void rebuild()
  {
    check_data();
    const double extent = compute_scale();
    m_vertex = internal::loop_vertices(m_control, m_mu); // eq. 20
    compute_area(extent);
    compute_normals(extent);
    check_no_folds();
    m_hull.resize(m_control.size());
    for(std::size_t i = 0; i < m_control.size(); ++i)
    {
      m_hull[i] = internal::Segment_hull::of(segment(i));
      m_strip_lo = (i == 0) ? m_hull[i].lo : m_strip_lo.cwiseMin(m_hull[i].lo);
      m_strip_hi = (i == 0) ? m_hull[i].hi : m_strip_hi.cwiseMax(m_hull[i].hi);
    }
  }

  // Sizes, finiteness and ranges of the data and constants.
  void check_data() const
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
  }

  // The extent of the control points, and the region's size for tolerances.
  double compute_scale()
  {
    Vector_2 lo = m_control[0], hi = m_control[0];
    for(const Vector_2& p : m_control)
    {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double extent = (hi - lo).maxCoeff();
    m_scale = (std::max)(extent, m_r);
    return extent;
  }

  void compute_area(double extent)
  {
    const double area = internal::loop_signed_area(m_vertex, m_control);
    if(!(std::abs(area) > 1e-12 * extent * extent))
      fail("the curve encloses no area");
    m_area = area;
    m_orientation = area > 0. ? 1 : -1;
  }

  // The normals n_i (length r, toward the retained side) and the middle normals (eq. 22, 23).
  void compute_normals(double extent)
  {
    const std::size_t n = m_control.size();
    // Normals at the k_i: the tangent there is k_{i(i+1)} - k_{(i-1)i}.
    m_normal.resize(n);
    const double s = normal_sign();
    for(std::size_t i = 0; i < n; ++i)
    {
      const Vector_2 t = m_control[i] - m_control[(i + n - 1) % n];
      const double len = t.norm();
      if(!(len > 1e-12 * extent))
        fail("control points " + std::to_string((i + n - 1) % n) + " and " + std::to_string(i) + " coincide");
      m_normal[i] = (s * m_r / len) * internal::perp(t);
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
  }

  // No folds: det[dC/dd, dC/dgamma] is affine in d; compare d = +-1 with d = 0.
  void check_no_folds() const
  {
    double reference_sign = 0.;
    for(std::size_t i = 0; i < m_control.size(); ++i)
      for(int k = 0; k <= 32; ++k)
      {
        const double g = k / 32.;
        // det(d) = N x K' + d N x N', with N the normal blend and K' the curve tangent.
        const internal::Strip_segment seg = segment(i);
        const Matrix_2 A0 = seg.jacobian(0., g);
        const Vector_2 np = seg.normal_blend_derivative(g);
        const double det0 = internal::det2(A0), det1 = A0(0, 0) * np.y() - A0(1, 0) * np.x();
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
  std::vector<internal::Segment_hull> m_hull; // the inverse's pre-test, one per segment
  Vector_2 m_strip_lo, m_strip_hi;            // the bounding box of the hulls: of the strip and the curve
  double m_area = 0.;
  int m_orientation = 1;
  double m_scale = 1.;
};

} // namespace Blended_shapes
} // namespace CGAL

// The ellipse-shaped region (App. A.3) is built on this class; it was
// declared here before it had its own header, and stays reachable from here.
#include <CGAL/Blended_shape/Blending/Ellipse_blending_region.h>

#endif // CGAL_BLENDED_SHAPE_BLENDING_BLENDING_REGION_H
