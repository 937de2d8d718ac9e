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
#define CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(NAME) CGAL_BLENDED_SHAPE_PARAMETER(NAME)
#include <CGAL/Blended_shape/internal/parameter_names.h>
#undef CGAL_BLENDED_SHAPE_EVOLUTION_SETTING
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
#define CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(NAME) CGAL_BLENDED_SHAPE_PARAMETER(NAME)
#include <CGAL/Blended_shape/internal/parameter_names.h>
#undef CGAL_BLENDED_SHAPE_EVOLUTION_SETTING
#undef CGAL_BLENDED_SHAPE_FITTING_SETTING
#undef CGAL_BLENDED_SHAPE_PARAMETER

} // namespace parameters

namespace internal {

// Reading settings (Fitting_settings, Evolution_settings) from named
// parameters, with the names written once, in the list: read_settings(s, np)
// sets each member NAME of `s` that the list names from the named parameter
// NAME of `np`, if given. (read_setting() of a NAME that `s` has no member of
// does nothing: the `long` overload.)
#define CGAL_BLENDED_SHAPE_PARAMETER(NAME)
#define CGAL_BLENDED_SHAPE_FITTING_SETTING(NAME)                                                       \
  template <class Settings, class NP>                                                                  \
  auto read_setting(Settings& s, const NP& np, internal_np::NAME##_t, int) -> decltype(void(s.NAME))   \
  {                                                                                                    \
    s.NAME = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, internal_np::NAME), s.NAME); \
  }                                                                                                    \
  template <class Settings, class NP>                                                                  \
  void read_setting(Settings&, const NP&, internal_np::NAME##_t, long) {}
#define CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(NAME) CGAL_BLENDED_SHAPE_FITTING_SETTING(NAME)
#include <CGAL/Blended_shape/internal/parameter_names.h>
#undef CGAL_BLENDED_SHAPE_EVOLUTION_SETTING
#undef CGAL_BLENDED_SHAPE_FITTING_SETTING

template <class Settings, class NP>
void read_settings(Settings& s, const NP& np)
{
#define CGAL_BLENDED_SHAPE_FITTING_SETTING(NAME) read_setting(s, np, internal_np::NAME, 0);
#define CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(NAME) read_setting(s, np, internal_np::NAME, 0);
#include <CGAL/Blended_shape/internal/parameter_names.h>
#undef CGAL_BLENDED_SHAPE_EVOLUTION_SETTING
#undef CGAL_BLENDED_SHAPE_FITTING_SETTING
}
#undef CGAL_BLENDED_SHAPE_PARAMETER

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PARAMETERS_H
