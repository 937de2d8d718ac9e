// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_FIT_BLENDED_SHAPE_H
#define CGAL_BLENDED_SHAPE_FITTING_FIT_BLENDED_SHAPE_H

#include <CGAL/Blended_shape/Fitting/Deformable_model_fitter.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model.h>
#include <CGAL/Blended_shape/Fitting/Fit_metrics.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Fitting/initialize_from_moments.h>
#include <CGAL/Blended_shape/internal/point_range_types.h>
#include <CGAL/Blended_shape/parameters.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <chrono>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeFitting
The closed model of an initial ellipsoid (sec. 5.3): a superquadric ellipsoid
with e1 = e2 = 1 placed at the ellipsoid's centre and rotation.

`z_axis` in {0, 1, 2} chooses which principal direction becomes the
primitive's z axis (the axis of e1); the frame is permuted cyclically so it
stays right-handed. The ellipsoid is the same for all three; the fits that
start from them are not, because a superquadric with e1 != e2 is not
symmetric under exchanging its z axis with another.
*/
template <class GeomTraits>
Deformable_model<Superquadric_ellipsoid<GeomTraits>> make_initial_model(const Ellipsoid_fit<GeomTraits>& fit,
                                                                        int z_axis = 2)
{
  if(z_axis < 0 || z_axis > 2)
    throw std::invalid_argument("make_initial_model: z_axis must be 0, 1 or 2");
  const int k = (z_axis + 1) % 3; // principal direction that becomes the primitive's x axis
  const Eigen::Matrix3d R0 = fit.rotation_matrix();
  Eigen::Matrix3d R;
  std::array<double, 3> a;
  for(int i = 0; i < 3; ++i)
  {
    R.col(i) = R0.col((k + i) % 3);
    a[std::size_t(i)] = fit.axes[std::size_t((k + i) % 3)];
  }
  const Superquadric_ellipsoid<GeomTraits> shape(a[0], a[1], a[2], 1., 1.);
  const Eigen::Vector3d c(CGAL::to_double(fit.center.x()), CGAL::to_double(fit.center.y()),
                          CGAL::to_double(fit.center.z()));
  return Deformable_model<Superquadric_ellipsoid<GeomTraits>>(shape, c, internal::quaternion_from_matrix(R));
}

/// \ingroup PkgBlendedShapeFitting
/// The number of similar superquadrics of similar_superquadric().
constexpr int number_of_similar_superquadrics = 5;

/*!
\ingroup PkgBlendedShapeFitting
A superquadric close to `model` in shape but in another basin of the fit
(the "similar superquadrics" of superquadric recovery from partial views),
in the same place:
- `swap` = 0 or 1: its z axis exchanged with its x axis (0) or y axis (1),
  with e1 and e2 exchanged;
- `swap` = 2: its cross-section turned by 45 degrees about z with e2 replaced
  by 2 - e2 and the section's axes averaged and stretched by 2^((1 - e2)/2)
  (a square seen across its diagonal is a diamond);
- `swap` = 3 or 4: swap 2 followed by swap 0 or 1 (a box whose square
  section was taken for a diamond about the wrong axis needs both).
\throws std::invalid_argument unless 0 <= swap < number_of_similar_superquadrics
*/
template <class GeomTraits>
Deformable_model<Superquadric_ellipsoid<GeomTraits>>
similar_superquadric(const Deformable_model<Superquadric_ellipsoid<GeomTraits>>& model, int swap)
{
  if(swap < 0 || swap >= number_of_similar_superquadrics)
    throw std::invalid_argument("similar_superquadric: swap must be in [0, " +
                                std::to_string(number_of_similar_superquadrics) + ")");
  if(swap > 2)
    return similar_superquadric(similar_superquadric(model, 2), swap - 3);
  const auto q = model.shape().parameters();
  const Eigen::Matrix3d R0 = model.rotation();
  Eigen::Matrix3d R = R0;
  Eigen::Vector3d a(q[0], q[1], q[2]);
  double e1 = q[4], e2 = q[3];
  if(swap < 2)
  {
    const int k = swap; // the axis that becomes z
    R.col(2) = R0.col(k);
    R.col(k) = -R0.col(2); // keeps R a rotation
    std::swap(a[2], a[k]);
  }
  else
  {
    // a quarter turn of the cross-section: a squarish section (e2 < 1) seen
    // from one side is close to a diamond-ish one (2 - e2) turned by 45 degrees
    const double c = std::sqrt(0.5);
    R.col(0) = c * (R0.col(0) + R0.col(1));
    R.col(1) = c * (R0.col(1) - R0.col(0));
    const double stretch = std::pow(2., 0.5 * (1. - q[4]));
    const double r = 0.5 * (a[0] + a[1]) * stretch;
    a[0] = a[1] = r;
    e1 = q[3];
    e2 = (std::min)((std::max)(2. - q[4], 0.1), 2.);
  }
  const Superquadric_ellipsoid<GeomTraits> shape(a[0], a[1], a[2], e1, e2);
  return Deformable_model<Superquadric_ellipsoid<GeomTraits>>(shape, model.translation(),
                                                              internal::quaternion_from_matrix(R));
}

/// \ingroup PkgBlendedShapeMetrics
/// The metrics of the current model of `fitter` after a run() that ended with `status`.
template <class Fitter, class GeomTraits>
Fit_metrics compute_fit_metrics(Fitter& fitter, const Ellipsoid_fit<GeomTraits>& initial,
                                const Fitting_status& status)
{
  Fit_metrics m;
  const auto forces = fitter.forces();
  std::vector<Eigen::Vector3d> residuals;
  residuals.reserve(forces.size());
  double sum = 0.;
  for(const auto& f : forces)
  {
    // Reported figures deserve foot points polished beyond what a fitting step needs.
    const Eigen::Vector3d& p = fitter.points()[f.index];
    const auto x = fitter.model().point(refine_closest_point(fitter.model(), p, f.chart_point, 50));
    residuals.push_back(p - Eigen::Vector3d(CGAL::to_double(x.x()), CGAL::to_double(x.y()), CGAL::to_double(x.z())));
    sum += residuals.back().squaredNorm();
  }
  m.number_of_points = forces.size();
  m.number_of_parameters = fitter.model().number_of_parameters();
  m.iterations = status.iterations;
  m.relative_rms = relative_rms(residuals, initial);
  m.rms = forces.empty() ? 0. : std::sqrt(sum / double(forces.size()));
  m.rms_over_bbox_diagonal = m.rms / fitter.bounding_box_diagonal();
  m.seconds = status.seconds;
  m.converged = status.converged;
  m.aborted = status.aborted;
  return m;
}

/// \ingroup PkgBlendedShapeFitting
/// What fit_blended_shape() returns.
template <class GeomTraits>
struct Fit_result
{
  typedef Deformable_model<Superquadric_ellipsoid<GeomTraits>> Model; ///< the model type
  Model model;                                  ///< the fitted model
  Ellipsoid_fit<GeomTraits> initial_ellipsoid;  ///< the initialization (sec. 5.3), also the frame of eq. 14
  Fit_metrics metrics;                          ///< the fit figures
  std::vector<Chart_mesh<GeomTraits>> meshes;   ///< the model's chart meshes, positioned
};

/*!
\ingroup PkgBlendedShapeFitting

Fits a model to `points`, in one call: best-fit ellipsoid initialization
(initialize_from_moments()), then the physics-based fit of
Deformable_model_fitter until steady state, then the metrics.

(This release fits a single superquadric ellipsoid; structural and
topological evolution, i.e. parts and holes, come with the blending features.)

\param points the input points (at least `minimum_number_of_points`, finite, not all identical)
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
  `try_all_axes` (`bool`, default `true`: fit roughly from each of the three choices
  of the primitive's z axis among the principal directions, see make_initial_model(),
  and from the similar superquadrics of the closest, see similar_superquadric(),
  on a 25th of the subset, at most 10 iterations each, and go on with the closest;
  after the full fit, search its similar superquadrics the same way; the
  iteration count includes these fits; `false`: one fit from the initial ellipsoid), and
  `reference_mesh` (a pointer to a `CGAL::Surface_mesh<Point_3>`: then the
  symmetric Chamfer distance to it is reported).

\throws Input_error if the points are unusable; std::invalid_argument on invalid parameters.
*/
template <class PointRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
auto fit_blended_shape(const PointRange& points, const NamedParameters& np = CGAL::parameters::default_values())
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
  auto visitor = choose_parameter(get_parameter(np, CGAL::internal_np::visitor), Default_fitting_visitor());

  const bool all_axes = choose_parameter(get_parameter(np, internal_np::try_all_axes), true);
  const auto start = std::chrono::steady_clock::now();

  const auto initial = initialize_from_moments(points, CGAL::parameters::point_map(point_map));
  typedef Deformable_model<Superquadric_ellipsoid<Geom_traits>> Model;
  typedef Deformable_model_fitter<Model> Fitter;
  // The short candidate fits: on a 25th of the subset (160 points by
  // default: enough to tell basins apart), loose tolerances, at most 10 iterations.
  Fitting_settings rough = s;
  rough.subset_size = (std::max<std::size_t>)(s.subset_size / 25, 100);
  rough.energy_tolerance = (std::max)(s.energy_tolerance, 1e-4);
  rough.force_tolerance = (std::max)(s.force_tolerance, 1e-2);
  rough.maximum_iterations = (std::min<std::size_t>)(s.maximum_iterations, 10);
  rough.mesh_resolution = (std::max)(2, s.mesh_resolution / 2); // the mesh only seeds the analytic closest points
  // The challengers' fits on the subset (see below): only to compare them.
  Fitting_settings medium = s;
  medium.energy_tolerance = (std::max)(s.energy_tolerance, 1e-6);
  medium.force_tolerance = (std::max)(s.force_tolerance, 1e-3);
  medium.maximum_iterations = (std::min<std::size_t>)(s.maximum_iterations, 30);
  // A rough fit of `m` on the rough subset (the same points for every
  // candidate: same seed and subset size), with its mean squared distance there.
  std::size_t candidate_iterations = 0;
  Fitting_status status;
  auto rough_fit = [&](const Model& m, double& distance) {
    Fitter candidate(points, m, rough, point_map);
    status = candidate.run(visitor, callback, Fitting_phase::Subset);
    candidate_iterations += status.iterations;
    distance = candidate.mean_squared_distance(false);
    return candidate.model();
  };
  // Each z-axis choice is fitted roughly, then the similar superquadrics of
  // the closest (see below); the closest of all goes on.
  Model start_model = make_initial_model(initial, 2);
  if(all_axes)
  {
    double best_distance = HUGE_VAL;
    auto consider = [&](const Model& m) {
      double d;
      const Model fitted = rough_fit(m, d);
      if(d < best_distance) // strict: ties keep the earlier candidate, deterministically
      {
        best_distance = d;
        start_model = fitted;
      }
    };
    for(int z_axis = 0; z_axis < 3 && !status.aborted; ++z_axis)
      consider(make_initial_model(initial, z_axis));
    const Model winner = start_model;
    for(int swap = 0; swap < number_of_similar_superquadrics && !status.aborted; ++swap)
      consider(similar_superquadric(winner, swap));
  }
  std::unique_ptr<Fitter> fitter = std::make_unique<Fitter>(points, start_model, s, point_map);
  Fitting_status final_status = status;
  if(!status.aborted)
    final_status = fitter->run(visitor, callback);
  // Partial views often leave the fit in the basin of a similar superquadric
  // (its z axis exchanged with x or y, the exponents swapped, its
  // cross-section turned by 45 degrees, or both; see similar_superquadric()), so the
  // fit is compared with them, as EMS iterates its similarity search: each similar one is
  // fitted roughly; one clearly closer to the rough subset than the fit is
  // fitted on the fit's subset, then, if closer there, on all points, and
  // kept if it ends closer to all points (by more than 1 % of the mean
  // squared distance, everywhere). At most three rounds.
  if(all_axes)
  {
    double current = fitter->mean_squared_distance(true);
    for(int round = 0; round < 3 && !final_status.aborted && !final_status.timed_out; ++round)
    {
      const Model fitted = fitter->model();
      double reference;
      {
        Fitter probe(points, fitted, rough, point_map);
        reference = probe.mean_squared_distance(false);
      }
      std::unique_ptr<Fitter> better;
      for(int swap = 0; swap < number_of_similar_superquadrics && !status.aborted; ++swap)
      {
        double d;
        const Model m = rough_fit(similar_superquadric(fitted, swap), d);
        // Clearly closer: a rough fit of the subset alone beats the full
        // fit there by a little even in the same basin.
        if(status.aborted || !(d < 0.8 * reference))
          continue;
        // Fitted on the fit's subset first (with looser tolerances: only to
        // compare): only one that ends closer there goes on to all points (a
        // few hundred points can be fitted closely by a superquadric that is
        // far from the rest of a partial view).
        std::unique_ptr<Fitter> challenger = std::make_unique<Fitter>(points, m, medium, point_map);
        Fitting_status st = challenger->run(visitor, callback, Fitting_phase::Subset);
        candidate_iterations += st.iterations;
        if(!st.aborted)
        {
          Fitter& best = better ? *better : *fitter;
          if(!(challenger->mean_squared_distance(false) < 0.99 * best.mean_squared_distance(false)))
            continue;
          challenger = std::make_unique<Fitter>(points, challenger->model(), s, point_map);
          st = challenger->run(visitor, callback);
          candidate_iterations += st.iterations;
        }
        if(st.aborted)
        {
          status.aborted = true;
          continue;
        }
        const double full = challenger->mean_squared_distance(true);
        if(full < 0.99 * current) // by more than 1 %: not the same rest state again
        {
          current = full;
          better = std::move(challenger);
          final_status.converged = st.converged;
        }
      }
      final_status.aborted = final_status.aborted || status.aborted;
      if(!better)
        break;
      fitter = std::move(better);
    }
  }
  final_status.iterations += candidate_iterations;
  final_status.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  Fit_result<Geom_traits> result{fitter->model(), initial, compute_fit_metrics(*fitter, initial, final_status),
                                 fitter->chart_meshes()};
  if(reference != nullptr)
    result.metrics.chamfer_distance = symmetric_chamfer_distance(result.meshes, *reference);
  return result;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_FIT_BLENDED_SHAPE_H
