// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_IO_CHECK_POINTS_H
#define CGAL_BLENDED_SHAPE_IO_CHECK_POINTS_H

#include <CGAL/Blended_shape/IO/Input_error.h>

#include <CGAL/number_utils.h>
#include <CGAL/property_map.h>

#include <boost/range/value_type.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <sstream>
#include <string>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

template <class Point>
bool is_finite_point(const Point& p)
{
  // to_double: the checks must also compile for kernels whose FT is not double.
  return std::isfinite(CGAL::to_double(p.x())) &&
         std::isfinite(CGAL::to_double(p.y())) &&
         std::isfinite(CGAL::to_double(p.z()));
}

template <class Point>
std::string point_to_string(const Point& p)
{
  std::ostringstream s;
  s.precision(10);
  s << CGAL::to_double(p.x()) << ' ' << CGAL::to_double(p.y()) << ' ' << CGAL::to_double(p.z());
  return s.str();
}

inline std::string plural(std::size_t n, const char* word)
{
  return std::to_string(n) + ' ' + word + (n == 1 ? "" : "s");
}

// The checks that do not depend on where the points came from: shared by
// check_points() (in memory) and read_points() (after dropping non-finite
// points). The points are assumed finite. `where` starts every message
// (e.g. "read_points: 'scan.xyz'"); `note` qualifies the count
// (e.g. " after dropping 3 points with non-finite coordinates").
template <class PointRange, class PointMap>
void check_count_and_spread(const PointRange& points, PointMap point_map,
                            const std::string& where, const std::string& note)
{
  const auto first = std::begin(points);
  std::size_t n = 0;
  bool all_identical = true;
  for(auto it = first; it != std::end(points); ++it, ++n)
    if(all_identical && n > 0 && !(get(point_map, *it) == get(point_map, *first)))
      all_identical = false;

  if(n == 0)
    throw Input_error(Input_error::No_points,
                      where + " contains no points" + note +
                      "; provide at least " + std::to_string(minimum_number_of_points) +
                      " points with finite coordinates");
  if(n < minimum_number_of_points)
    throw Input_error(Input_error::Too_few_points,
                      where + " contains only " + plural(n, "point") + note + ", but at least " +
                      std::to_string(minimum_number_of_points) +
                      " are needed to fit a shape; use a denser sampling of the surface");
  if(all_identical)
    throw Input_error(Input_error::All_points_identical,
                      where + ": all " + std::to_string(n) + " points" + note +
                      " are identical (" + point_to_string(get(point_map, *first)) +
                      "); the points must sample a surface, so check how they were produced or exported");
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeIO

Checks that a point set can be given to the initialization and the fit:
it is not empty, has at least `minimum_number_of_points` points, every
coordinate is finite and at most `maximum_coordinate_magnitude` in absolute
value, not all points are identical, and their extent (the largest side of
their bounding box) is at least `minimum_point_set_extent`.

Unlike `read_points()`, which drops non-finite points read from a file, an
in-memory range is rejected as a whole: silently skipping elements would
break the correspondence with the caller's indices.

Collinear or coplanar point sets pass: the initialization reports those.

\tparam PointRange a model of `ConstRange` (traversed twice at most).
\tparam PointMap a model of `ReadablePropertyMap` whose key type is the value
        type of `PointRange` and whose value type is a `Point_3` of a CGAL kernel.

\throws Input_error with code `No_points`, `Non_finite_point` (the message
        gives the index of the first bad point), `Scale_out_of_range` for a
        too large coordinate (the same), `Too_few_points`,
        `All_points_identical` or `Scale_out_of_range` for a too small extent,
        checked in this order.
*/
template <class PointRange, class PointMap>
void check_points(const PointRange& points, PointMap point_map)
{
  std::size_t i = 0;
  double low[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, high[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for(auto it = std::begin(points); it != std::end(points); ++it, ++i)
  {
    const auto& p = get(point_map, *it);
    if(!internal::is_finite_point(p))
      throw Input_error(Input_error::Non_finite_point,
                        "check_points: point " + std::to_string(i) + " (counting from 0) has a "
                        "non-finite coordinate (" + internal::point_to_string(p) +
                        "); remove or repair points with NaN or infinite coordinates before "
                        "the fit (read_points() drops them when reading a file)");
    if(!internal::has_coordinates_in_range(p)) // (finite, checked above: too large)
    {
      std::ostringstream s;
      s << "check_points: point " << i << " (counting from 0) has a coordinate beyond " << maximum_coordinate_magnitude
        << " in absolute value (" << internal::point_to_string(p) << "), whose square overflows double "
           "precision; express the points in a larger unit (or translate them nearer the origin) so that every "
           "coordinate is at most " << maximum_coordinate_magnitude;
      throw Input_error(Input_error::Scale_out_of_range, s.str());
    }
    const double x[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    for(int k = 0; k < 3; ++k)
    {
      low[k] = (std::min)(low[k], x[k]);
      high[k] = (std::max)(high[k], x[k]);
    }
  }
  internal::check_count_and_spread(points, point_map, "check_points: the point range", "");
  const double extent = (std::max)({high[0] - low[0], high[1] - low[1], high[2] - low[2]});
  if(extent < minimum_point_set_extent)
  {
    std::ostringstream s;
    s << "check_points: the points span only " << extent << " (the largest side of their bounding box), under "
      << minimum_point_set_extent << ", whose square underflows double precision; express the points in a smaller "
         "unit so that they span at least " << minimum_point_set_extent;
    throw Input_error(Input_error::Scale_out_of_range, s.str());
  }
}

/*!
\ingroup PkgBlendedShapeIO

Same as `check_points(points, point_map)` for a range of points.
*/
template <class PointRange>
void check_points(const PointRange& points)
{
  typedef typename boost::range_value<PointRange>::type Point;
  check_points(points, CGAL::Identity_property_map<Point>());
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_CHECK_POINTS_H
