// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_SHAPE_POINT_H
#define CGAL_BLENDED_SHAPE_BLENDING_SHAPE_POINT_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>

#include <cstddef>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeBlending
/// A point of the domain of a blended shape: a chart point of one component.
/// Several such points may be the same point of the quotient domain (eq. 2);
/// `Blended_shape::canonical_point()` chooses one.
struct Shape_point
{
  std::size_t component = 0; ///< the component
  Chart_point u;             ///< the chart point of that component

  Shape_point() = default;
  /// Chart point `p` of component `c`.
  Shape_point(std::size_t c, const Chart_point& p) : component(c), u(p) {}
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_SHAPE_POINT_H
