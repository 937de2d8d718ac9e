// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_EVOLUTION_FIT_BLENDED_SHAPE_H
#define CGAL_BLENDED_SHAPE_EVOLUTION_FIT_BLENDED_SHAPE_H

#include <CGAL/Blended_shape/Evolution/Evolution_settings.h>
#include <CGAL/Blended_shape/Evolution/Part_evolution.h>
#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <CGAL/Blended_shape/Fitting/internal/Point_normalization.h>
#include <CGAL/Blended_shape/internal/point_range_types.h>
#include <CGAL/Blended_shape/parameters.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeEvolution
/// What fit_blended_shape() returns: the evolved model and the record of its evolution.
template <class GeomTraits>
struct Blended_fit_result
{
  typedef Deformable_blended_model<GeomTraits> Model; ///< the model type
  Model model;                          ///< the evolved model, in the frame of the input points
  /// The splits tried, kept or undone, in order. Their RMS distances are in
  /// the unit of the input points, their description lengths those of the
  /// points in that unit (see Part_evolution).
  std::vector<Evolution_event> events;
  Evolution_status status;              ///< how evolution ended (its iterations do not count the first fit's)
  /// The indices (in the input order, increasing) of the points judged
  /// isolated, which evolution does not fit (Part_evolution::isolated_points()).
  std::vector<std::size_t> isolated_points;
  double rms = 0.;                      ///< RMS distance of the points fitted to the model (Part_evolution::mean_squared_distance())
  double rms_over_bbox_diagonal = 0.;   ///< the same over the diagonal of their bounding box
  Fit_result<GeomTraits> first_fit;     ///< the one superquadric evolution started from (fit_superquadric())
  double seconds = 0.;                  ///< wall-clock time of the whole fit
};

/*!
\ingroup PkgBlendedShapeEvolution

Fits a blended shape to `points` in one call: one superquadric first
(fit_superquadric(), robust by default), then part evolution
(Part_evolution::run(): splits where the forces at rest say the model
cannot fit the data, each kept only if it pays for its parameters).

Like fit_superquadric(), evolution works on a copy of the points centred at
the origin at about unit size, and the model is mapped back exactly: the
result does not depend on the unit of the points or on where they are.

\param points the input points (see check_points())
\param np optional named parameters:
  - every member of Fitting_settings (settings_from_named_parameters()),
    for the first fit and for evolution's fits (which are least-squares
    fits of the points that are not isolated, see Part_evolution);
  - every member of Evolution_settings (evolution_settings_from_named_parameters()):
    `maximum_number_of_parts` (1: one superquadric), `target_accuracy`,
    `maximum_split_tries`, `threshold_factor`, `analysis_resolution`;
  - `point_map`, `geom_traits`, `try_all_axes`, `reference_mesh`: as for fit_superquadric();
  - `visitor`: a fitting visitor (Default_fitting_visitor), whose
    `on_split()` and `on_undo()` are called too if it has them
    (Default_evolution_visitor);
  - `callback`: as for fit_superquadric(), passed to every fit; when it
    stops evolution, the model is the last one kept.

\throws Input_error if the points are unusable; std::invalid_argument on invalid parameters.
*/
template <class PointRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
auto fit_blended_shape(const PointRange& points, const NamedParameters& np = CGAL::parameters::default_values())
{
  const auto start = std::chrono::steady_clock::now();
  const Evolution_settings evolution_settings = evolution_settings_from_named_parameters(np);
  check_evolution_settings(evolution_settings, "fit_blended_shape");

  typedef internal::Point_range_types<PointRange, NamedParameters> Types;
  typedef typename Types::Geom_traits Geom_traits;
  typedef Blended_fit_result<Geom_traits> Result;
  typedef typename Result::Model Model;
  const typename Types::Point_map point_map = Types::point_map(np);
  const std::function<bool(double)> callback = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, CGAL::internal_np::callback), std::function<bool(double)>());
  auto visitor = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::visitor),
                                                    Default_evolution_visitor());

  auto first = fit_superquadric(points, np);
  const internal::Point_normalization<Geom_traits> normalization(points, point_map);
  const auto first_normalized = normalization.model_to_normalized(first.model);
  Part_evolution<Geom_traits> evolution(
    normalization.normalized_points(points, point_map),
    Model(Blended_shape<Geom_traits>(first_normalized.shape()), first_normalized.translation(),
          first_normalized.quaternion()),
    settings_from_named_parameters(np), evolution_settings);
  Result result{normalization.model_from_normalized(evolution.model()), {}, {}, {}, 0., 0., std::move(first), 0.};
  if(result.first_fit.metrics.aborted)
    result.status.aborted = true; // the model is the first fit's, as far as it went
  else
  {
    result.status = evolution.run(visitor, callback);
    result.model = normalization.model_from_normalized(evolution.model());
  }
  // Lengths back in the input's unit: distances times the scale, and the
  // description length of the points (n/2) ln(MSD) shifted by n ln(scale).
  const double scale = normalization.scale();
  const double n = double(evolution.fitter().number_of_points());
  result.events = evolution.events();
  for(Evolution_event& e : result.events)
  {
    e.rms_before *= scale;
    e.rms_after *= scale;
    e.description_length_before += n * std::log(scale);
    e.description_length_after += n * std::log(scale);
  }
  result.isolated_points = evolution.isolated_points();
  const double rms = std::sqrt(evolution.mean_squared_distance());
  result.rms = rms * scale;
  const double diagonal = evolution.fitter().bounding_box_diagonal();
  result.rms_over_bbox_diagonal = diagonal > 0. ? rms / diagonal : 0.;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_EVOLUTION_FIT_BLENDED_SHAPE_H
