// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_SUPERQUADRIC_PARAMETERS_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_SUPERQUADRIC_PARAMETERS_H

// The parameter tables of the superquadric primitives (App. B): semi-axes,
// the toroid's ring ratios, and exponents in [0.01, 2] (the closed-form
// normals need e <= 2).

#include <CGAL/Blended_shape/Primitives/internal/Primitive_parameters.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>

#include <cmath>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// A semi-axis scale `a1`, `a2` or `a3`: a positive length (any: the fitter
/// bounds sizes relative to the data, see Fitting_settings).
inline Parameter_info semi_axis(const char* name) { return {name, smallest_size, HUGE_VAL, 1., Parameter_kind::Length}; }
/// A ring ratio `a4` or `a5` of the toroid: at least 1 (the hole closes at 1).
inline Parameter_info ring_ratio(const char* name, double default_value)
{
  return {name, 1., HUGE_VAL, default_value, Parameter_kind::Dimensionless};
}
/// A superquadric exponent `e1` or `e2`.
inline Parameter_info superquadric_exponent(const char* name)
{
  return {name, 0.01, 2., 1., Parameter_kind::Dimensionless};
}

/// `(a1, a2, a3, e1, e2)` of Superquadric_ellipsoid.
inline const Parameter_table<5>& superquadric_ellipsoid_parameters()
{
  static const Parameter_table<5> t{"Superquadric_ellipsoid",
                                    {{semi_axis("a1"), semi_axis("a2"), semi_axis("a3"),
                                      superquadric_exponent("e1"), superquadric_exponent("e2")}}};
  return t;
}

/// `(a1, a2, a3, a4, a5, e1, e2)` of Superquadric_toroid (`a4 = a5 = 2` by default)
/// or, with `a4 = a5 = 1` by default (a hole starts closed), of Hole_component.
template <bool hole>
const Parameter_table<7>& toroid_parameters()
{
  const double ring = hole ? 1. : 2.;
  static const Parameter_table<7> t{hole ? "Hole_component" : "Superquadric_toroid",
                                    {{semi_axis("a1"), semi_axis("a2"), semi_axis("a3"), ring_ratio("a4", ring),
                                      ring_ratio("a5", ring), superquadric_exponent("e1"),
                                      superquadric_exponent("e2")}}};
  return t;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_SUPERQUADRIC_PARAMETERS_H
