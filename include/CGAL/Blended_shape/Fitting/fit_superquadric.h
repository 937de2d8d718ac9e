// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_FIT_SUPERQUADRIC_H
#define CGAL_BLENDED_SHAPE_FITTING_FIT_SUPERQUADRIC_H

#include <CGAL/Blended_shape/Fitting/Deformable_model_fitter.h>
#include <CGAL/Blended_shape/Fitting/Fitting_settings.h>
#include <CGAL/Blended_shape/Fitting/Superquadric_multistart_search.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model.h>
#include <CGAL/Blended_shape/Fitting/Fit_metrics.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Fitting/initialize_from_moments.h>
#include <CGAL/Blended_shape/Fitting/internal/Point_normalization.h>
#include <CGAL/Blended_shape/Fitting/internal/stray_surface_points.h>
#include <CGAL/Blended_shape/internal/isolated_points.h>
#include <CGAL/Blended_shape/internal/point_range_types.h>
#include <CGAL/Blended_shape/parameters.h>

#include <CGAL/Bbox_3.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeMetrics
/// The metrics of the current model of `fitter` after a run() that ended with `status`;
/// the indices of the points judged stray (Fit_metrics::number_of_stray_points)
/// go to `stray_points`, in increasing order, if it is given.
template <class Fitter, class GeomTraits>
Fit_metrics compute_fit_metrics(Fitter& fitter, const Ellipsoid_fit<GeomTraits>& initial,
                                const Fitting_status& status, std::vector<std::size_t>* stray_points = nullptr)
{
  Fit_metrics m;
  const auto forces = fitter.forces();
  std::vector<Eigen::Vector3d> residuals;
  std::vector<double> distances;
  residuals.reserve(forces.size());
  distances.reserve(forces.size());
  for(const auto& f : forces)
  {
    // Reported figures deserve foot points polished beyond what a fitting step needs.
    const Eigen::Vector3d& p = fitter.points()[f.index];
    const auto x = fitter.model().point(refine_closest_point(fitter.model(), p, f.chart_point, 50));
    residuals.push_back(p - Eigen::Vector3d(CGAL::to_double(x.x()), CGAL::to_double(x.y()), CGAL::to_double(x.z())));
    distances.push_back(residuals.back().norm());
  }
  const Robust_loss& loss = fitter.robust_loss();
  std::vector<Eigen::Vector3d> inlier_residuals;
  CGAL::Bbox_3 inlier_box;
  double sum = 0.;
  for(std::size_t k = 0; k < forces.size(); ++k)
  {
    if(loss.is_stray(distances[k]))
    {
      ++m.number_of_stray_points;
      if(stray_points != nullptr)
        stray_points->push_back(forces[k].index);
      continue;
    }
    const Eigen::Vector3d& p = fitter.points()[forces[k].index];
    inlier_box += CGAL::Bbox_3(p[0], p[1], p[2], p[0], p[1], p[2]);
    inlier_residuals.push_back(residuals[k]);
    sum += residuals[k].squaredNorm();
  }
  m.number_of_points = forces.size();
  m.number_of_parameters = fitter.model().number_of_parameters();
  m.iterations = status.iterations;
  m.iterations_on_all_points = status.iterations_on_all_points;
  m.relative_rms = relative_rms(inlier_residuals, initial);
  m.degeneracy = initial.degeneracy;
  m.rms = inlier_residuals.empty() ? 0. : std::sqrt(sum / double(inlier_residuals.size()));
  const double diagonal = std::sqrt(CGAL::square(inlier_box.xmax() - inlier_box.xmin()) +
                                    CGAL::square(inlier_box.ymax() - inlier_box.ymin()) +
                                    CGAL::square(inlier_box.zmax() - inlier_box.zmin()));
  m.rms_over_bbox_diagonal = diagonal > 0. ? m.rms / diagonal : 0.;
  m.seconds = status.seconds;
  m.converged = status.converged;
  m.aborted = status.aborted;
  return m;
}

namespace internal {

// A rest of the robust fit `fitter` (which ended with `status`) that leaves
// out part of the surface of a clean scan: its points are judged stray but
// lie on a surface of their own (count_stray_surface_points()). Range scans
// are dense where the surface faces the scanner and sparse where it is seen
// at a slant, and a robust fit can rest on the dense part alone. When more
// than 1 % of the points (at least minimum_number_of_points) are such, the
// points not isolated are fitted by least squares
// (`least_squares_start(points, status)`: the multi-start search, then a
// fit on the subset), the robust fit goes on from there on the subset, and
// if it then leaves fewer points of a surface out, it goes on to its rest
// on all points and replaces the first. The iterations of all count in
// `status`.
template <class Fitter, class Point_3, class LeastSquaresStart, class Visitor>
std::unique_ptr<Fitter> mend_missed_surface(std::unique_ptr<Fitter> fitter, Fitting_status& status,
                                            const LeastSquaresStart& least_squares_start,
                                            const std::vector<Point_3>& points, Visitor& visitor,
                                            const std::function<bool(double)>& callback)
{
  const std::vector<Eigen::Vector3d>& coordinates = fitter->points();
  const double threshold = (std::max)(0.01 * double(coordinates.size()), double(minimum_number_of_points));
  std::vector<bool> stray = fitter->stray_points();
  if(double(std::count(stray.begin(), stray.end(), true)) <= threshold)
    return fitter;
  const std::vector<bool> isolated = isolated_points(coordinates);
  const std::size_t missed = count_stray_surface_points(coordinates, stray, isolated);
  if(double(missed) <= threshold)
    return fitter;
  std::vector<Point_3> surface;
  for(std::size_t i = 0; i < points.size(); ++i)
    if(!isolated[i])
      surface.push_back(points[i]);
  auto add_up = [&status](const Fitting_status& st) { // false if `st` was aborted
    status.iterations += st.iterations;
    status.iterations_on_all_points += st.iterations_on_all_points;
    status.aborted = st.aborted;
    return !st.aborted;
  };
  Fitting_status st;
  const std::unique_ptr<Fitter> least_squares = least_squares_start(surface, st);
  if(!add_up(st))
    return fitter;
  std::unique_ptr<Fitter> again = std::make_unique<Fitter>(points, least_squares->model(), fitter->settings());
  if(!add_up(again->run(visitor, callback, Fitting_phase::Subset)))
    return fitter;
  stray = again->stray_points();
  if(!(count_stray_surface_points(coordinates, stray, isolated) < missed))
    return fitter;
  st = again->run(visitor, callback);
  if(!add_up(st))
    return fitter;
  status.converged = st.converged;
  status.timed_out = st.timed_out;
  return again;
}

} // namespace internal

/// \ingroup PkgBlendedShapeFitting
/// What fit_superquadric() returns.
template <class GeomTraits>
struct Fit_result
{
  typedef Deformable_model<Superquadric_ellipsoid<GeomTraits>> Model; ///< the model type
  Model model;                                  ///< the fitted model
  Ellipsoid_fit<GeomTraits> initial_ellipsoid;  ///< the initialization (sec. 5.3), also the frame of eq. 14
  Fit_metrics metrics;                          ///< the fit figures
  /// The indices (in the input order) of the points judged stray, increasing
  /// (see Fit_metrics::number_of_stray_points).
  std::vector<std::size_t> stray_points;
  std::vector<Chart_mesh<GeomTraits>> meshes;   ///< the model's chart meshes, positioned
};

namespace internal {

// The body of fit_superquadric() once its named parameters are read and its
// points normalized (`normalized`, by `normalization`; `start`: when the fit
// began). It depends on the kernel and the visitor only, so that a program
// calling fit_superquadric() with many combinations of named parameters (as
// fit_blended_shape() does) compiles the fit once, not once per combination.
template <class GeomTraits, class Visitor>
Fit_result<GeomTraits> fit_normalized_superquadric(const Point_normalization<GeomTraits>& normalization,
                                                   const std::vector<typename GeomTraits::Point_3>& normalized,
                                                   const Fitting_settings& s, bool all_axes, bool mend,
                                                   Visitor& visitor, const std::function<bool(double)>& callback,
                                                   const CGAL::Surface_mesh<typename GeomTraits::Point_3>* reference,
                                                   std::chrono::steady_clock::time_point start)
{
  typedef GeomTraits Geom_traits;
  typedef typename Geom_traits::Point_3 Point_3;
  typedef CGAL::Identity_property_map<Point_3> Normalized_point_map;
  // Strays ruin the moments (sec. 5.3's initialization) when many are far away.
  const auto initial = s.robust_weighting == Robust_weighting::None ? initialize_from_moments(normalized)
                                                                    : initialize_from_trimmed_moments(normalized);
  typedef Superquadric_multistart_search<Geom_traits, std::vector<Point_3>, Normalized_point_map> Search;
  typedef typename Search::Model Model;
  typedef typename Search::Fitter Fitter;
  // The multi-start search and the fit of `pts` from `init` up to `last_phase`;
  // after a fit to rest on all points, the search among similar basins too.
  auto searched_fit = [&](const std::vector<Point_3>& pts, const Fitting_settings& settings,
                          const Ellipsoid_fit<Geom_traits>& init, Fitting_phase last_phase, Fitting_status& status) {
    Search search(pts, Normalized_point_map(), settings);
    const Model start_model = all_axes ? search.best_start(init, visitor, callback) : make_initial_model(init, 2);
    std::unique_ptr<Fitter> fitter = std::make_unique<Fitter>(pts, start_model, settings);
    status = search.last_candidate_status();
    if(!search.aborted())
      status = fitter->run(visitor, callback, last_phase);
    if(all_axes && last_phase == Fitting_phase::All_points)
      fitter = search.search_similar_basins(std::move(fitter), status, visitor, callback);
    status.iterations += search.candidate_iterations();
    status.iterations_on_all_points += search.candidate_iterations_on_all_points();
    return fitter;
  };
  Fitting_status final_status;
  std::unique_ptr<Fitter> fitter = searched_fit(normalized, s, initial, Fitting_phase::All_points, final_status);
  if(all_axes && s.robust_weighting != Robust_weighting::None && mend && !final_status.aborted &&
     !final_status.timed_out)
  {
    // (on the subset only: a start for the robust fit, see mend_missed_surface())
    auto least_squares_start = [&](const std::vector<Point_3>& pts, Fitting_status& status) {
      Fitting_settings least_squares = s;
      least_squares.robust_weighting = Robust_weighting::None;
      return searched_fit(pts, least_squares, initialize_from_moments(pts), Fitting_phase::Subset, status);
    };
    fitter = internal::mend_missed_surface(std::move(fitter), final_status, least_squares_start, normalized, visitor,
                                           callback);
  }
  final_status.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<std::size_t> stray_points;
  Fit_metrics metrics = compute_fit_metrics(*fitter, initial, final_status, &stray_points);
  if(reference != nullptr)
    metrics.chamfer_distance = symmetric_chamfer_distance(fitter->chart_meshes(), normalization.to_normalized_mesh(*reference));
  const Model model = normalization.model_from_normalized(fitter->model());
  return Fit_result<Geom_traits>{model, normalization.from_normalized(initial), normalization.from_normalized(metrics),
                                 std::move(stray_points), normalization.positioned_meshes(fitter->chart_meshes(), model)};
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeFitting

Fits one superquadric ellipsoid to `points`, in one call: best-fit
ellipsoid initialization (initialize_from_trimmed_moments(), or with
`robust_weighting` `Robust_weighting::None` the paper's
initialize_from_moments()), the search for the
closest start (Superquadric_multistart_search), the physics-based fit of
Deformable_model_fitter until steady state, the search for a closer fit
from similar superquadrics, with robust weighting a second fit where the
first left out part of a surface (`mend_missed_surfaces` below), then the metrics.

The fit works on a normalized copy of the points, centred at the origin
at about unit size (the centre of their bounding box subtracted, then divided
by a power of two near its size: exactly), and the result is mapped back: so
the fit is the same, relatively, whatever the unit of the points and however
far from the origin they are (coordinates up to `maximum_coordinate_magnitude`),
and the bounds of the fit (the smallest semi-axis, `maximum_size_factor`) are
relative to the data.

(The evolution of a blended shape by splits and holes, sec. 5.4, is not
done here: the model is always one superquadric.)

\param points the input points (at least `minimum_number_of_points`, finite, not all identical; see check_points())
\param np optional named parameters.
  The settings of the fit: every member of Fitting_settings, read by
  settings_from_named_parameters() (meanings and defaults there).
  From CGAL::parameters also:
  - `point_map` (default identity), `geom_traits` (default from the point type),
  - `visitor`: see Default_fitting_visitor (default: none),
  - `callback`: `std::function<bool(double)>` called before each iteration with the
    fraction of the iteration budget spent; returning false stops the fit, which
    then holds the last accepted model (default: none).

  From Blended_shapes::parameters also:
  `try_all_axes` (`bool`, default `true`: the multi-start search of
  Superquadric_multistart_search before and after the full fit, whose
  iterations count in the result's; `false`: one fit from the initial
  ellipsoid with make_initial_model()'s default z axis),
  `mend_missed_surfaces` (`bool`, default `true`: with robust weighting and
  `try_all_axes`, a rest that judges more than 1 % of the points stray
  where they lie on a surface of their own, as the part of a range scan
  seen at a slant, is challenged by a fit from a least-squares start, and
  the one that leaves fewer such points out is kept; see the manual, Robust
  Weights), and
  `reference_mesh` (a pointer to a `CGAL::Surface_mesh<Point_3>`: then the
  symmetric Chamfer distance to it is reported).

\throws Input_error if the points are unusable (check_points(), before any fitting: e.g. `Scale_out_of_range`
        for coordinates whose squares overflow); std::invalid_argument on invalid parameters
        (a reference mesh without faces, with faces that are not triangles, or with a coordinate that is not finite or beyond `maximum_coordinate_magnitude` too, before any fitting).
*/
template <class PointRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
auto fit_superquadric(const PointRange& points, const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  typedef internal::Point_range_types<PointRange, NamedParameters> Types;
  typedef typename Types::Geom_traits Geom_traits;
  typedef CGAL::Surface_mesh<typename Geom_traits::Point_3> Mesh;

  const typename Types::Point_map point_map = Types::point_map(np);
  const Fitting_settings s = settings_from_named_parameters(np);
  const std::function<bool(double)> callback =
    choose_parameter(get_parameter(np, CGAL::internal_np::callback), std::function<bool(double)>());
  const Mesh* reference = choose_parameter(get_parameter(np, internal_np::reference_mesh), static_cast<const Mesh*>(nullptr));
  if(reference != nullptr) // (refused before any fitting)
    internal::check_reference_mesh(*reference, "fit_superquadric");
  auto visitor = choose_parameter(get_parameter(np, CGAL::internal_np::visitor), Default_fitting_visitor());

  const bool all_axes = choose_parameter(get_parameter(np, internal_np::try_all_axes), true);
  const bool mend = choose_parameter(get_parameter(np, internal_np::mend_missed_surfaces), true);
  const auto start = std::chrono::steady_clock::now();

  // The fit sees the points centred at unit size (checked first), the result is taken back.
  const internal::Point_normalization<Geom_traits> normalization(points, point_map);
  return internal::fit_normalized_superquadric(normalization, normalization.normalized_points(points, point_map), s,
                                               all_axes, mend, visitor, callback, reference, start);
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_FIT_SUPERQUADRIC_H
