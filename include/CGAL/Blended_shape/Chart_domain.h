// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_CHART_DOMAIN_H
#define CGAL_BLENDED_SHAPE_CHART_DOMAIN_H

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
  Torus  ///< the square [0, 2 pi)^2, periodic in both coordinates
};

/// \ingroup PkgBlendedShapeCharts
/// Description of one chart domain.
struct Chart_domain
{
  Chart_kind kind = Chart_kind::Disk; ///< the shape of the domain
  /// Disk charts: the radius of the domain (1 + margin for the ellipsoid halves).
  double radius = 1.;

  /// The disk of radius `r` centred at the origin.
  static Chart_domain disk(double r) { return Chart_domain{Chart_kind::Disk, r}; }
  /// The periodic square `[0, 2 pi)^2`.
  static Chart_domain torus() { return Chart_domain{Chart_kind::Torus, 0.}; }

  /// Period of a periodic coordinate (0 for disks).
  double period() const { return kind == Chart_kind::Torus ? 2. * M_PI : 0.; }

  /// Whether (x, y) is a point of the domain (periodic coordinates: any value).
  bool contains(double x, double y) const
  {
    if(kind == Chart_kind::Torus)
      return std::isfinite(x) && std::isfinite(y);
    return x * x + y * y <= radius * radius;
  }
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_CHART_DOMAIN_H
