// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PARAMETERS_H
#define CGAL_BLENDED_SHAPE_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>

/*
  Package-specific named parameters.

  CGAL's own names (point_map, geom_traits, number_of_iterations, visitor,
  callback, random_seed, maximum_running_time) are used as they are, through
  CGAL::parameters. The names below are specific to this package. CGAL 5.5
  generates the chaining member functions only for its own names, so a
  package parameter starts a chain (and CGAL names chain after it with '.'),
  or takes an existing pack as its second argument:

    namespace BSP = CGAL::Blended_shapes::parameters;
    fit_superquadric(points, BSP::integrator(Integrator::Explicit).number_of_iterations(500));
    fit_superquadric(points, BSP::refine_axes(false, CGAL::parameters::point_map(pm)));
*/

namespace CGAL {
namespace Blended_shapes {
namespace internal_np {

#define CGAL_BLENDED_SHAPE_PARAMETER(NAME) enum NAME##_t { NAME };
#define CGAL_BLENDED_SHAPE_FITTING_SETTING(NAME) CGAL_BLENDED_SHAPE_PARAMETER(NAME)
#include <CGAL/Blended_shape/internal/parameter_names.h>
#undef CGAL_BLENDED_SHAPE_FITTING_SETTING
#undef CGAL_BLENDED_SHAPE_PARAMETER

} // namespace internal_np

namespace parameters {

#define CGAL_BLENDED_SHAPE_PARAMETER(NAME)                                            \
  template <class T>                                                                  \
  CGAL::Named_function_parameters<T, internal_np::NAME##_t> NAME(const T& value)      \
  {                                                                                   \
    return CGAL::Named_function_parameters<T, internal_np::NAME##_t>(value);          \
  }                                                                                   \
  template <class T, class NP_T, class NP_Tag, class NP_Base>                         \
  CGAL::Named_function_parameters<T, internal_np::NAME##_t,                           \
                                  CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>> \
  NAME(const T& value, const CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>& pack) \
  {                                                                                   \
    return CGAL::Named_function_parameters<T, internal_np::NAME##_t,                  \
             CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>>(value, pack);    \
  }
#define CGAL_BLENDED_SHAPE_FITTING_SETTING(NAME) CGAL_BLENDED_SHAPE_PARAMETER(NAME)
#include <CGAL/Blended_shape/internal/parameter_names.h>
#undef CGAL_BLENDED_SHAPE_FITTING_SETTING
#undef CGAL_BLENDED_SHAPE_PARAMETER

} // namespace parameters
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PARAMETERS_H
