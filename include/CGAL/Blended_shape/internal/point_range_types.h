// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_POINT_RANGE_TYPES_H
#define CGAL_BLENDED_SHAPE_INTERNAL_POINT_RANGE_TYPES_H

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The types an entry point taking (points, np) works with: the point map
// (named parameter `point_map`, default identity), its point type, and the
// kernel (named parameter `geom_traits`, default deduced from the point type).
template <class PointRange, class NamedParameters>
struct Point_range_types
{
  typedef typename CGAL::GetPointMap<PointRange, NamedParameters>::const_type Point_map;
  typedef typename boost::property_traits<Point_map>::value_type Point_3;
  typedef typename CGAL::Kernel_traits<Point_3>::Kernel Default_traits;
  typedef typename CGAL::internal_np::Lookup_named_param_def<
    CGAL::internal_np::geom_traits_t, NamedParameters, Default_traits>::type Geom_traits;

  static Point_map point_map(const NamedParameters& np)
  {
    return CGAL::parameters::choose_parameter<Point_map>(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::point_map));
  }
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_INTERNAL_POINT_RANGE_TYPES_H
