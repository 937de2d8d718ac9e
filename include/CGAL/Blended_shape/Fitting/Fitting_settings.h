// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_FITTING_SETTINGS_H
#define CGAL_BLENDED_SHAPE_FITTING_FITTING_SETTINGS_H

#include <CGAL/Blended_shape/parameters.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <cmath>
#include <cstddef>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeFitting
/// How the dynamics `dq/dt = f_q` (eq. 7) are integrated.
enum class Integrator
{
  /// The paper's explicit first-order dynamics: `q <- q + dt f_q` with
  /// `dt = 1 / lambda_max(J^T J)`, the largest step that is stable for the
  /// linearized dynamics, halved until the step is accepted (see Deformable_model_fitter::step()).
  Explicit,
  /// An implicit (damped Gauss-Newton, Levenberg-Marquardt) step of the same dynamics with the
  /// same correspondences: `(J^T J + lambda diag(J^T J)) dq = J^T r`, within a box trust
  /// region (Deformable_model_fitter::maximum_step). Same rest states, far fewer iterations. The default.
  Gauss_newton
};

/// \ingroup PkgBlendedShapeFitting
/// Down-weighting of far points (stray points of real scans).
enum class Robust_weighting
{
  None,  ///< every point pulls with weight 1 (the paper's least squares)
  /// Cauchy weights `w_i = 1 / (1 + (r_i / c)^2)`, recomputed every iteration from the
  /// distances `r_i` to the model, with `c` = cauchy_scale() of the `r_i`.
  Cauchy,
  /// The weight of each point is its probability of being an inlier of a
  /// mixture of Gaussian noise about the surface and strays spread uniformly,
  /// whose parameters are re-estimated every iteration (see Robust_loss). The default.
  Mixture
};

/*!
\ingroup PkgBlendedShapeFitting
Everything that steers a fit, with its defaults: the member initializers
below are the only place they are written. Every member can be given as a
named parameter, read by settings_from_named_parameters(), which the entry
points that take named parameters (fit_superquadric()) use.
*/
struct Fitting_settings
{
  Integrator integrator = Integrator::Gauss_newton; ///< the integration scheme
  /// Iterations over all phases (named parameter `CGAL::parameters::number_of_iterations`).
  std::size_t maximum_iterations = 100;
  double energy_tolerance = 1e-10;        ///< relative energy decrease of one step
  double force_tolerance = 1e-6;          ///< largest scaled parameter force, see Step_report::scaled_force
  std::size_t steady_iterations = 2;      ///< consecutive steps at rest that end a phase
  /// A model that cannot represent the data (one superquadric for a mug)
  /// comes to rest with data forces that balance but do not vanish, while its
  /// closest points keep creeping: the energy then drops by a tiny fraction
  /// per step for hundreds of steps. That is a rest state too (it is where
  /// the split decision of sec. 5.4 acts): a step that lowers the energy by
  /// at most this fraction counts as at rest whatever the forces. 0: only
  /// vanishing forces (`energy_tolerance` and `force_tolerance`) are a rest state.
  double rest_tolerance = 1e-4;
  /// A step whose trials the true energy refuses (with the trial's closest
  /// points) although, at the step's fixed correspondences, each promised
  /// to lower it by at most this fraction, counts as at rest: near a rest
  /// state the point-to-plane model promises a little that the moving
  /// closest points (and the robust loss's re-estimated parameters) take
  /// back, and the damping would otherwise grow by a factor of 8 a trial
  /// until the step is negligible, several steps of two closest-point sweeps
  /// each. 0: only that growth ends such steps. The fits of part evolution
  /// set it to 0 (see Part_evolution).
  double settling_tolerance = 1e-3;
  int mesh_resolution = 10;               ///< chart tessellation (rings from pole to equator)
  int projection_iterations = 20;         ///< at most this many Gauss-Newton steps from a start to the closest point on the surface
  /// Where the foot points of a blended model (one with blends) are not
  /// known yet (the fitter's first closest-point sweep, or after
  /// set_model()), each point is projected onto the surface from the
  /// closest point of the chart tessellation and from each of its 4 nearest
  /// of this many points spread over the surface by area, and the closest
  /// result wins: a blend's strip, narrow in its chart, can span a large curved
  /// piece of surface that the tessellation misses (see the manual, Closest
  /// Points of a Blended Model). 0: the tessellation alone. Models without
  /// blends always use the tessellation alone. At most 1e7. The fits of
  /// part evolution set it to 0 (see Part_evolution).
  std::size_t projection_start_samples = 4000;
  std::size_t subset_size = 4000;         ///< points used before the all-points phase (0: all from the start)
  /// Chooses the subset (named parameter `CGAL::parameters::random_seed`).
  unsigned int random_seed = 0;
  bool rigid_first = false;               ///< parameter scheduling: translation and rotation alone first
  std::size_t rigid_iterations = 5;       ///< at most this many rigid-only steps
  Robust_weighting robust_weighting = Robust_weighting::Mixture; ///< weighting of far points
  /// With robust weighting, the scale of the loss (the mixture's noise
  /// `sigma`, Cauchy's `c`; see Robust_loss) is kept at most this fraction of
  /// the diameter of the points: far from the rest state one broad Gaussian
  /// would explain the inliers and the nearby strays alike, and the strays
  /// would pull the model towards them.
  double noise_ceiling = 0.02;
  /// The same ceiling in the rough fits with which the multistart search
  /// of fit_superquadric() compares its starts (Superquadric_multistart_search:
  /// at most 10 steps from each start, far from any rest). With the ceiling
  /// of the full fits, a rough fit of a cloud of uneven density (the dense
  /// cap and sparse side of a scanned cylinder) is pulled by the points near
  /// its start alone, and none reaches the basin of the shape that holds
  /// the whole cloud (see the manual, Robust Weights). The candidates are
  /// compared with capped distances, so strays still decide nothing. The part
  /// fits of part evolution keep `noise_ceiling` (see Part_evolution).
  double candidate_noise_ceiling = 0.05;
  /// Shape lengths (Parameter_kind::Length, e.g. semi-axes) are kept at most this
  /// factor times the diameter of the points about their centroid (twice the
  /// largest distance to it; unlike a bounding box, it does not depend on the
  /// orientation of the cloud): with one view of an object nothing else stops
  /// the model from growing where there is no data.
  double maximum_size_factor = 1.;
  /// The loose spring of sec. 3.5 that holds the placement of each added
  /// component of a blended model (relative to its parent) to where it was
  /// when the fit started: its stiffness per parameter is this fraction of
  /// the mean stiffness the data give that placement's translation or
  /// quaternion at the first step. It keeps the join good where the data
  /// leave a placement free (a hole turning about its axis, a part sliding
  /// along its base) and biases the rest by about this fraction of the
  /// distance moved. 0: no spring.
  double placement_stiffness = 0.01;
  /// The weight of the model's surface area in the fit (see the manual,
  /// Compact Models). A point sampled from a surface of area `A` costs
  /// `ln A` to place on it, besides its distance to it: the fit minimizes
  /// `(N/2) ln E + area_weight N ln(A + A_0)`, `E` the data energy of the
  /// `N` points, `A` the area of the model's surface and `A_0 = N s^2` the
  /// area the points cover (`s` their median spacing; it keeps a model from
  /// shrinking to a line, whose area term would fall without bound). Each
  /// step takes the term as `lambda A` with `lambda = 2 area_weight E /
  /// (A + A_0)` at the step's start: the same rest states, with least
  /// squares' steps. Where no point pulls (the unseen side and the margins
  /// of a single view) the surface shrinks instead of growing to the size
  /// cap; where points pull it hardly moves: on a fit at the noise the
  /// pressure is that of the noise. 0: no area term (the paper's fit); 0.3
  /// keeps single views compact (the manual's measurements).
  double area_weight = 0.;
  /// Seconds (named parameter `CGAL::parameters::maximum_running_time`).
  double maximum_running_time = HUGE_VAL;
  /// Threads of the closest-point sweeps and of the assembly of the normal
  /// equations (with TBB; without, the fit runs on one core): 0 for all
  /// cores; more than TBB can run, as many as it can. The results are
  /// bit-identical whatever the number.
  std::size_t number_of_threads = 0;
};

/*!
\ingroup PkgBlendedShapeFitting
The settings of a fit given by the named parameters `np`; a setting not
given keeps the default of Fitting_settings. Every member of
Fitting_settings is read: from `CGAL::parameters`, `number_of_iterations`
(Fitting_settings::maximum_iterations), `random_seed` and
`maximum_running_time`; from `Blended_shapes::parameters`, the others under
their member names. Other parameters in `np` are ignored.
*/
template <class NamedParameters = CGAL::parameters::Default_named_parameters>
Fitting_settings settings_from_named_parameters(const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  Fitting_settings s;
  // CGAL's own names
  s.maximum_iterations = choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), s.maximum_iterations);
  s.random_seed = choose_parameter(get_parameter(np, CGAL::internal_np::random_seed), s.random_seed);
  s.maximum_running_time = choose_parameter(get_parameter(np, CGAL::internal_np::maximum_running_time), s.maximum_running_time);
  // the package's, one per member of the same name (internal/parameter_names.h)
  internal::read_settings(s, np);
  return s;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_FITTING_SETTINGS_H
