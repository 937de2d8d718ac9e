// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_BLEND_REGION_CHECKS_H
#define CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_BLEND_REGION_CHECKS_H

// The validity of the blends of a blended shape: every blend's regions lie in
// their charts with their strips, and regions of different blends are disjoint
// and on the surface (sec. 3.6: at most one blend reaches a point).

#include <CGAL/Blended_shape/Blending/Blend.h>
#include <CGAL/Blended_shape/Blending/Shape_point.h>
#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/Primitives/Component_shape.h>
#include <CGAL/Blended_shape/Primitives/Hole_component.h>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// Whether component `c` of `shape` (a Blended_shape) is a hole in its Tube domain.
template <class Shape>
bool is_tube_component(const Shape& shape, std::size_t c)
{
  typedef typename Shape::Hole Hole;
  const Hole* h = shape.component(c).shape().template primitive<Hole>();
  return h && h->domain() == Hole_domain::Tube;
}

/// Sample points of the strips and disks of blend `b` on its base component
/// (`base_side`) or on its added one, as shape points.
template <class Shape>
std::vector<Shape_point> region_samples(const Shape& shape, std::size_t b, bool base_side)
{
  const Blend& B = shape.blend(b);
  std::vector<Shape_point> s;
  const int n = 48;
  for(int k = 0; k < n; ++k)
  {
    const double th = 2. * M_PI * k / n;
    for(double d : {-1., 0., 1.})
    {
      if(base_side)
      {
        const Eigen::Vector2d v = B.base_region().strip_point(d, th);
        s.push_back(Shape_point(B.base_component(), Chart_point(B.base_region().chart(), v.x(), v.y())));
      }
      else
        s.push_back(Shape_point(B.added_component(),
                                B.added_side().strip_point(d, th, is_tube_component(shape, B.added_component()))));
    }
  }
  return s;
}

/// Whether blend `b` reaches or cuts away `p`: its strips, its base disk or
/// discarded part, and the part of an added component outside its ellipse
/// region (a region there would be on no surface).
template <class Shape>
bool blend_reaches(const Shape& shape, std::size_t b, const Shape_point& p)
{
  const Blend& B = shape.blend(b);
  const Component_shape& s = shape.component(p.component).shape();
  Chart_point v;
  if(p.component == B.base_component() && s.to_chart(p.u, B.base_region().chart(), v))
  {
    const Region_side side = B.base_region().locate(Eigen::Vector2d(v.x, v.y)).side;
    if(side != Region_side::Retained)
      return true;
  }
  if(p.component == B.added_component())
  {
    const bool tube = is_tube_component(shape, p.component);
    const bool ellipse = B.added_side().kind() == Added_side::Ellipse;
    if(!s.to_chart(p.u, B.added_side().chart(tube), v))
      return ellipse;
    const Region_side side = B.added_side().locate(v, tube, B.core_stretch()).side;
    if(side == Region_side::Strip || (ellipse && side == Region_side::Discarded))
      return true;
  }
  return false;
}

/// Whether blends `b` and `o` have a component in common.
template <class Shape>
bool blends_share_a_component(const Shape& shape, std::size_t b, std::size_t o)
{
  const Blend &B = shape.blend(b), &O = shape.blend(o);
  return B.base_component() == O.base_component() || B.base_component() == O.added_component() ||
         B.added_component() == O.base_component() || B.added_component() == O.added_component();
}

/// \throws std::invalid_argument unless blend `b`'s regions (with their
/// strips) are inside their charts.
template <class Shape>
void check_blend_in_charts(const Shape& shape, std::size_t b)
{
  const Blend& B = shape.blend(b);
  // The base region must stay inside its chart, with its strip.
  const Component_shape& base = shape.component(B.base_component()).shape();
  if(B.base_region().chart() >= base.number_of_charts())
    throw std::invalid_argument("Blended_shape: the region's chart " + std::to_string(B.base_region().chart()) +
                                " is not a chart of component " + std::to_string(B.base_component()));
  const Chart_domain dom = base.chart_domain(B.base_region().chart());
  for(const Shape_point& p : region_samples(shape, b, true))
    if(!dom.contains(p.u.x, p.u.y))
      throw std::invalid_argument("Blended_shape: the blending region of blend " + std::to_string(b) +
                                  " (with its strip) leaves chart " + std::to_string(p.u.chart) + " of component " +
                                  std::to_string(p.component) + "; make it smaller or move it inside the chart");
  if(B.added_side().kind() == Added_side::Ellipse)
  {
    const Component_shape& added = shape.component(B.added_component()).shape();
    const Chart_domain ad = added.chart_domain(B.added_side().chart(false));
    for(const Shape_point& p : region_samples(shape, b, false))
      if(!ad.contains(p.u.x, p.u.y))
        throw std::invalid_argument("Blended_shape: the added component's region of blend " + std::to_string(b) +
                                    " leaves its chart");
  }
}

/// \throws std::invalid_argument if blend `b`'s regions meet a region of a
/// blend before `others` (but `b`) that shares a component with it.
template <class Shape>
void check_blend_disjoint(const Shape& shape, std::size_t b, std::size_t others)
{
  for(std::size_t o = 0; o < others; ++o)
  {
    if(o == b || !blends_share_a_component(shape, b, o))
      continue;
    bool meet = false;
    for(bool side : {true, false})
    {
      for(const Shape_point& p : region_samples(shape, b, side))
        meet = meet || blend_reaches(shape, o, p);
      for(const Shape_point& p : region_samples(shape, o, side))
        meet = meet || blend_reaches(shape, b, p);
    }
    if(meet)
      throw std::invalid_argument("Blended_shape: the region of blend " + std::to_string(b) + " meets the region of blend " +
                                  std::to_string(o) + " or lies where it cuts the surface away; regions of "
                                  "different blends must be disjoint and on the surface");
  }
}

/// Blend `b`'s regions (with their strips) are inside their charts, and meet
/// no region of the blends before `others` (but `b`) that share a component with it.
template <class Shape>
void validate_blend(const Shape& shape, std::size_t b, std::size_t others)
{
  check_blend_in_charts(shape, b);
  check_blend_disjoint(shape, b, others);
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_BLEND_REGION_CHECKS_H
