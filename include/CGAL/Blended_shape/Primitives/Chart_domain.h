// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_CHART_DOMAIN_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_CHART_DOMAIN_H

#include <cmath>
#include <cstddef>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeCharts
/// A point of a chart: which chart of the primitive, and its two chart
/// coordinates. Chart coordinates are plain doubles whatever the kernel:
/// they are parameters of the map, not geometry.
struct Chart_point
{
  std::size_t chart = 0; ///< index of the chart, in [0, number of charts of the primitive)
  double x = 0.;         ///< first chart coordinate
  double y = 0.;         ///< second chart coordinate

  Chart_point() = default;
  /// The point `(xx, yy)` of chart `c`.
  Chart_point(std::size_t c, double xx, double yy) : chart(c), x(xx), y(yy) {}
};

/// \ingroup PkgBlendedShapeCharts
/// The shapes of chart domains the package knows how to tessellate.
/// Sec. 3.2 of the paper: only disks, open tubes and tori can be
/// parameterized without singularity.
enum class Chart_kind
{
  Disk,  ///< the closed disk x^2 + y^2 <= radius^2
  Torus, ///< the square [0, 2 pi)^2, periodic in both coordinates
  Tube   ///< the strip [0, 2 pi) x [y_min, y_max], periodic in x only (an open tube, two boundary circles)
};

/// \ingroup PkgBlendedShapeCharts
/// Description of one chart domain: its kind and its extent. Make it with
/// the factories disk(), torus() and tube(), which set every member.
struct Chart_domain
{
  Chart_kind kind = Chart_kind::Disk; ///< the shape of the domain
  /// Disk charts: the radius of the domain (1 + margin for the ellipsoid
  /// halves). Torus and tube charts: 0 (unused).
  double radius = 1.;
  /// The smallest `y` of the domain. Tube charts: the lower boundary circle.
  /// Disk charts: `-radius`. Torus charts: 0 (`y` is periodic; `[y_min, y_max)`
  /// is one period).
  double y_min = -1.;
  /// The largest `y` of the domain. Tube charts: the upper boundary circle.
  /// Disk charts: `radius`. Torus charts: `2 pi` (`y` is periodic).
  double y_max = 1.;

  /// The disk of radius `r` centred at the origin.
  static Chart_domain disk(double r) { return Chart_domain{Chart_kind::Disk, r, -r, r}; }
  /// The periodic square `[0, 2 pi)^2`.
  static Chart_domain torus() { return Chart_domain{Chart_kind::Torus, 0., 0., 2. * M_PI}; }
  /// The open tube `[0, 2 pi) x [y_min, y_max]`: `x` periodic with period
  /// `2 pi`, `y` bounded (its two boundary circles are real boundaries).
  /// \pre `y_min < y_max`, both finite (Chart_mesh checks it).
  static Chart_domain tube(double y_min, double y_max) { return Chart_domain{Chart_kind::Tube, 0., y_min, y_max}; }

  /// Period of the periodic coordinates: `2 pi` for Torus (both `x` and `y`)
  /// and Tube (`x` only), 0 for disks. See x_period() and y_period() for
  /// the period of each coordinate.
  double period() const { return (kind == Chart_kind::Torus || kind == Chart_kind::Tube) ? 2. * M_PI : 0.; }
  /// Period of `x`: `2 pi` for Torus and Tube, 0 (not periodic) for Disk.
  double x_period() const { return period(); }
  /// Period of `y`: `2 pi` for Torus, 0 (not periodic) for Disk and Tube.
  double y_period() const { return kind == Chart_kind::Torus ? 2. * M_PI : 0.; }

  /// Whether (x, y) is a point of the domain (periodic coordinates: any
  /// finite value; the tube's `y` must be in `[y_min, y_max]`).
  bool contains(double x, double y) const
  {
    switch(kind)
    {
    case Chart_kind::Torus:
      return std::isfinite(x) && std::isfinite(y);
    // Points on the rim up to rounding (e.g. the tessellation's boundary
    // vertices, cos and sin times the radius) are in the domain.
    case Chart_kind::Tube:
      return std::isfinite(x) && y >= y_min - 1e-12 && y <= y_max + 1e-12;
    case Chart_kind::Disk:
    default:
      return x * x + y * y <= radius * radius * (1. + 1e-12);
    }
  }
};

namespace internal {

/// An angle reduced to [0, 2 pi), with -0 turned into 0 (periodic chart
/// coordinates and strip angles are compared and stored in this range).
inline double wrap_angle(double t)
{
  const double two_pi = 2. * M_PI;
  t = std::fmod(t, two_pi);
  if(t < 0.)
    t += two_pi;
  return (t >= two_pi) ? 0. : t + 0.;
}

} // namespace internal

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_CHART_DOMAIN_H
