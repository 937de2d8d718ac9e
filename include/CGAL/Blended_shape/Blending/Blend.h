// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_BLEND_H
#define CGAL_BLENDED_SHAPE_BLENDING_BLEND_H

#include <CGAL/Blended_shape/Blending/Blending_region.h>
#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/Primitives/Hole_component.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeBlending
/// How a blend came about (sec. 4): it decides nothing in the evaluation,
/// which depends only on the regions, but the hierarchy and the files keep it.
enum class Blend_kind
{
  Split, ///< the added component started as a copy of the base (sec. 4.1)
  Part,  ///< a different primitive blended in gradually (sec. 4.1)
  Hole   ///< one end of a hole component (sec. 4.2); a hole has two such blends
};

/// \ingroup PkgBlendedShapeBlending
/// The name of a blend kind in files and graphs ("split", "part", "hole").
inline const char* blend_kind_name(Blend_kind k)
{
  switch(k)
  {
  case Blend_kind::Split: return "split";
  case Blend_kind::Part: return "part";
  default: return "hole";
  }
}

/*!
\ingroup PkgBlendedShapeBlending

The added component's side of a blend: the strip `omega_2` with its
coordinates `C_2(d, theta)` and, for gradual blending, the disk
coordinates of its retained interior (Fig. 6, 7). The correspondence
`beta` of eq. 16 is `beta(C_1(d, theta)) = C_2(-d, theta)`, extended to the
disk by equal disk coordinates `(t, theta)`.

Two kinds:
- `Ellipse`: a fixed `Ellipse_blending_region` in one chart of the added
  component, retaining the inside of its curve. Its parameters are
  constants: the base side's region carries the blend's parameters
  (eq. 29); the added component moves through its own shape and placement.
- `Hole_end`: one end of a `Hole_component` (App. B.2). In the
  Two_disks domain, end `e` is disk chart `e`, the curve is the circle of
  radius `1 - delta`, the strip the ring `1 - 2 delta <= rho <= 1`
  (`d = (1 - delta - rho)/delta`, positive toward the pinch), at polar angle
  `theta + phase`. In the Tube domain the same points through
  `Hole_component::to_domain()`: `(x, y) = (-(theta + phase), rho)` for end 0 and
  `(theta + phase, -rho)` for end 1. Both curves run counterclockwise in
  outward-oriented charts, like the base's, so `beta` preserves orientation.
*/
class Added_side
{
public:
  typedef Eigen::Vector2d Vector_2; ///< a chart point or vector
  typedef Eigen::Matrix2d Matrix_2; ///< a 2 x 2 matrix

  /// The two kinds of added sides.
  enum Kind
  {
    Ellipse, ///< an ellipse region in a chart of the added component
    Hole_end ///< an end of a hole component
  };

  /// An ellipse region (its retained side must be `Inside`).
  /// \throws std::invalid_argument otherwise
  static Added_side ellipse(const Ellipse_blending_region& region)
  {
    if(region.retained_side() != Retained_side::Inside)
      throw std::invalid_argument("Added_side: the added component keeps the inside of its curve");
    Added_side a;
    a.m_kind = Ellipse;
    a.m_ellipse = region;
    return a;
  }

  /// End `end` (0 or 1) of a hole component, strip half-width `delta` in
  /// `(0, 0.5)` (radial units of the disk charts), angle offset `phase`.
  /// \throws std::invalid_argument on invalid values
  static Added_side hole_end(int end, double delta, double phase)
  {
    if(end != 0 && end != 1)
      throw std::invalid_argument("Added_side: a hole has ends 0 and 1");
    if(!(delta > 0. && delta < 0.5))
      throw std::invalid_argument("Added_side: the hole end strip half-width must be in (0, 0.5)");
    if(!std::isfinite(phase))
      throw std::invalid_argument("Added_side: the hole end phase must be finite");
    Added_side a;
    a.m_kind = Hole_end;
    a.m_end = end;
    a.m_delta = delta;
    a.m_phase = phase;
    return a;
  }

  /// The kind.
  Kind kind() const { return m_kind; }
  /// `Ellipse` only: the region.
  const Ellipse_blending_region& ellipse_region() const { return *m_ellipse; }
  /// `Hole_end` only: which end (0: chart 0 of the Two_disks domain, `r >= 0`).
  int end() const { return m_end; }
  /// `Hole_end` only: the strip half-width.
  double delta() const { return m_delta; }
  /// `Hole_end` only: the angle offset.
  double phase() const { return m_phase; }

  /// The chart of the added component holding the strip (`tube`: the hole is in its Tube domain).
  std::size_t chart(bool tube) const
  {
    if(m_kind == Ellipse)
      return m_ellipse->chart();
    return tube ? 0 : std::size_t(m_end);
  }

  /// `C_2(d, theta)` as a chart point of the added component, and `[∂/∂d, ∂/∂theta]`.
  Chart_point strip_point(double d, double theta, bool tube, Matrix_2* J = nullptr) const
  {
    if(m_kind == Ellipse)
    {
      const Vector_2 p = m_ellipse->strip_point(d, theta, J);
      return Chart_point(m_ellipse->chart(), p.x(), p.y());
    }
    const double rho = 1. - m_delta - m_delta * d, phi = theta + m_phase;
    if(tube)
    {
      const double s = (m_end == 0) ? -1. : 1.;
      if(J)
        *J << 0., s, (m_end == 0 ? -m_delta : m_delta), 0.;
      return Chart_point(0, internal::wrap_angle(s * phi), (m_end == 0) ? rho : -rho);
    }
    const double c = std::cos(phi), sn = std::sin(phi);
    if(J)
      *J << -m_delta * c, -rho * sn, -m_delta * sn, rho * c;
    return Chart_point(std::size_t(m_end), rho * c, rho * sn);
  }

  /// The point with disk coordinates `(t, theta)` (see
  /// `Ellipse_blending_region::core_point()`, with `d_b = +1` and the
  /// blend's core stretch `k`) and `[∂/∂t, ∂/∂theta]` (not in the Tube
  /// domain: there the ends are annuli). For a hole end the curves are
  /// radial: `rho(t) = t R + b(t) (k delta - R)`, `R = 1 - 2 delta`.
  Chart_point core_point(double t, double theta, double k, Matrix_2* J = nullptr) const
  {
    if(m_kind == Ellipse)
    {
      const Vector_2 p = m_ellipse->core_point(t, theta, 1., k, J);
      return Chart_point(m_ellipse->chart(), p.x(), p.y());
    }
    const double R = 1. - 2. * m_delta, phi = theta + m_phase;
    const double rho = t * R + Ellipse_blending_region::core_bend(t) * (k * m_delta - R);
    const double drho = R + Ellipse_blending_region::core_bend_derivative(t) * (k * m_delta - R);
    const double c = std::cos(phi), sn = std::sin(phi);
    if(J)
      *J << drho * c, -rho * sn, drho * sn, rho * c;
    return Chart_point(std::size_t(m_end), rho * c, rho * sn);
  }

  /// Where chart point `u` (of chart `chart(tube)`) lies: in the strip
  /// (with `d`, `theta`), inside (with disk coordinates when available), or outside.
  struct Location
  {
    Region_side side = Region_side::Retained; ///< `Retained`: inside the curve beyond the strip
    double d = 0.;                            ///< strip coordinate, if in the strip
    double theta = 0.;                        ///< strip or disk angle
    double t = 0.;                            ///< disk coordinate, if inside and available
    bool has_core = false;                    ///< whether `t`, `theta` are the disk coordinates
  };

  /// Locates `u` (a chart point of `chart(tube)`); `k` is the blend's core stretch.
  Location locate(const Chart_point& u, bool tube, double k) const
  {
    Location loc;
    if(m_kind == Ellipse)
    {
      const Vector_2 v(u.x, u.y);
      const Region_location r = m_ellipse->locate(v);
      loc.side = r.side;
      if(r.side == Region_side::Strip)
      {
        loc.d = r.coordinates.d;
        loc.theta = r.coordinates.theta;
      }
      else if(r.side == Region_side::Retained)
      {
        if(std::optional<Core_coordinates> c = m_ellipse->core_coordinates(v, 1., k))
        {
          loc.has_core = true;
          loc.t = c->t;
          loc.theta = c->theta;
        }
      }
      return loc;
    }
    double rho, phi;
    if(tube)
    {
      const bool mine = (m_end == 0) ? (u.y >= 0.) : (u.y < 0.);
      if(!mine)
        return loc; // the other half of the tube: retained as far as this end is concerned
      rho = std::abs(u.y);
      phi = (m_end == 0) ? -u.x : u.x;
    }
    else
    {
      if(u.chart != std::size_t(m_end))
        return loc;
      rho = std::hypot(u.x, u.y);
      phi = (rho > 0.) ? std::atan2(u.y, u.x) : 0.;
    }
    const double d = (1. - m_delta - rho) / m_delta;
    loc.theta = internal::wrap_angle(phi - m_phase);
    if(d <= 1. + 1e-12) // the strip's edges, up to rounding, are in the strip (as for ellipse regions)
    {
      loc.side = (d >= -1. - 1e-12) ? Region_side::Strip : Region_side::Discarded;
      loc.d = (std::max)(-1., (std::min)(1., d));
    }
    else if(!tube)
    {
      loc.has_core = true;
      loc.t = hole_end_core_t(rho, k);
    }
    return loc;
  }

  /// The ratio of a region's mean radius to its strip half-width (an
  /// ellipse region: `(e_1 + e_2) / 2 / r`; a hole end: `(1 - 2 delta) / delta`).
  double radius_to_half_width() const
  {
    if(m_kind == Ellipse)
      return 0.5 * (m_ellipse->parameters()[Ellipse_blending_region::E_1] +
                    m_ellipse->parameters()[Ellipse_blending_region::E_2]) / m_ellipse->half_width();
    return (1. - 2. * m_delta) / m_delta;
  }

private:
  // t in [0, 1] with rho(t) = rho (rho(t) increases: the stretch keeps b's dent mild).
  double hole_end_core_t(double rho, double k) const
  {
    const double R = 1. - 2. * m_delta;
    double t = (std::min)(1., rho / R);
    for(int it = 0; it < 40; ++it)
    {
      const double f = t * R + Ellipse_blending_region::core_bend(t) * (k * m_delta - R) - rho;
      const double df = R + Ellipse_blending_region::core_bend_derivative(t) * (k * m_delta - R);
      if(std::abs(f) <= 4e-16 || !(df > 0.))
        break;
      t -= f / df;
    }
    return t;
  }

  Kind m_kind = Ellipse;
  std::optional<Ellipse_blending_region> m_ellipse;
  int m_end = 0;
  double m_delta = 0.1;
  double m_phase = 0.;
};

/*!
\ingroup PkgBlendedShapeBlending

One blend of a blended shape (eq. 3): the base side, an ellipse-shaped
region (eq. 29) in chart `base_region().chart()` of component
`base_component()`, whose seven parameters are the blend's parameters, and
the added side (`Added_side`) on component `added_component()`. A disk
region (`Blending_region_kind::Disk`) is a gradual blend: the discarded
disk of the base corresponds to the whole retained part of the added
component (Fig. 7, `Omega_2 = omega_2`), and `h` sets how much of it is
expressed. An annulus region is cut and glue (Fig. 6): `h = 0`, and the
added component's retained interior is its own surface.
*/
class Blend
{
public:
  /// A blend of the given kind between the two components; `core_stretch`
  /// `k` > 0 of the disk coordinates (0: default_core_stretch()).
  /// \throws std::invalid_argument if the base region keeps its inside or `k` is negative or not finite
  Blend(Blend_kind kind, std::size_t base_component, const Ellipse_blending_region& base_region,
        std::size_t added_component, const Added_side& added_side, std::size_t hole = no_hole,
        double core_stretch = 0.)
    : m_kind(kind), m_base(base_component), m_region(base_region), m_added(added_component), m_side(added_side),
      m_hole(hole), m_stretch(core_stretch)
  {
    if(base_region.retained_side() != Retained_side::Outside)
      throw std::invalid_argument("Blend: the base keeps the outside of its region's curve");
    if(!(core_stretch >= 0.) || !std::isfinite(core_stretch))
      throw std::invalid_argument("Blend: the core stretch must be a finite positive number (or 0 for the default)");
    if(m_stretch == 0.)
      m_stretch = default_core_stretch(base_region, added_side);
  }

  /// The default core stretch `k` of a blend: the geometric mean of the two
  /// sides' radius to half-width ratios, so that on both sides the disk
  /// coordinates' end velocity `k ∂C/∂d` is within a factor
  /// `sqrt(ratio_1 / ratio_2)` of the radius (a mild bend; see
  /// `Ellipse_blending_region::core_point()`). Fixed when the blend is made:
  /// it is not a parameter.
  static double default_core_stretch(const Ellipse_blending_region& base_region, const Added_side& added_side)
  {
    const Eigen::Vector2d q = base_region.parameters().segment<2>(Ellipse_blending_region::E_1);
    const double base_ratio = 0.5 * (q.x() + q.y()) / base_region.half_width();
    return std::sqrt(base_ratio * added_side.radius_to_half_width());
  }

  /// Marks "no hole" in hole().
  static constexpr std::size_t no_hole = std::numeric_limits<std::size_t>::max();

  /// How the blend came about.
  Blend_kind kind() const { return m_kind; }
  /// The component whose chart holds the base region.
  std::size_t base_component() const { return m_base; }
  /// The base region: its parameters are the blend's (eq. 29).
  const Ellipse_blending_region& base_region() const { return m_region; }
  /// The base region, to modify (its chart, kind and side must not change).
  Ellipse_blending_region& base_region() { return m_region; }
  /// The added component.
  std::size_t added_component() const { return m_added; }
  /// The added side.
  const Added_side& added_side() const { return m_side; }
  /// The index of the hole this blend is an end of, or `no_hole`.
  std::size_t hole() const { return m_hole; }
  /// Whether the blend is gradual (disk region, `h` free).
  bool is_gradual() const { return m_region.kind() == Blending_region_kind::Disk; }
  /// The core stretch `k` of the disk coordinates on both sides (see
  /// `Ellipse_blending_region::core_point()`): beta is C1 across the disk boundary.
  double core_stretch() const { return m_stretch; }

  /// \cond INTERNAL
  void set_base_component(std::size_t c) { m_base = c; }
  void set_added_component(std::size_t c) { m_added = c; }
  void set_hole(std::size_t h) { m_hole = h; }
  /// \endcond

private:
  Blend_kind m_kind;
  std::size_t m_base;
  Ellipse_blending_region m_region;
  std::size_t m_added;
  Added_side m_side;
  std::size_t m_hole;
  double m_stretch;
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_BLEND_H
