// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_HOLE_COMPONENT_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_HOLE_COMPONENT_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_toroid.h>
#include <CGAL/Blended_shape/Primitives/internal/Primitive_parameters.h>
#include <CGAL/Blended_shape/Primitives/internal/superquadric_parameters.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapePrimitives
/// The two domains of a Hole_component (paper sec. 4.2, Fig. 13 and 31).
/// The same parameters give the same geometry on both while the hole is
/// closed (`a4 = a5 = 1`); switching between them changes the topology of
/// the domain, not the surface.
enum class Hole_domain
{
  /// Two disk charts, the tube cut along its middle circle `r = 0`, each half
  /// circle collapsed to the centre of its disk (Fig. 31(b)). Produces two
  /// disks glued into the base: the pinched sphere. Only a parameterization
  /// of the surface while the hole is closed.
  Two_disks,
  /// One chart, the strip `(theta, r)` in `[0, 2 pi) x [-1, 1]`, periodic in
  /// `theta` only (Fig. 31(a)), the chart domain `Chart_domain::tube(-1., 1.)`.
  /// Produces a tube glued into the base: a hole that can open.
  Tube
};

/*!
\ingroup PkgBlendedShapePrimitives

The hole component of a blended shape (paper sec. 4.2 and App. B.2, eq. 32
and 33): the inner half of a superquadric toroid,

    h(theta, r) = s_torus((1 + r/2) pi, theta),   r in [-1, 1], theta in [0, 2 pi)

with `s_torus(u, v)` the map of Superquadric_toroid (`u` around the tube, `v`
around the axis). The toroid angle `u = (1 + r/2) pi` sweeps the inner half
`[pi/2, 3 pi/2]`: `r = -1` is the toroid's top circle `u = pi/2` (`z = a3`),
`r = 1` its bottom circle `u = 3 pi/2` (`z = -a3`), where the hole is glued to
the base; `r = 0` is the inner equator `u = pi`, of radii `a1 (a4 - 1)` and
`a2 (a5 - 1)`. At `a4 = a5 = 1` that circle collapses to one point of the
axis, the pinch point: the component is the retained part of the pinched
sphere (Fig. 12, 13). Larger `a4`, `a5` open the hole (Fig. 14).

The point, the parameter Jacobian and the normal are those of a
Superquadric_toroid with the same parameters (toroid()), evaluated at the
toroid chart point toroid_chart_point(): nothing is recomputed here.

<b>Domains</b> (Hole_domain, Fig. 31), chosen with set_domain():

- `Tube`: one chart, chart point `(x, y) = (theta, r)`, `x` periodic with
  period `2 pi`, `y` in `[-1, 1]`. Counterclockwise chart triangles give the
  outward normal (`d/dy` is `pi/2` times the toroid's `d/du`, the same
  orientation as the toroid's chart `(v, u)`).
- `Two_disks`: two unit-disk charts sharing the parameters; chart 0 is the
  half `r` in `[0, 1]` (the lower half, `z <= 0`), chart 1 the half `r` in
  `[-1, 0]`. Chart point `(x, y)`, `rho = |(x, y)|`:
  chart 0 has `r = rho`, `theta = atan2(-y, x)`; chart 1 has `r = -rho`,
  `theta = atan2(y, x)`. These orientations make counterclockwise chart
  triangles give the outward normal on both disks. The centre of a disk is
  the collapsed circle `r = 0`; it is evaluated at `theta = 0` (see to_domain()).

"Outward" is the toroid's outward normal: on this inner half it points into
the hole, toward the axis, away from the material of the base it is glued to.

<b>The hole sequence</b> (sec. 4.2): with `a4 = a5 = 1` the
pinched sphere is blended in on the Two_disks domain; once fully expressed
the domain is switched to the Tube (set_domain(), to_domain(): no point of
the surface moves); then `a4` and `a5` are freed and the hole opens. The
Two_disks domain is a parameterization of the surface only while the hole is
closed: for `a4` or `a5 > 1` the middle circle has a positive radius, but a
disk centre is one chart point. set_domain() refuses to switch to Two_disks
unless hole_is_closed(), and the constructor likewise. set_parameters()
accepts `a4, a5 > 1` in the Two_disks domain too, because finite
differences (check_jacobian()) and trial steps need the map there; holding
`a4 = a5 = 1` while on the Two_disks domain is the caller's job. The map is
then still finite and its Jacobian exact, but it jumps at the disk centre.

<b>Pinch point.</b> At `a4 = a5 = 1` every point of `r = 0` maps to the same
point of the axis, where the surface is not smooth (each half is a cusp
tangent to the axis): normal() there returns the normal at `theta = 0`, the
same on both domains, though the normals around the pinch have no limit.

<b>Charts and meshes.</b> In the Two_disks domain chart_domain() is
`Chart_domain::disk(1.)` for both charts; in the Tube domain it is
`Chart_domain::tube(-1., 1.)` (Chart_kind::Tube: `x` periodic with period
`2 pi`, `y` in `[-1, 1]`). make_chart_meshes(), random_chart_point() and
check_chart_consistency() work on both domains; the tube's chart mesh has a
row of vertices on each glue circle `r = -1`, `r = 1` (its two boundary
loops) and one on the middle circle `r = 0`.

Parameters `(a1, a2, a3, a4, a5, e1, e2)` with the bounds of
Superquadric_toroid (`a1, a2, a3 > 0`, `a4, a5 >= 1`, `ei` in [0.01, 2]); the
defaults are the toroid's except `a4 = a5 = 1`: a hole starts closed. The
parameter queries of the concept (`parameter_info()` and the others) give these.

\tparam GeomTraits a CGAL kernel whose `FT` is `double`.

\cgalModels{BlendedShapePrimitive (in both domains; the Two_disks domain only while the hole is closed)}
*/
template <class GeomTraits>
class Hole_component : public internal::Parameter_queries<7, internal::toroid_parameters<true>>
{
public:
  /// The toroid whose inner half the component is, with the same parameters;
  /// the component's types are the toroid's.
  typedef Superquadric_toroid<GeomTraits> Toroid;
  typedef typename Toroid::Geom_traits Geom_traits; ///< the kernel
  typedef typename Toroid::FT FT;                   ///< the number type of the kernel
  typedef typename Toroid::Point_3 Point_3;         ///< the point type
  typedef typename Toroid::Vector_3 Vector_3;       ///< the vector type (normals)

  /// The dimension of the parameter vector: the toroid's, 7.
  static constexpr int number_of_parameters = Toroid::number_of_parameters;
  /// The parameter vector (see Parameter_index for the order).
  typedef typename Toroid::Parameter_vector Parameter_vector;
  /// The parameter Jacobian ds/dq at one chart point (3 x 7).
  typedef typename Toroid::Jacobian Jacobian;
  /// The chart Jacobian [ds/dx, ds/dy] at one chart point (3 x 2).
  typedef typename Toroid::Chart_jacobian Chart_jacobian;

  /// Indices into the parameter vector: those of Superquadric_toroid.
  enum Parameter_index
  {
    A1 = Toroid::A1, ///< x semi-axis scale
    A2 = Toroid::A2, ///< y semi-axis scale
    A3 = Toroid::A3, ///< z semi-axis (half the depth of the hole)
    A4 = Toroid::A4, ///< x ring ratio; the hole's x radius is `a1 (a4 - 1)`
    A5 = Toroid::A5, ///< y ring ratio; the hole's y radius is `a2 (a5 - 1)`
    E1 = Toroid::E1, ///< exponent of the profile (around the tube)
    E2 = Toroid::E2  ///< exponent of the cross-section (around the axis)
  };

  /// A hole component with the given parameters on the domain `domain`.
  /// The defaults are the closed hole (the pinched sphere) on two disks.
  /// \throws std::invalid_argument on out-of-bound parameters.
  /// \throws std::logic_error if `domain` is Two_disks and `a4` or `a5` is not 1.
  explicit Hole_component(double a1 = 1., double a2 = 1., double a3 = 1.,
                          double a4 = 1., double a5 = 1.,
                          double e1 = 1., double e2 = 1.,
                          Hole_domain domain = Hole_domain::Two_disks)
    : m_domain(Hole_domain::Tube)
  {
    Parameter_vector q;
    q << a1, a2, a3, a4, a5, e1, e2;
    set_parameters(q);
    set_domain(domain);
  }

  /// \name Parameters
  /// @{

  /// The current parameters.
  const Parameter_vector& parameters() const { return m_toroid.parameters(); }

  /// Sets the parameters, in either domain (see the class description for
  /// `a4, a5 > 1` on the Two_disks domain).
  /// \throws std::invalid_argument if a value is not finite or out of bounds;
  ///         the component is then unchanged.
  void set_parameters(const Parameter_vector& q)
  {
    const internal::Parameter_table<number_of_parameters>& table = internal::toroid_parameters<true>();
    internal::validate_parameters<number_of_parameters>(table.owner, table.info, q);
    m_toroid.set_parameters(q);
  }

  /// Whether the hole is closed: `a4 = a5 = 1` exactly, so that the middle
  /// circle `r = 0` is the pinch point and both domains give the same surface.
  bool hole_is_closed() const
  {
    return parameters()[A4] == 1. && parameters()[A5] == 1.;
  }

  /// The Superquadric_toroid with the same parameters, which evaluates the component.
  const Toroid& toroid() const { return m_toroid; }
  /// @}

  /// \name Domains
  /// @{

  /// The current domain.
  Hole_domain domain() const { return m_domain; }

  /// Switches to the domain `d` (the topological surgery of sec. 4.2): chart
  /// points of the old domain are chart points of the new one through
  /// to_domain(), which moves no surface point while the hole is closed.
  /// Switching to `Tube` is always allowed; to `Two_disks` only while the
  /// hole is closed. The number of charts changes with the domain.
  /// \throws std::logic_error if `d` is Two_disks and `a4` or `a5` is not 1;
  ///         the domain is then unchanged.
  void set_domain(Hole_domain d)
  {
    if(d == Hole_domain::Two_disks && !hole_is_closed())
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "Hole_component: cannot use the Two_disks domain with a4 = " << parameters()[A4]
          << ", a5 = " << parameters()[A5]
          << ": two disks parameterize the hole only while it is closed (a4 = a5 = 1, the pinched sphere);"
             " set a4 = a5 = 1 first, or keep the Tube domain";
      throw std::logic_error(msg.str());
    }
    m_domain = d;
  }

  /*!
  The chart point of the domain `target` that is the same point of the hole
  as `p`, a chart point of the other domain (the domain switch, Fig. 31):

  - to `Tube`, from disk chart `p.chart` (0 or 1): `(theta, r)` with
    `r = rho` and `theta = atan2(-y, x)` on chart 0, `r = -rho` and
    `theta = atan2(y, x)` on chart 1, `theta` reduced to `[0, 2 pi)`. A disk
    centre, the whole collapsed circle `r = 0`, goes to `(0, 0)`: `theta = 0`.
  - to `Two_disks`, from the tube point `(theta, r)`: chart 0 if `r >= 0`,
    chart 1 if `r < 0`, at distance `|r|` from the centre, so that the map
    above brings it back; every point of the circle `r = 0` goes to the
    centre of chart 0.

  The surface point is the same on both sides whenever the tube point is not
  on `r = 0`, and everywhere while the hole is closed. It does not depend on
  the parameters or on the current domain.
  \throws std::invalid_argument if `target` is Tube and `p.chart` is not 0 or 1,
          or `target` is Two_disks and `p.chart` is not 0.
  */
  static Chart_point to_domain(const Chart_point& p, Hole_domain target)
  {
    if(target == Hole_domain::Tube)
    {
      if(p.chart > 1)
        throw std::invalid_argument("Hole_component::to_domain: a chart point of the Two_disks domain has chart 0 or 1");
      const double rho = std::hypot(p.x, p.y);
      if(rho == 0.)
        return Chart_point(0, 0., 0.);
      const double theta = (p.chart == 0) ? std::atan2(-p.y, p.x) : std::atan2(p.y, p.x);
      return Chart_point(0, internal::wrap_angle(theta), (p.chart == 0) ? rho : -rho);
    }
    if(p.chart != 0)
      throw std::invalid_argument("Hole_component::to_domain: a chart point of the Tube domain has chart 0");
    const double rho = std::abs(p.y);
    const double c = std::cos(p.x), s = std::sin(p.x);
    if(p.y < 0.)
      return Chart_point(1, rho * c, rho * s);
    return Chart_point(0, rho * c, -rho * s);
  }

  /// The chart point of toroid() at which the component is evaluated for the
  /// chart point `p` of the current domain: `(v, u) = (theta, (1 + r/2) pi)`.
  /// The circles `r = -1, 0, 1` give exactly the toroid's `u = pi/2, pi, 3 pi/2`.
  Chart_point toroid_chart_point(const Chart_point& p) const
  {
    const Chart_point t = (m_domain == Hole_domain::Tube) ? p : to_domain(p, Hole_domain::Tube);
    return Chart_point(0, t.x, (1. + 0.5 * t.y) * M_PI);
  }
  /// @}

  /// \name Charts
  /// @{

  /// 2 (the disks: chart 0 for `r >= 0`, chart 1 for `r <= 0`) in the
  /// Two_disks domain, 1 (the tube) in the Tube domain.
  std::size_t number_of_charts() const { return (m_domain == Hole_domain::Tube) ? 1 : 2; }

  /// The domain of chart `c` in the current domain: `Chart_domain::tube(-1., 1.)`
  /// (`x = theta` periodic with period `2 pi`, `y = r` in `[-1, 1]`) in the
  /// Tube domain, `Chart_domain::disk(1.)` for both charts of the Two_disks domain.
  Chart_domain chart_domain(std::size_t) const
  {
    if(m_domain == Hole_domain::Tube)
      return Chart_domain::tube(-1., 1.);
    return Chart_domain::disk(1.);
  }

  /// Tube: the only chart is 0, and `q` is `p` with `x` reduced to
  /// `[0, 2 pi)`. Two_disks: the disks do not overlap (they are distinct
  /// pieces of surface; at `a4 = a5 = 1` their centres are the same point of
  /// space but not the same point of the surface), so `q = p` for
  /// `target == p.chart` and `false` otherwise.
  bool to_chart(const Chart_point& p, std::size_t target, Chart_point& q) const
  {
    if(target != p.chart || target >= number_of_charts())
      return false;
    q = canonical_chart_point(p);
    return true;
  }

  /// Tube: `p` with `x` reduced to `[0, 2 pi)`. Two_disks: `p` itself.
  Chart_point canonical_chart_point(const Chart_point& p) const
  {
    if(m_domain == Hole_domain::Tube)
      return Chart_point(p.chart, internal::wrap_angle(p.x), p.y);
    return p;
  }
  /// @}

  /// \name Evaluation
  /// @{

  /// The surface point at `p` (chart point of the current domain).
  Point_3 point(const Chart_point& p) const { return m_toroid.point(toroid_chart_point(p)); }

  /// The parameter Jacobian ds/dq (3 x 7) at `p`, and the point itself: the
  /// toroid's at toroid_chart_point(p) (the chart map does not depend on the parameters).
  Point_3 point_and_jacobian(const Chart_point& p, Jacobian& J) const
  {
    return m_toroid.point_and_jacobian(toroid_chart_point(p), J);
  }

  /// The parameter Jacobian ds/dq at `p`.
  void jacobian(const Chart_point& p, Jacobian& J) const { point_and_jacobian(p, J); }

  /// The surface point at `p` (the same as point()), and the chart Jacobian
  /// `D = [ds/dx, ds/dy]` there: the toroid's chart Jacobian `[ds/dv, ds/du]`
  /// at toroid_chart_point(p), chained with `u = (1 + r/2) pi`, and on the
  /// Two_disks domain with the polar map of to_domain() (`theta`, `r = +-rho`).
  /// Finite everywhere (see the toroid's). Within 1e-6
  /// (internal::signed_power_derivative_floor) of a disk centre, where the
  /// polar map is not differentiable (the pinch is a cusp), column `k` is
  /// the one-sided derivative along the positive chart axis `k`, from the
  /// centre outward.
  Point_3 point_and_chart_jacobian(const Chart_point& p, Chart_jacobian& D) const
  {
    const double h = 0.5 * M_PI; // du/dr
    Chart_jacobian Dt;
    const Point_3 s = m_toroid.point_and_chart_jacobian(toroid_chart_point(p), Dt);
    if(m_domain == Hole_domain::Tube)
    {
      D.col(0) = Dt.col(0);
      D.col(1) = h * Dt.col(1);
      return s;
    }
    // Chart 0: theta = atan2(-y, x), r = rho; chart 1: theta = atan2(y, x), r = -rho.
    const double sr = (p.chart == 0) ? 1. : -1.;
    const double rho = std::hypot(p.x, p.y);
    if(rho < internal::signed_power_derivative_floor)
    {
      // Rays from the centre along +x (theta = 0) and +y (theta = -sr pi/2):
      // theta is constant on each, r = sr t.
      Chart_jacobian Dx, Dy;
      m_toroid.point_and_chart_jacobian(Chart_point(0, 0., M_PI), Dx);
      m_toroid.point_and_chart_jacobian(Chart_point(0, internal::wrap_angle(-sr * h), M_PI), Dy);
      D.col(0) = (sr * h) * Dx.col(1);
      D.col(1) = (sr * h) * Dy.col(1);
      return s;
    }
    // d theta = sr (uy, -ux) / rho, d r = sr (ux, uy); the ds/dtheta column is
    // divided by rho first: it vanishes like rho^2 at the centre of a closed hole.
    const double ux = p.x / rho, uy = p.y / rho;
    const Eigen::Vector3d dtheta = (sr / rho) * Dt.col(0), dr = (sr * h) * Dt.col(1);
    D.col(0) = uy * dtheta + ux * dr;
    D.col(1) = -ux * dtheta + uy * dr;
    return s;
  }

  /// The unit outward normal at `p`: the toroid's at toroid_chart_point(p)
  /// (both domains are oriented like the toroid's chart). At the pinch point
  /// (`r = 0` with `a4 = a5 = 1`) it is the normal at `theta`, which on the
  /// Two_disks domain is `theta = 0`.
  Vector_3 normal(const Chart_point& p) const { return m_toroid.normal(toroid_chart_point(p)); }
  /// @}

private:
  Toroid m_toroid;
  Hole_domain m_domain;
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_HOLE_COMPONENT_H
