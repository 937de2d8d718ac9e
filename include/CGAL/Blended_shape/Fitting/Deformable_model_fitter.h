// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_DEFORMABLE_MODEL_FITTER_H
#define CGAL_BLENDED_SHAPE_FITTING_DEFORMABLE_MODEL_FITTER_H

#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>
#include <CGAL/Blended_shape/Fitting/Closest_point_locator.h>
#include <CGAL/Blended_shape/Fitting/Fitting_settings.h>
#include <CGAL/Blended_shape/Fitting/Robust_loss.h>
#include <CGAL/Blended_shape/Fitting/Fitting_visitor.h>
#include <CGAL/Blended_shape/Fitting/internal/Box_constrained_step.h>
#include <CGAL/Blended_shape/Fitting/internal/chart_mesh_deviation_bound.h>
#include <CGAL/Blended_shape/Fitting/internal/Point_blocks.h>
#include <CGAL/Blended_shape/Fitting/internal/sampled_projection_starts.h>
#include <CGAL/Blended_shape/Fitting/internal/Surface_area.h>
#include <CGAL/Blended_shape/IO/check_points.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>
#include <CGAL/Blended_shape/internal/point_spacing.h>

#include <CGAL/Bbox_3.h>
#include <CGAL/property_map.h>

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeFitting
/// What one iteration did.
struct Step_report
{
  std::size_t points_used = 0; ///< the points whose forces the step used (the subset or all)
  /// The true energy `(1/2) sum_i rho(|p_i - x(u_i)|)` at the closest points
  /// `u_i` of the model before the step (`rho` of Robust_loss: `d^2` without
  /// robust weighting), plus the energies of the placement springs and of the
  /// area term (Fitting_settings::placement_stiffness, area_weight).
  double energy_before = 0.;
  double energy_after = 0.;   ///< the same, with the closest points of the new model
  /// The energy of the linearized dynamics at the fixed correspondences (u_i, n_i, w_i)
  /// of the step, `(1/2) sum_i w_i (n_i . (p_i - x(u_i)))^2`, before the step
  /// (plus the springs' and the area term's, as for `energy_before`).
  double fixed_energy_before = 0.;
  double fixed_energy_after = 0.; ///< the same energy after the step
  /// `max_k |f_q[k]| / sqrt(2 E (J^T J)[k][k])`: the largest cosine between the residual
  /// and a parameter direction; 0 at a rest state, scale-free.
  double scaled_force = 0.;
  bool accepted = false;      ///< whether the parameters moved
  /// No step can lower the energy any more: the proposed change is negligible, the
  /// damping (Gauss-Newton) or the step-size reduction (explicit) is exhausted, or the
  /// trials the true energy refused promised at most Fitting_settings::settling_tolerance.
  bool stalled = false;
  /// Gauss-Newton: whether the step of the last attempt is the maximum of the
  /// quadratic model in the box trust region (see maximum_step). False when
  /// the projected Gauss-Seidel sweeps that find it, where the free step
  /// leaves the box, stopped at 100 (badly conditioned normal equations):
  /// the step is then the best one they found, which still lowers the
  /// linearized energy.
  bool step_in_box_converged = true;
};

/// \ingroup PkgBlendedShapeFitting
/// One data force (eq. 8): point `index` is attached to the model point
/// x(`chart_point`), its closest point, and pulls with `force` = w n n^T (p - x).
template <class GeomTraits>
struct Data_force
{
  std::size_t index;                         ///< index of the data point in the input
  Chart_point chart_point;                   ///< its closest point u on the model
  typename GeomTraits::Point_3 model_point;  ///< x(u)
  typename GeomTraits::Vector_3 force;       ///< w n n^T (p - x(u))
  double weight;                             ///< w: 1, or the robust weight (Robust_loss::weight())
  double normal_distance;                    ///< n . (p - x(u)): how far out of the surface the point is
};

/// \ingroup PkgBlendedShapeFitting
/// How a run() ended.
struct Fitting_status
{
  std::size_t iterations = 0; ///< iterations done (accepted or not)
  /// Of `iterations`, those whose step used all points (the others used a
  /// subset of them: the subset phase, the short fits that compare starts).
  std::size_t iterations_on_all_points = 0;
  bool converged = false;  ///< steady state reached on all points
  bool aborted = false;    ///< the callback returned false
  bool timed_out = false;  ///< maximum_running_time reached
  double seconds = 0.;     ///< wall time of run()
};

/*!
\ingroup PkgBlendedShapeFitting

The estimation engine of sec. 5.1-5.3 with explicit steps: data forces from
closest points (eq. 8), one integration step of the dynamics (eq. 7), and a
run loop with phases and steady-state detection.

Each step: (1) the chart meshes are positioned by the current model and the
AABB tree of Closest_point_locator is rebuilt over them when searched; (2)
each data point in use is attached to its closest mesh point, whose chart,
face and barycentric coordinates give a domain point, refined into the
closest point `u_i` on the analytic surface by a few safeguarded
Gauss-Newton steps on the chart coordinates (in the sweeps of trial steps,
from the point's previous foot point instead; the mesh is then only searched
for points closer than the foot point found, and projected from where it has
one more than a mesh spacing away); the model and its Jacobian `L(u_i)` are evaluated
there analytically, and the data force is
`f_i = w_i n_i n_i^T (p_i - x(u_i))` (stiffness 1, `n_i` the model
normal at `u_i`): the paper's force `p_i - x(u_i)` (eq. 8) projected on the
normal. Where `u_i` is the exact closest point the two are equal; the
projection removes the tangential error of locating `u_i` on a tessellation,
which would otherwise pin model points to data points tangentially and slow
the fit down like point-to-point ICP;
(3) the integrator moves `q` with these correspondences (`u_i`, `n_i`,
`w_i`) fixed (Gauss-Newton: within the box trust region of maximum_step);
a step is only accepted if it lowers the energy
`E = (1/2) sum_i w_i (n_i . (p_i - x(u_i)))^2` at these correspondences and
does not increase the true energy (see step()).

Phases (run()): optionally rigid-only first (parameter scheduling), then all
parameters on a fixed random subset of `subset_size` points (the iterations
far from the rest state do not need every point), then all parameters on all
points until steady state: the relative energy decrease of a step is below
`energy_tolerance` and the scaled force below `force_tolerance` for
`steady_iterations` consecutive steps.

The per-point work of (2), in every sweep, and the sums of the linear system
of (3) run on `Fitting_settings::number_of_threads` threads (with TBB), with
results that are bit-identical at any number of threads: the points are
summed in fixed blocks of 256, whose sums are added in block order.

\tparam Model a model of the concept `DeformableModel`: Deformable_model (one
  primitive) or Deformable_blended_model (a blended shape of fixed structure).
*/
template <class Model>
class Deformable_model_fitter
{
public:
  typedef typename Model::Geom_traits Geom_traits;  ///< the kernel
  typedef typename Geom_traits::Point_3 Point_3;    ///< the point type
  typedef typename Geom_traits::Vector_3 Vector_3;  ///< the vector type
  typedef Chart_mesh<Geom_traits> Chart_mesh_type;  ///< the tessellation of one chart

  /// A fitter of `initial_model` to `points` (copied, as `double`), with the
  /// chart meshes of the model at `settings.mesh_resolution` and their Closest_point_locator.
  /// \throws Input_error if the points are unusable (see check_points()).
  /// \throws std::invalid_argument on invalid settings.
  template <class PointRange, class PointMap = CGAL::Identity_property_map<Point_3>>
  Deformable_model_fitter(const PointRange& points, const Model& initial_model,
                          const Fitting_settings& settings = Fitting_settings(),
                          PointMap point_map = PointMap())
    : m_model(initial_model), m_settings(settings), m_blocks(settings.number_of_threads)
  {
    check_points(points, point_map);
    check_settings(settings);
    read_points(points, point_map);
    choose_subset();
    set_area_weight();
    restructure(initial_model); // what depends on the model: the same as for a later structure change
  }

  /// The current model: that of the last accepted step.
  const Model& model() const { return m_model; }
  /// The settings given to the constructor.
  const Fitting_settings& settings() const { return m_settings; }
  /// The number of input points.
  std::size_t number_of_points() const { return m_points.size(); }
  /// The diagonal of the bounding box of the points (the length scale of the fit).
  double bounding_box_diagonal() const { return m_diagonal; }
  /// The chart meshes, positioned by the current model.
  const std::vector<Chart_mesh_type>& chart_meshes() const { return m_charts; }

  /// Replaces the model (same kind of parameters and charts, e.g. after a
  /// user edit); the next step recomputes all correspondences. For a model
  /// of another structure, see restructure().
  void set_model(const Model& model)
  {
    if(model.number_of_parameters() != m_model.number_of_parameters() ||
       model.number_of_charts() != m_model.number_of_charts())
      throw std::invalid_argument("Deformable_model_fitter::set_model: the model structure differs");
    m_model = model;
    m_rest = m_model.parameters(); // the springs hold the placements to where they are now
    m_spring.clear();
    refresh();
  }

  /*!
  Goes on with `model`, whose structure may differ from the current one's:
  other numbers of parameters, charts, components or blends, as after
  Blended_shape::split(), Blended_shape::add_hole() or
  Blended_shape::remove_component() (sec. 4) applied to the fitted shape.

  Kept: the points, the settings and the subset of the first phase (they do
  not depend on the model). Rebuilt for `model`: everything sized by its
  parameter vector or its charts (the chart meshes and their
  Closest_point_locator, the set of moving parameters, the rest state of the
  placement springs, whose stiffness the next step sets anew). Reset, as it
  no longer applies: the correspondences, the Gauss-Newton damping and the
  explicit step-size reduction (learned on another energy), and the choice
  of points and parameters (all points, every parameter).

  Afterwards the fitter is in the state of a fitter constructed anew from
  the same points and settings with `model`: the next steps and run() give
  the same results, without reading the points again.
  */
  void restructure(const Model& model)
  {
    m_model = model;
    m_locator.reset(); // it keeps pointers to the chart meshes, rebuilt here
    m_charts.clear();
    m_charts.reserve(m_model.number_of_charts());
    for(std::size_t c = 0; c < m_model.number_of_charts(); ++c)
      m_charts.emplace_back(c, m_model.chart_domain(c), m_settings.mesh_resolution);
    position_meshes(m_model);
    m_locator = std::make_unique<Closest_point_locator<Geom_traits>>(m_charts);
    m_locator->set_face_mask(&m_kept_faces);
    m_tree_outdated = true;
    m_correspondences = Correspondences();
    m_inherited.reset();
    m_scratch = Correspondences();
    m_correspondences_valid = m_correspondences_all = false;
    m_start.clear();
    m_start_valid.clear();
    m_use_all = true;
    m_active_parameters.assign(m_model.number_of_parameters(), true);
    m_rest = m_model.parameters();
    m_spring.clear();
    m_lambda = initial_damping;
    m_dt_scale = 1.;
    m_area = m_data_area > 0. ? internal::Surface_area<Model>(m_model, area_resolution) : internal::Surface_area<Model>();
  }

  /*!
  Starts the next closest-point sweep of all points from the foot points
  `other` found at its last sweep of all points (its model's chart points,
  each projected onto this model's surface and checked against the
  tessellation as at every step), instead of from the tessellation alone.

  For a fitter of a model that `other`'s became by a structure change that
  keeps every chart of `other`'s model as the same chart of this one, with
  the same points: Blended_shape::split() and Blended_shape::add_hole() add
  components after the others. The surface does not move at such a change
  (`h = 0`), so the sweep finds the foot points of `other` again (where they
  are still on the surface), where a search from the tessellation misses
  some, by as much as a split gains (measured: about 4 % of the energy of a
  mug scan). Without effect if `other` has no such sweep.

  A foot point that is no longer on the surface may still be, at the same
  chart coordinates, in another chart: `moved_to` (if not empty: one entry
  per chart of `other`'s model) gives, for chart `g`, the chart of this
  model to look in, or `std::size_t(-1)` for none. After
  Blended_shape::split() these are the charts of the new component (a copy
  of the split one, placed where it is) for the split component's charts:
  the inside of the region moves to the copy, at the same chart points.
  Without them, the foot points of the points there are searched for from
  the tessellation again, and the split model starts farther from the
  points than the model it was split from (measured on a mug scan: by 9 %
  of the energy, more than the split could gain).

  \throws std::invalid_argument if `other` has other points or more charts,
          or `moved_to` has not one entry per chart of `other`'s model or names
          a chart this model does not have.
  */
  void start_from_foot_points_of(const Deformable_model_fitter& other,
                                 const std::vector<std::size_t>& moved_to = std::vector<std::size_t>())
  {
    const std::string who = "Deformable_model_fitter::start_from_foot_points_of: ";
    if(other.m_points != m_points || other.m_model.number_of_charts() > m_model.number_of_charts())
      throw std::invalid_argument(who + "the fitters have other points, or the other model has more charts; give "
                                        "the fitter this one's model was split from");
    if(!moved_to.empty() && moved_to.size() != other.m_model.number_of_charts())
      throw std::invalid_argument(who + "moved_to has " + std::to_string(moved_to.size()) +
                                  " entries; give one per chart of the other model (" +
                                  std::to_string(other.m_model.number_of_charts()) + ")");
    for(std::size_t g : moved_to)
      if(g != std::size_t(-1) && g >= m_model.number_of_charts())
        throw std::invalid_argument(who + "moved_to names chart " + std::to_string(g) + ", but the model has " +
                                    std::to_string(m_model.number_of_charts()) + " charts");
    m_inherited.reset();
    if(other.m_correspondences_valid && other.m_correspondences_all)
    {
      m_inherited = other.m_correspondences;
      if(!moved_to.empty())
        for(Chart_point& u : m_inherited->u)
          if(moved_to[u.chart] != std::size_t(-1) && !m_model.is_on_surface(u))
          {
            const Chart_point there(moved_to[u.chart], u.x, u.y);
            if(m_model.is_on_surface(there))
              u = there;
          }
    }
    m_correspondences_valid = false;
  }

  /*!
  Starts the next sweep of all points from the chart points `starts` (one
  per point, in the order of the points; e.g. the foot points of nearby
  points in a fit of some of them): each projection starts there, and the
  tessellation is searched only for closer points, as after a step. A
  start that is not on the surface is searched for from the tessellation.
  \throws std::invalid_argument if `starts` has not one entry per point or
          names a chart the model does not have.
  */
  void start_from_chart_points(const std::vector<Chart_point>& starts)
  {
    const std::string who = "Deformable_model_fitter::start_from_chart_points: ";
    if(starts.size() != m_points.size())
      throw std::invalid_argument(who + std::to_string(starts.size()) + " chart points for " +
                                  std::to_string(m_points.size()) + " points; give one per point");
    for(const Chart_point& u : starts)
      if(u.chart >= m_model.number_of_charts())
        throw std::invalid_argument(who + "chart " + std::to_string(u.chart) + " named, but the model has " +
                                    std::to_string(m_model.number_of_charts()) + " charts");
    Correspondences c;
    c.u = starts;
    m_inherited = std::move(c);
    m_correspondences_valid = false;
  }

  /// Restricts the next steps to all points (`true`) or to the subset.
  void use_all_points(bool all) { m_use_all = all; }
  /// Lets only the pose (translation and rotation) move (`true`) or every parameter.
  void move_pose_only(bool pose_only)
  {
    for(std::size_t i = 0; i < m_active_parameters.size(); ++i)
      m_active_parameters[i] = !pose_only || m_model.is_pose_parameter(i);
  }

  /*!
  One iteration. With the correspondences of the current model (closest
  points, normals and robust weights, kept from the previous step), the
  integrator proposes parameters (clamped to the bounds, the shape lengths
  also to `maximum_size_factor` times the bounding-box diagonal); a proposal is
  accepted only if it lowers the energy at these fixed correspondences (by
  more than `energy_tolerance`, relatively: a smaller decrease means a rest
  state, and the model stays put) and does not increase the true energy (with
  the closest points of the proposed model, which the next step then reuses,
  so an accepted step costs one closest-point sweep). Otherwise the damping
  grows (Gauss-Newton, up to 8 tries; not at a rest state, which would only
  leave the next phase with needlessly damped first steps) or the time step
  halves (explicit, up to 12 tries) and it tries again; at most two trials of
  a step get a closest-point sweep. A Gauss-Newton proposal the model
  refuses (a blending region out of its chart) holds the blending-region
  parameters for the step's remaining tries instead of raising the damping.
  A step whose swept trials the true energy all refused, each having
  promised at most `settling_tolerance` of it, stalls: a rest state.
  */
  Step_report step()
  {
    const std::vector<std::size_t>& active = m_use_all ? m_all : m_subset;
    Step_report report;
    report.points_used = active.size();
    if(!m_correspondences_valid || m_correspondences_all != m_use_all)
      set_correspondences(m_use_all ? attach_all_points() : attach(m_model, active), m_use_all);
    const Correspondences& corr = m_correspondences;
    const Eigen::VectorXd q = m_model.parameters();

    Normal_equations system = assemble_normal_equations(active, corr);
    const double area_energy_before = add_area_term(system);
    const double spring_energy_before = add_placement_springs(system, q, active.size());
    report.energy_before = true_energy(corr.distance, corr.loss) + spring_energy_before + area_energy_before;
    const std::vector<bool> free_parameter = freeze_parameters_at_bounds(system, q);
    report.fixed_energy_before = report.fixed_energy_after = system.energy;
    report.energy_after = report.energy_before;
    report.scaled_force = scaled_force(system, free_parameter, active.size());

    Step_trials trials{active, corr, q, system};
    if(m_settings.integrator == Integrator::Gauss_newton)
      damped_gauss_newton_step(trials, report);
    else
      explicit_step(trials, report);
    report.stalled = !report.accepted &&
                     (trials.negligible || m_lambda >= 1e10 || m_dt_scale <= 1e-8 || !(report.energy_before > 0.) ||
                      (trials.sweeps > 0 && trials.swept_decrease <= m_settings.settling_tolerance));
    if(!report.accepted)
      position_meshes(m_model); // a rejected trial left the meshes where it was
    return report;
  }

  /*!
  Iterates through the phases until steady state on all points, the
  iteration limit, the time limit, or until `callback` (called before each
  iteration with the fraction of the iteration budget spent) returns false.
  The model is always a valid model of the last accepted step.
  With `last_phase` = `Fitting_phase::Subset` (or `Rigid`), it stops when that
  phase comes to rest (used to compare several starts cheaply).
  */
  template <class Visitor = Default_fitting_visitor>
  Fitting_status run(Visitor&& visitor = Visitor(),
                     const std::function<bool(double)>& callback = std::function<bool(double)>(),
                     Fitting_phase last_phase = Fitting_phase::All_points)
  {
    const auto start = std::chrono::steady_clock::now();
    Fitting_status status;
    Fitting_phase phase = first_phase();
    auto enter = [&](Fitting_phase p) {
      phase = p;
      enter_phase(p);
      visitor.on_phase(p, status.iterations);
    };
    enter(phase);
    std::size_t steady = 0, in_phase = 0;
    bool rechecked = false; // see recheck_correspondences(): once, at the first rest state on all points
    while(status.iterations < m_settings.maximum_iterations)
    {
      if(callback && !callback(double(status.iterations) / double(m_settings.maximum_iterations)))
      {
        status.aborted = true;
        break;
      }
      if(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
         m_settings.maximum_running_time)
      {
        status.timed_out = true;
        break;
      }
      const Step_report r = step();
      ++status.iterations;
      if(r.points_used == m_all.size())
        ++status.iterations_on_all_points;
      ++in_phase;
      visitor.on_iteration(status.iterations, r.energy_after, r.points_used);
      steady = is_at_rest(r) ? steady + 1 : 0;
      const bool phase_done = steady >= m_settings.steady_iterations ||
                              (phase == Fitting_phase::Rigid && in_phase >= m_settings.rigid_iterations);
      if(!phase_done)
        continue;
      steady = 0;
      in_phase = 0;
      if(phase != Fitting_phase::All_points && phase == last_phase)
        break;
      if(phase != Fitting_phase::All_points)
        enter(next_phase(phase));
      else if(rechecked || !recheck_correspondences())
      {
        status.converged = true;
        visitor.on_phase(Fitting_phase::Steady_state, status.iterations);
        break;
      }
      else
        rechecked = true;
    }
    move_pose_only(false);
    use_all_points(true);
    status.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return status;
  }

  /// The closest point (foot point) on the current model of every point, in
  /// the order of the points: the chart points of forces(), without the forces.
  std::vector<Chart_point> foot_points() { return correspondences_of_all_points().u; }

  /// The data forces of every point on the current model (eq. 8).
  std::vector<Data_force<Geom_traits>> forces()
  {
    const Correspondences& corr = correspondences_of_all_points();
    std::vector<Data_force<Geom_traits>> result;
    result.reserve(m_all.size());
    for(std::size_t k = 0; k < m_all.size(); ++k)
    {
      const Point_3 x = m_model.point(corr.u[k]);
      const double w = corr.loss.weight(corr.distance[k]);
      const double r = corr.normal[k].dot(m_points[k] - Eigen::Vector3d(x.x(), x.y(), x.z()));
      const Eigen::Vector3d f = (w * r) * corr.normal[k];
      result.push_back({k, corr.u[k], x, Vector_3(f[0], f[1], f[2]), w, r});
    }
    return result;
  }

  /// The robust loss of the current model's distances to all points (see Robust_loss).
  const Robust_loss& robust_loss() { return correspondences_of_all_points().loss; }

  /// Whether each point, in the order of the points, is judged stray at the
  /// current model (Robust_loss::is_stray() of its distance; never without robust weighting).
  std::vector<bool> stray_points()
  {
    const Correspondences& corr = correspondences_of_all_points();
    std::vector<bool> stray(corr.distance.size());
    for(std::size_t k = 0; k < stray.size(); ++k)
      stray[k] = corr.loss.is_stray(corr.distance[k]);
    return stray;
  }

  /// The mean squared distance from the points in use (all, or the subset)
  /// to their closest model points: comparable between fits of the same points.
  /// Each squared distance is capped at `truncation^2`: then the points
  /// farther than `truncation` (strays) add the same to every fit.
  double mean_squared_distance(bool all_points, double truncation = HUGE_VAL)
  {
    // those of the last step, if they are of the subset (as after a run() that stopped after the subset phase)
    const Correspondences& corr = all_points ? correspondences_of_all_points()
                                             : (m_correspondences_valid && !m_correspondences_all)
                                                 ? m_correspondences
                                                 : (m_scratch = attach(m_model, m_subset));
    double sum = 0.;
    for(double d : corr.distance)
      sum += CGAL::square((std::min)(d, truncation));
    return corr.distance.empty() ? 0. : sum / double(corr.distance.size());
  }

  /// The energy of the placement springs (see Fitting_settings::placement_stiffness)
  /// of `model` for `points_used` points (0 before the first step, which sets the springs).
  double placement_spring_energy(const Model& model, std::size_t points_used) const
  {
    return spring_energy(model.parameters(), points_used);
  }

  /// The input points, as read (in their original order).
  const std::vector<Eigen::Vector3d>& points() const { return m_points; }

  /// The smallest size (a shape length bounded below by 0 or more, e.g. a
  /// semi-axis) a fit gives, relative to the diameter of the points about
  /// their centroid (see Fitting_settings::maximum_size_factor for the largest).
  static constexpr double minimum_size_ratio = 1e-9;

  /// The box trust region of a Gauss-Newton step: no parameter changes by
  /// more than this in one step (a length: this fraction of the diameter of
  /// the points about their centroid; exponents, quaternion components and
  /// blending-region parameters: this value). A parameter the points hardly
  /// constrain (an exponent of a face-like superquadric at its bound, whose
  /// faces do not depend on it) has a tiny diagonal in `J^T J`, so the
  /// damped step moves it by far more than its linearization holds and the
  /// step fails however the damping grows: the fit stalls before it moves
  /// at all (measured: the split models of a human body's front view).
  static constexpr double maximum_step = 0.25;

  /// The resolution of the tessellations the area term measures the surface on.
  static constexpr int area_resolution = 6;

  /// A fit whose root mean square distance is at most this fraction of the
  /// diameter of the points about their centroid fits them to the precision
  /// of the distances (the foot points are found to 1e-12 relatively), far
  /// below any scan's noise: at rest, whatever its last steps changed. Its
  /// energy is rounding, whose relative changes from step to step say
  /// nothing; without this a fit of noise-free points could step on at
  /// random until its iteration limit and call itself not converged.
  static constexpr double exact_fit_ratio = 1e-9;

private:
  // The model's bounds, with shape lengths also bounded by the data's size:
  // sizes (lengths bounded below by 0 or more) from minimum_size_ratio times
  // it (a size shrinking to nothing would make the normals overflow), lengths
  // up to maximum_size_factor times it.
  double lower_bound(std::size_t i) const
  {
    const double b = m_model.parameter_lower_bound(i);
    return is_shape_length(i) && b >= 0. ? (std::max)(b, minimum_size_ratio * m_diameter) : b;
  }
  double upper_bound(std::size_t i) const
  {
    const double b = m_model.parameter_upper_bound(i);
    return is_shape_length(i) ? (std::min)(b, m_settings.maximum_size_factor * m_diameter) : b;
  }
  bool is_shape_length(std::size_t i) const
  {
    return !m_model.is_pose_parameter(i) && m_model.parameter_kind(i) == Parameter_kind::Length;
  }

  // Closest points of the points `active` on `model`: chart points, normals
  // and distances, with the robust loss of these distances.
  struct Correspondences
  {
    std::vector<Chart_point> u;
    std::vector<Eigen::Vector3d> normal;
    std::vector<double> distance;
    Robust_loss loss; // of these distances
  };

  // \throws std::invalid_argument naming the first setting the fit cannot work with.
  static void check_settings(const Fitting_settings& s)
  {
    auto require = [](bool ok, const char* what) {
      if(!ok)
        throw std::invalid_argument(std::string("Deformable_model_fitter: invalid settings: ") + what);
    };
    require(s.mesh_resolution >= 2, "mesh_resolution must be at least 2 (10 is the default)");
    require(s.maximum_iterations >= 1, "maximum_iterations (number_of_iterations) must be at least 1");
    require(s.steady_iterations >= 1, "steady_iterations must be at least 1");
    require(s.projection_iterations >= 1, "projection_iterations must be at least 1");
    require(s.projection_start_samples <= 10000000,
            "projection_start_samples must be at most 1e7 (4000 is the default; 0: the tessellation alone)");
    require(s.energy_tolerance >= 0. && std::isfinite(s.energy_tolerance),
            "energy_tolerance must be a finite number >= 0");
    require(s.force_tolerance >= 0. && std::isfinite(s.force_tolerance),
            "force_tolerance must be a finite number >= 0");
    require(s.rest_tolerance >= 0. && s.rest_tolerance < 1.,
            "rest_tolerance must be in [0, 1) (a relative energy decrease per step; 1e-4 is the default)");
    require(s.settling_tolerance >= 0. && s.settling_tolerance < 1.,
            "settling_tolerance must be in [0, 1) (a relative energy decrease per step; 1e-3 is the default)");
    require(s.noise_ceiling > 0. && s.noise_ceiling <= 1.,
            "noise_ceiling must be in (0, 1] (a fraction of the points' diameter; 0.02 is the default)");
    require(s.candidate_noise_ceiling > 0. && s.candidate_noise_ceiling <= 1.,
            "candidate_noise_ceiling must be in (0, 1] (a fraction of the points' diameter; 0.05 is the default)");
    require(s.maximum_size_factor > 0., "maximum_size_factor must be > 0");
    require(s.placement_stiffness >= 0. && std::isfinite(s.placement_stiffness),
            "placement_stiffness must be a finite number >= 0");
    require(s.area_weight >= 0. && std::isfinite(s.area_weight),
            "area_weight must be a finite number >= 0 (0, the default: no area term; 0.3 keeps single views compact)");
    require(s.maximum_running_time > 0., "maximum_running_time must be > 0 seconds");
  }

  // Copies the points as `double`, with the two length scales of the fit.
  template <class PointRange, class PointMap>
  void read_points(const PointRange& points, PointMap point_map)
  {
    CGAL::Bbox_3 box;
    for(const auto& item : points)
    {
      const Point_3& p = get(point_map, item);
      m_points.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
      box += p.bbox();
    }
    m_diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                           CGAL::square(box.zmax() - box.zmin()));
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for(const Eigen::Vector3d& p : m_points) centroid += p;
    centroid /= double(m_points.size());
    for(const Eigen::Vector3d& p : m_points) m_diameter = (std::max)(m_diameter, 2. * (p - centroid).norm());
  }

  // The phases of run(), in order: rigid (if asked for), the subset (if it
  // is not all points), all points.
  Fitting_phase first_phase() const
  {
    if(m_settings.rigid_first)
      return Fitting_phase::Rigid;
    return m_subset.size() < m_all.size() ? Fitting_phase::Subset : Fitting_phase::All_points;
  }
  Fitting_phase next_phase(Fitting_phase p) const
  {
    if(p == Fitting_phase::Rigid && m_subset.size() < m_all.size())
      return Fitting_phase::Subset;
    return Fitting_phase::All_points;
  }
  void enter_phase(Fitting_phase p)
  {
    move_pose_only(p == Fitting_phase::Rigid);
    use_all_points(p == Fitting_phase::All_points || (p == Fitting_phase::Rigid && !(m_subset.size() < m_all.size())));
    // A phase starts undamped: the damping that ended the last one (grown by
    // the failed steps of its rest state) says nothing about the new energy,
    // and would only slow the new phase's first steps down.
    m_lambda = (std::min)(m_lambda, initial_damping);
    m_dt_scale = 1.;
  }

  // The convergence test of one step of run(): it stalled; or it was
  // accepted with a relative energy decrease and a scaled force under the
  // tolerances (a stationary point); or accepted with a relative energy
  // decrease under `rest_tolerance` (the creeping rest of a shape the model
  // cannot represent, see Fitting_settings::rest_tolerance); or the model
  // fits the points exactly (exact_fit_ratio).
  bool is_at_rest(const Step_report& r) const
  {
    const double decrease = relative_decrease(r);
    const double exact_energy = 0.5 * double(r.points_used) * CGAL::square(exact_fit_ratio * m_diameter);
    return r.stalled || r.energy_after <= exact_energy ||
           (r.accepted && ((decrease <= m_settings.energy_tolerance && r.scaled_force <= m_settings.force_tolerance) ||
                           decrease <= m_settings.rest_tolerance));
  }
  static double relative_decrease(const Step_report& r)
  {
    return (r.energy_before - r.energy_after) / (std::max)(r.energy_before, 1e-300);
  }

  // The linear system of the dynamics at fixed correspondences (eq. 7, 8),
  // point-to-plane: H = J^T W J and g = J^T W r (the parameter force f_q),
  // J's rows the force directions in parameter space L(u_i)^T n_i; the
  // weights w_i, and the energy E = (1/2) sum_i w_i r_i^2 (with the
  // springs' energy once add_placement_springs() has added them).
  struct Normal_equations
  {
    Eigen::MatrixXd H;
    Eigen::VectorXd g;
    std::vector<double> w;
    double energy = 0.;
  };

  // The sums of assemble_normal_equations() over some points (H's lower triangle).
  struct Normal_equation_sums
  {
    Eigen::MatrixXd H;
    Eigen::VectorXd g;
    double energy = 0.;
    Normal_equation_sums& operator+=(const Normal_equation_sums& other)
    {
      H += other.H;
      g += other.g;
      energy += other.energy;
      return *this;
    }
  };

  Normal_equations assemble_normal_equations(const std::vector<std::size_t>& active, const Correspondences& corr) const
  {
    const Eigen::Index n = Eigen::Index(m_model.number_of_parameters());
    Normal_equations system;
    system.w.resize(active.size());
    const Normal_equation_sums zero{Eigen::MatrixXd::Zero(n, n), Eigen::VectorXd::Zero(n), 0.};
    Normal_equation_sums sums = m_blocks.sum_over_blocks(active.size(), zero, [&](std::size_t first, std::size_t last) {
      Normal_equation_sums block = zero;
      Eigen::VectorXd Jn(n);
      std::vector<Eigen::Index> nonzero;
      typename Model::Jacobian L;
      for(std::size_t k = first; k < last; ++k)
      {
        const Point_3 x = m_model.point_and_jacobian(corr.u[k], L);
        const double r = corr.normal[k].dot(m_points[active[k]] - Eigen::Vector3d(x.x(), x.y(), x.z()));
        const double w = system.w[k] = corr.loss.weight(corr.distance[k]);
        Jn.noalias() = L.transpose() * corr.normal[k];
        block.g.noalias() += (w * r) * Jn;
        block.energy += 0.5 * w * r * r;
        // A point of a blended model depends on the few components and blends
        // that reach it: the outer product only over its nonzero entries.
        nonzero.clear();
        for(Eigen::Index i = 0; i < n; ++i)
          if(Jn[i] != 0.)
            nonzero.push_back(i);
        if(2 * Eigen::Index(nonzero.size()) > n)
          block.H.template selfadjointView<Eigen::Lower>().rankUpdate(Jn, w);
        else
          for(std::size_t a = 0; a < nonzero.size(); ++a)
          {
            const double wa = w * Jn[nonzero[a]];
            for(std::size_t b = 0; b <= a; ++b)
              block.H(nonzero[a], nonzero[b]) += wa * Jn[nonzero[b]];
          }
      }
      return block;
    });
    system.H = std::move(sums.H);
    system.g = std::move(sums.g);
    system.energy = sums.energy;
    system.H.template triangularView<Eigen::Upper>() = system.H.transpose();
    return system;
  }

  // The placement springs (sec. 3.5), E_s = (1/2) sum_i N k_i (q_i - rest_i)^2
  // for N points, added to the system (their stiffness set at the first
  // step); returns E_s.
  double add_placement_springs(Normal_equations& system, const Eigen::VectorXd& q, std::size_t points_used)
  {
    if(m_spring.empty())
      set_springs(system.H, points_used);
    const double N = double(points_used);
    for(std::size_t i = 0; i < m_spring.size(); ++i)
      if(m_spring[i] > 0.)
      {
        const Eigen::Index ii = Eigen::Index(i);
        system.H(ii, ii) += N * m_spring[i];
        system.g[ii] -= N * m_spring[i] * (q[ii] - m_rest[ii]);
      }
    const double e = spring_energy(q, points_used);
    system.energy += e;
    return e;
  }

  // The area term (Fitting_settings::area_weight): the fit minimizes
  // (N/2) ln E + w N ln(A + A_0), whose gradient is, times 2 E / N, that of
  // E + lambda A with lambda = 2 w E / (A + A_0): each step adds lambda A to
  // the energy with lambda set from the step's E and A (at rest, the
  // gradient of the logarithmic objective vanishes). A_0 = N s^2, the area
  // the points cover (s: their median spacing), set once for the points;
  // where they coincide, the square of their diameter.
  void set_area_weight()
  {
    m_data_area = 0.;
    if(m_settings.area_weight > 0.)
    {
      const double s = internal::median_spacing(m_points);
      m_data_area = double(m_points.size()) * s * s;
      if(!(m_data_area > 0.))
        m_data_area = CGAL::square(m_diameter);
    }
  }

  // Adds the area term at the current model to the system: sets this
  // step's lambda from the system's (data) energy, adds lambda times the
  // area's gradient and, as its Gauss-Newton matrix, that of the face areas
  // taken as squares (internal::Surface_area); returns its energy lambda A.
  // Called before the springs are added.
  double add_area_term(Normal_equations& system)
  {
    if(m_area.empty())
      return 0.;
    Eigen::VectorXd gradient;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(system.H.rows(), system.H.cols());
    const double a = m_area.area_and_gradient(m_model, gradient, H);
    m_area_lambda = m_settings.area_weight * 2. * system.energy / (a + m_data_area);
    const double e = m_area_lambda * a;
    system.H += m_area_lambda * H;
    system.g -= m_area_lambda * gradient;
    system.energy += e;
    return e;
  }

  // The area term's energy of `model`.
  double area_energy(const Model& model) const { return m_area.empty() ? 0. : m_area_lambda * m_area.area(model); }

  // Parameters held at a bound by a force pushing past it are frozen for
  // this step (an active set): a step computed without the bound and then
  // clamped points the wrong way and only makes the damping grow. So are
  // those move_pose_only() holds. Returns which parameters may move.
  std::vector<bool> freeze_parameters_at_bounds(Normal_equations& system, const Eigen::VectorXd& q) const
  {
    const std::size_t n = m_model.number_of_parameters();
    std::vector<bool> free_parameter = m_active_parameters;
    for(std::size_t i = 0; i < n; ++i)
    {
      const Eigen::Index ii = Eigen::Index(i);
      if((system.g[ii] < 0. && q[ii] <= lower_bound(i)) || (system.g[ii] > 0. && q[ii] >= upper_bound(i)))
        free_parameter[i] = false;
    }
    for(std::size_t i = 0; i < n; ++i)
      if(!free_parameter[i])
      {
        system.H.row(Eigen::Index(i)).setZero();
        system.H.col(Eigen::Index(i)).setZero();
        system.H(Eigen::Index(i), Eigen::Index(i)) = 1.;
        system.g[Eigen::Index(i)] = 0.;
      }
    return free_parameter;
  }

  // Step_report::scaled_force: the largest cosine between the residual and a
  // free parameter direction.
  double scaled_force(const Normal_equations& system, const std::vector<bool>& free_parameter,
                      std::size_t points_used) const
  {
    const double floor = CGAL::square(1e-12 * m_diameter) * double(points_used);
    double result = 0.;
    for(std::size_t i = 0; i < free_parameter.size(); ++i)
    {
      const Eigen::Index ii = Eigen::Index(i);
      if(!free_parameter[i])
        continue;
      const double den = std::sqrt(2. * (system.energy + floor) * system.H(ii, ii));
      if(den > 0.)
        result = (std::max)(result, std::abs(system.g[ii]) / den);
    }
    return result;
  }

  // The trials of one step (see step()): its points, correspondences,
  // parameters and system, and what the trials so far found.
  struct Step_trials
  {
    const std::vector<std::size_t>& active;
    const Correspondences& corr;
    const Eigen::VectorXd& q;
    const Normal_equations& system;
    bool negligible = false; // a trial's decrease was under the tolerance: a rest state
    bool refused = false;    // the model refused the last trial's parameters
    bool regions_held = false; // the blending-region parameters stay as they are (after a refusal)
    int sweeps = 0;          // closest-point sweeps spent on trials
    double swept_decrease = 0.; // the largest relative decrease at fixed correspondences of a swept trial
  };

  // The acceptance test of one proposed change `delta` (clamped to the
  // bounds): it must lower the energy at the step's correspondences, by more
  // than the energy tolerance, and not raise the true energy, measured with
  // the closest points of the trial model (at most two such sweeps a step).
  // On acceptance the trial becomes the model, with these closest points.
  bool try_step(const Eigen::VectorXd& delta, Step_trials& trials, Step_report& report)
  {
    const std::vector<std::size_t>& active = trials.active;
    const Correspondences& corr = trials.corr;
    const std::size_t n = m_model.number_of_parameters();
    Eigen::VectorXd q1 = trials.q + delta;
    for(std::size_t i = 0; i < n; ++i)
      q1[Eigen::Index(i)] = (std::min)((std::max)(q1[Eigen::Index(i)], lower_bound(i)), upper_bound(i));
    Model trial = m_model;
    try
    {
      trial.set_parameters(q1);
    }
    catch(const std::invalid_argument&)
    {
      trials.refused = true; // e.g. a blending region leaving its chart
      return false;
    }
    // (the energies of the terms that depend on the parameters only: the springs, the area)
    const double spring1 = spring_energy(q1, active.size()) + area_energy(trial);
    double E1 = spring1;
    // the points (the same as point()) with their chart Jacobians: the
    // closest-point sweep starts from these chart points
    // (where a blended model's regions moved, a chart point may have left
    // the surface or have another canonical point: then only the point)
    m_start.resize(active.size());
    m_start_valid.assign(active.size(), false);
    E1 += m_blocks.sum_over_blocks(active.size(), 0., [&](std::size_t first, std::size_t last) {
      double e = 0.;
      for(std::size_t k = first; k < last; ++k)
      {
        Chart_point cu;
        const Chart_point& u = corr.u[k];
        internal::Evaluated_start<Model>& start = m_start[k];
        m_start_valid[k] = internal::evaluate_canonical(trial, u, cu, start.x, start.J, start.has_normal, start.normal) &&
                           cu.chart == u.chart && cu.x == u.x && cu.y == u.y;
        if(!m_start_valid[k])
        {
          const Point_3 x = trial.point(u);
          start.x = Eigen::Vector3d(x.x(), x.y(), x.z());
        }
        e += 0.5 * trials.system.w[k] * CGAL::square(corr.normal[k].dot(m_points[active[k]] - start.x));
      }
      return e;
    });
    const double E0 = trials.system.energy;
    if(!(E1 <= E0))
      return false;
    if(E0 - E1 <= m_settings.energy_tolerance * E0)
    {
      trials.negligible = true; // a rest state: not worth a sweep, and the model stays put
      return false;
    }
    if(++trials.sweeps > 2)
      return false;
    trials.swept_decrease = (std::max)(trials.swept_decrease, (E0 - E1) / E0);
    Correspondences moved = attach(trial, active, &corr, true);
    const double F1 = true_energy(moved.distance, corr.loss) + spring1;
    if(!(F1 <= report.energy_before))
      return false;
    m_model = trial;
    set_correspondences(std::move(moved), m_use_all);
    report.energy_after = F1;
    report.fixed_energy_after = E1;
    report.accepted = true;
    return true;
  }

  // The step solve of the implicit integrator (Integrator::Gauss_newton):
  // (H + lambda diag(H)) dq = g within the box trust region
  // (solve_in_step_box()), the damping lambda lowered after an accepted
  // trial and raised after a rejected one. After a trial the model refuses
  // (a blending region pushed out of its chart), the region parameters are
  // held for the rest of the step instead: a fit pushes a region against
  // its chart's edge in ever shorter accepted steps, and there any move
  // outwards, however short, is refused. Before, the damping grew instead,
  // to 1e9 and more, which froze every other parameter while the regions'
  // own (whose diagonals of J^T J are tiny: 1e-12 and below) still pushed
  // out: split fits stalled at their start and were undone with the surface
  // unmoved (measured on the box/cylinder scan's and the mannequin's).
  void damped_gauss_newton_step(Step_trials& trials, Step_report& report)
  {
    const std::size_t n = m_model.number_of_parameters();
    const Eigen::VectorXd diag = trials.system.H.diagonal();
    const double ridge = 1e-12 * (diag.sum() / double(n) + 1e-300);
    for(int attempt = 0; attempt < 8 && !report.accepted && !trials.negligible && trials.sweeps <= 2; ++attempt)
    {
      Eigen::MatrixXd A = trials.system.H;
      A.diagonal() += m_lambda * diag + Eigen::VectorXd::Constant(Eigen::Index(n), ridge);
      const internal::Box_constrained_step box =
        solve_in_step_box(A, trials.system.g, trials.q, trials.regions_held);
      report.step_in_box_converged = box.converged;
      trials.refused = false;
      if(box.delta.allFinite() && try_step(box.delta, trials, report))
        m_lambda = (std::max)(m_lambda / 3., 1e-9);
      else if(trials.refused && !trials.regions_held)
        trials.regions_held = true;
      else if(!trials.negligible) // at a rest state the damping is not to blame: it would
        m_lambda = (std::min)(m_lambda * 8., 1e12); // only slow down the next phase's first steps
    }
  }

  // The largest change of parameter `i` in one Gauss-Newton step: see maximum_step.
  double step_limit(std::size_t i) const
  {
    return m_model.parameter_kind(i) == Parameter_kind::Length ? maximum_step * m_diameter : maximum_step;
  }

  // A dq = g for the step from `q`, with each dq_i in the box
  // [-step_limit(i), step_limit(i)] cut by the parameter's bounds (a box
  // trust region), as internal::solve_in_box() finds it; with
  // `regions_held`, the blending-region parameters do not move.
  internal::Box_constrained_step solve_in_step_box(const Eigen::MatrixXd& A, const Eigen::VectorXd& g,
                                                   const Eigen::VectorXd& q, bool regions_held) const
  {
    const Eigen::Index n = A.rows();
    Eigen::VectorXd low(n), high(n), limit(n);
    for(Eigen::Index i = 0; i < n; ++i)
    {
      limit[i] = step_limit(std::size_t(i));
      const bool held = regions_held && m_model.is_blending_region_parameter(std::size_t(i));
      low[i] = held ? 0. : (std::min)(0., (std::max)(-limit[i], lower_bound(std::size_t(i)) - q[i]));
      high[i] = held ? 0. : (std::max)(0., (std::min)(limit[i], upper_bound(std::size_t(i)) - q[i]));
    }
    return internal::solve_in_box(A, g, low, high, limit);
  }

  // The step solve of the paper's explicit integrator (eq. 7):
  // dq = dt f_q with dt = 1 / lambda_max(J^T J), stable for the linearized
  // dynamics q' = f_q, times a reduction that persists between steps
  // (halved on failure, grown back on success) where the nonlinearity needs
  // shorter steps.
  void explicit_step(Step_trials& trials, Step_report& report)
  {
    const double lmax =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(trials.system.H, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
    const double dt = (lmax > 0.) ? 1. / lmax : 0.;
    for(int attempt = 0; attempt < 12 && !report.accepted && !trials.negligible && trials.sweeps <= 2 && dt > 0.;
        ++attempt)
    {
      if(try_step(m_dt_scale * dt * trials.system.g, trials, report))
        m_dt_scale = (std::min)(1., 1.5 * m_dt_scale);
      else
        m_dt_scale *= 0.5;
    }
  }

  // Positions the chart meshes; their AABB tree is rebuilt when next searched
  // (a rejected trial's meshes are put back without a rebuild that nobody uses).
  // The faces searched are those with a corner on the surface (sec. 3.3:
  // the faces wholly in a discarded part of a blended shape's domain are
  // omitted; for a single primitive, all).
  void position_meshes(const Model& model)
  {
    m_kept_faces.resize(m_charts.size());
    for(std::size_t i = 0; i < m_charts.size(); ++i)
    {
      Chart_mesh_type& cm = m_charts[i];
      cm.set_positions([&](const Chart_point& u) { return model.point(u); });
      const auto& mesh = cm.mesh();
      std::vector<bool> on(mesh.number_of_vertices());
      for(auto v : mesh.vertices())
        on[std::size_t(v)] = model.is_on_surface(cm.chart_point(v));
      m_kept_faces[i].assign(mesh.number_of_faces(), false);
      for(auto f : mesh.faces())
        for(auto v : cm.face_vertices(f))
          if(on[std::size_t(v)])
            m_kept_faces[i][std::size_t(f)] = true;
    }
    m_tree_outdated = true;
  }

  // A start for the projection of a located mesh point: its chart point, or,
  // on a face that straddles a cut, the face's corner on the surface with the
  // largest barycentric weight.
  Chart_point projection_start(const Located_point<Geom_traits>& loc, const Model& model) const
  {
    if(model.is_on_surface(loc.chart_point))
      return loc.chart_point;
    const Chart_mesh_type& cm = m_charts[loc.chart_mesh];
    const auto v = cm.face_vertices(loc.face);
    int best = -1;
    for(int k = 0; k < 3; ++k)
      if(model.is_on_surface(cm.chart_point(v[std::size_t(k)])) &&
         (best < 0 || loc.barycentric[std::size_t(k)] > loc.barycentric[std::size_t(best)]))
        best = k;
    CGAL_assertion(best >= 0); // the kept faces have a corner on the surface
    return cm.chart_point(v[std::size_t(best < 0 ? 0 : best)]);
  }

  // The locator over the current mesh positions.
  const Closest_point_locator<Geom_traits>& locator()
  {
    if(m_tree_outdated)
    {
      m_locator->rebuild();
      m_tree_outdated = false;
    }
    return *m_locator;
  }

  void choose_subset()
  {
    m_all.resize(m_points.size());
    std::iota(m_all.begin(), m_all.end(), std::size_t(0));
    if(m_settings.subset_size == 0 || m_settings.subset_size >= m_points.size())
    {
      m_subset = m_all;
      return;
    }
    // A deterministic partial Fisher-Yates shuffle (std::shuffle's algorithm is
    // implementation-defined; this keeps results identical across libraries).
    std::vector<std::size_t> idx = m_all;
    std::mt19937_64 rng(m_settings.random_seed);
    for(std::size_t i = 0; i < m_settings.subset_size; ++i)
    {
      const std::size_t j = i + std::size_t(rng() % (idx.size() - i));
      std::swap(idx[i], idx[j]);
    }
    m_subset.assign(idx.begin(), idx.begin() + std::ptrdiff_t(m_settings.subset_size));
    std::sort(m_subset.begin(), m_subset.end());
  }

  void refresh()
  {
    position_meshes(m_model);
    m_correspondences_valid = false;
  }

  void set_correspondences(Correspondences&& c, bool all_points)
  {
    m_correspondences = std::move(c);
    m_correspondences_all = all_points;
    m_correspondences_valid = true;
  }

  // At a rest state: the foot points followed from step to step are local
  // closest points; where the data point is near the medial axis (inside an
  // edge of the model, say) another sheet of the surface may have become
  // closer without the bounded search seeing it past the tessellation's chord
  // error. Every point's tessellation closest point is projected too; true
  // when that lowers the energy enough for the fit to go on (the rest state
  // was one of the followed foot points, not of the closest ones).
  bool recheck_correspondences()
  {
    const Correspondences& corr = correspondences_of_all_points();
    const double before = true_energy(corr.distance, corr.loss);
    Correspondences fresh = attach(m_model, m_all, &corr, false, true);
    const double after = true_energy(fresh.distance, corr.loss);
    set_correspondences(std::move(fresh), true);
    return after < before * (1. - m_settings.energy_tolerance);
  }

  const Correspondences& correspondences_of_all_points()
  {
    if(!m_correspondences_valid || !m_correspondences_all)
      set_correspondences(attach_all_points(), true);
    return m_correspondences;
  }

  // The correspondences of all points on the current model: from the foot
  // points inherited (start_from_foot_points_of()), once, or from the tessellation.
  Correspondences attach_all_points()
  {
    if(!m_inherited)
      return attach(m_model, m_all);
    const Correspondences inherited = std::move(*m_inherited);
    m_inherited.reset();
    return attach(m_model, m_all, &inherited);
  }

  // With `previous` (the correspondences of the same points on the model
  // before a small step), each projection starts from the previous foot
  // point, and the tessellation is only searched for points closer than the
  // foot point found (a search bounded by that distance, hence cheap); where
  // it has one, the projection from there is made too and the closer result
  // wins: the true energy of consecutive models is then measured
  // consistently, and a nearby foot point is not lost to a tessellation
  // artifact.
  // With `evaluated`, m_start holds the model's points, chart Jacobians (and
  // normals, where the model gives them) at the previous chart points
  // (try_step()), and m_start_valid says where these are canonical.
  // With `search_everywhere` (and `previous`, which must then be the
  // correspondences of `model` itself: the recheck at rest, whose foot points
  // stand as they are), the tessellation's closest point is projected too,
  // whatever its distance, and the closer result wins;
  // the search for it is bounded by the foot point's distance plus
  // internal::chart_mesh_deviation_bound() where there are enough points.
  Correspondences attach(const Model& model, const std::vector<std::size_t>& active,
                         const Correspondences* previous = nullptr, bool evaluated = false,
                         bool search_everywhere = false)
  {
    position_meshes(model);
    Correspondences c;
    c.u.resize(active.size());
    c.normal.resize(active.size());
    c.distance.resize(active.size());
    const int iterations = m_settings.projection_iterations;
    // Distances to 1e-12 relatively (energies far more precisely than the
    // energy tolerance can see); the foot points themselves to ~1e-6 of the distance.
    const double tolerance = 1e-12;
    const double spacing2 = 1. / CGAL::square(double(m_settings.mesh_resolution)); // squared chart distance
    // The tree is rebuilt here, before the parallel sweep, which only reads it.
    const Closest_point_locator<Geom_traits>& search = locator();
    // The search everywhere looks for the closest mesh point, which lies
    // within the foot point's distance plus the mesh's deviation from the
    // surface: bounded by that, it visits far fewer nodes of the tree than
    // an unbounded search (which starts from the nearest mesh vertex). The
    // bound costs four evaluations per face: taken where the points
    // outnumber them.
    std::optional<double> deviation;
    if(search_everywhere && previous != nullptr)
    {
      std::size_t faces_searched = 0;
      for(const std::vector<bool>& kept : m_kept_faces)
        faces_searched += std::size_t(std::count(kept.begin(), kept.end(), true));
      if(active.size() >= 8 * faces_searched)
        deviation = internal::chart_mesh_deviation_bound(m_charts, &m_kept_faces, model);
    }
    // Without foot points to follow, a blended model's projections also
    // start from surface samples (Fitting_settings::projection_start_samples).
    const std::vector<Chart_point> sampled_start =
      previous == nullptr
        ? internal::sampled_projection_starts(model, m_points, active, m_settings.projection_start_samples)
        : std::vector<Chart_point>();
    m_blocks.for_each_point(active.size(), [&](std::size_t k) {
      const Eigen::Vector3d& p = m_points[active[k]];
      const Point_3 query(p[0], p[1], p[2]);
      internal::Foot_point foot;
      Located_point<Geom_traits> loc;
      bool kept_previous = false; // the foot point of `previous`, as it is
      // A start evaluated by try_step() is known to be canonical on `model`,
      // hence on its surface: locating it again (a blended model's costliest
      // part of an evaluation) would only repeat that answer.
      const bool start_evaluated = evaluated && m_start_valid[k];
      if(previous != nullptr && (start_evaluated || model.is_on_surface(previous->u[k])))
      {
        if(search_everywhere) // `previous` is of `model` itself: its foot points stand
        {
          foot.u = previous->u[k];
          foot.squared_distance = CGAL::square(previous->distance[k]);
          kept_previous = true;
        }
        else
          foot = start_evaluated
                   ? internal::refine_foot_point(model, p, previous->u[k], iterations, tolerance, &m_start[k])
                   : internal::refine_foot_point(model, p, previous->u[k], iterations, tolerance);
        // A closer tessellation point within a mesh spacing of the foot point
        // (in the same chart) leads back to the same foot point: only one
        // farther away can lead to another one. The search everywhere
        // projects the closest one wherever it is: a projection from it may
        // also polish a foot point that converged slowly (next to a crease),
        // and the fit then goes on to the same rest state whatever the
        // pose of the data (without it, equivariance in flat valleys of the
        // energy suffers: 2.8e-4 instead of 2e-6 relatively on one case of
        // fit_single_superquadric --equivariance 60).
        bool located = false;
        if(!search_everywhere)
          located = search.locate_closer_than(query, Point_3(foot.x[0], foot.x[1], foot.x[2]), loc);
        else
        {
          if(deviation)
          {
            // any point at the foot point's distance plus the deviation bounds the search
            const double r = std::sqrt(foot.squared_distance) + *deviation;
            located = search.locate_closer_than(query, Point_3(p[0] + r, p[1], p[2]), loc);
          }
          if(!located) // no bound, or it failed (it is sampled: faces straddling a blend's cut show less)
          {
            loc = search.locate(query);
            located = true;
          }
        }
        if(located && (search_everywhere ||
                       !(loc.chart_point.chart == foot.u.chart &&
                         CGAL::square(loc.chart_point.x - foot.u.x) + CGAL::square(loc.chart_point.y - foot.u.y) <=
                           spacing2)))
        {
          const internal::Foot_point w =
            internal::refine_foot_point(model, p, projection_start(loc, model), iterations, tolerance);
          if(!(foot.squared_distance < w.squared_distance)) // ties go to the tessellation's start
          {
            foot = w;
            kept_previous = false;
          }
        }
      }
      else // no previous foot point, or it left the surface of a blended model
      {
        foot = internal::refine_foot_point(model, p, projection_start(search.locate(query), model), iterations,
                                           tolerance);
        const std::size_t starts = sampled_start.size() / active.size(); // per point
        for(std::size_t j = k * starts; j < (k + 1) * starts; ++j)
        {
          const internal::Foot_point w = internal::refine_foot_point(model, p, sampled_start[j], iterations, tolerance);
          if(w.squared_distance < foot.squared_distance) // ties go to the earlier start
            foot = w;
        }
      }
      c.u[k] = foot.u;
      if(kept_previous)
      {
        c.normal[k] = previous->normal[k];
        c.distance[k] = previous->distance[k];
        return;
      }
      if(foot.has_normal) // the same as model.normal(foot.u), from the search's evaluation
        c.normal[k] = foot.normal;
      else
      {
        const Vector_3 nv = model.normal(foot.u);
        c.normal[k] = Eigen::Vector3d(nv.x(), nv.y(), nv.z());
      }
      c.distance[k] = std::sqrt(foot.squared_distance);
    });
    // The strays' volume: the ball of the points' diameter D (rotation-invariant,
    // unlike their box). The noise is taken to be at most noise_ceiling D.
    c.loss = Robust_loss::estimate(m_settings.robust_weighting, c.distance, surface_area(),
                                   CGAL_PI / 6. * CGAL::square(m_diameter) * m_diameter, 1e-9 * m_diameter,
                                   m_settings.noise_ceiling * m_diameter);
    return c;
  }

  // The springs' stiffness per point and parameter: for each run of
  // placement parameters of one kind (a translation, a quaternion), the
  // settings' fraction of the mean of the data's stiffness H_ii over the run.
  void set_springs(const Eigen::MatrixXd& H, std::size_t points_used)
  {
    const std::size_t n = m_model.number_of_parameters();
    m_spring.assign(n, 0.);
    if(!(m_settings.placement_stiffness > 0.) || points_used == 0)
      return;
    for(std::size_t i = 0; i < n;)
    {
      if(!m_model.is_placement_parameter(i))
      {
        ++i;
        continue;
      }
      std::size_t j = i;
      double sum = 0.;
      while(j < n && m_model.is_placement_parameter(j) && m_model.parameter_kind(j) == m_model.parameter_kind(i))
        sum += H(Eigen::Index(j), Eigen::Index(j)), ++j;
      const double k = m_settings.placement_stiffness * sum / double(j - i) / double(points_used);
      for(std::size_t l = i; l < j; ++l)
        m_spring[l] = k;
      i = j;
    }
  }

  double spring_energy(const Eigen::VectorXd& q, std::size_t points_used) const
  {
    double e = 0.;
    for(std::size_t i = 0; i < m_spring.size(); ++i)
      e += 0.5 * double(points_used) * m_spring[i] * CGAL::square(q[Eigen::Index(i)] - m_rest[Eigen::Index(i)]);
    return e;
  }

  static double true_energy(const std::vector<double>& distance, const Robust_loss& loss)
  {
    double e = 0.;
    for(double d : distance)
      e += 0.5 * loss.loss(d);
    return e;
  }

  // The area of the searched faces of the chart meshes as positioned (the
  // overlaps of charts count twice: an overestimate by a constant factor
  // that only shifts the strays' density in Robust_loss a little).
  double surface_area() const
  {
    double area = 0.;
    for(std::size_t i = 0; i < m_charts.size(); ++i)
    {
      const auto& mesh = m_charts[i].mesh();
      for(auto f : mesh.faces())
        if(m_kept_faces[i][std::size_t(f)])
        {
          const auto v = m_charts[i].face_vertices(f);
          area += std::sqrt(CGAL::to_double(CGAL::squared_area(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]))));
        }
    }
    return area;
  }

  Model m_model;
  Fitting_settings m_settings;
  internal::Point_blocks m_blocks; // runs the per-point loops of the sweeps and the assembly
  std::vector<Eigen::Vector3d> m_points;
  double m_diagonal = 0.;  // of the bounding box: for the metrics
  double m_diameter = 0.;  // about the centroid: the rotation-invariant length scale
  std::vector<Chart_mesh_type> m_charts;
  std::vector<std::vector<bool>> m_kept_faces; // per chart mesh and face: searched (see position_meshes())
  std::unique_ptr<Closest_point_locator<Geom_traits>> m_locator;
  bool m_tree_outdated = false; // the meshes moved since the locator's tree was built
  std::vector<internal::Evaluated_start<Model>> m_start; // the trial's points at the chart points before it: see attach()
  std::vector<unsigned char> m_start_valid; // see attach(); not vector<bool>: written by several threads
  std::vector<std::size_t> m_all, m_subset;
  bool m_use_all = true;
  std::vector<bool> m_active_parameters;
  Correspondences m_correspondences;     // of m_model, on all points or the subset
  Correspondences m_scratch;             // those of mean_squared_distance() on the subset
  std::optional<Correspondences> m_inherited; // see start_from_foot_points_of()
  bool m_correspondences_valid = false;
  bool m_correspondences_all = false;
  Eigen::VectorXd m_rest;             // the parameters the placement springs pull towards
  std::vector<double> m_spring;       // per parameter: spring stiffness per point (set at the first step)
  double m_data_area = 0.;            // the area the points cover (see set_area_weight()); 0: no area term
  double m_area_lambda = 0.;          // the area term's lambda in the current step
  internal::Surface_area<Model> m_area; // its tessellations of the charts (empty: no area term)
  static constexpr double initial_damping = 1e-3;
  double m_lambda = initial_damping; // Gauss-Newton damping
  double m_dt_scale = 1.;    // explicit integrator: reduction of the stable step
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_DEFORMABLE_MODEL_FITTER_H
