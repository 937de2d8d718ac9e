// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_EVOLUTION_FIT_BLENDED_SHAPE_H
#define CGAL_BLENDED_SHAPE_EVOLUTION_FIT_BLENDED_SHAPE_H

#include <CGAL/Blended_shape/Evolution/Evolution_settings.h>
#include <CGAL/Blended_shape/Evolution/Part_evolution.h>
#include <CGAL/Blended_shape/Fitting/Blended_model_metrics.h>
#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <CGAL/Blended_shape/Fitting/internal/Point_blocks.h>
#include <CGAL/Blended_shape/Fitting/internal/Point_normalization.h>
#include <CGAL/Blended_shape/Fitting/internal/Shared_callback.h>
#include <CGAL/Blended_shape/internal/isolated_points.h>
#include <CGAL/Blended_shape/internal/nearest_points.h>
#include <CGAL/Blended_shape/internal/point_range_types.h>
#include <CGAL/Blended_shape/parameters.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

namespace internal {

// An event of evolution on normalized points (Point_normalization), in the
// unit of the input: distances times the scale, and the description length
// of the `n` points, (n/2) ln(MSD), shifted by n ln(scale).
inline Evolution_event event_in_input_unit(Evolution_event e, double scale, double n)
{
  e.rms_before *= scale;
  e.rms_after *= scale;
  e.description_length_before += n * std::log(scale);
  e.description_length_after += n * std::log(scale);
  return e;
}

// The indices (increasing) of the points evolution works on
// (Evolution_settings::maximum_evolution_points): every k-th point not
// `isolated`, in order, k the smallest that leaves at most `maximum` (0: all of them).
inline std::vector<std::size_t> evolution_sample(const std::vector<bool>& isolated, std::size_t maximum)
{
  std::vector<std::size_t> kept;
  for(std::size_t i = 0; i < isolated.size(); ++i)
    if(!isolated[i])
      kept.push_back(i);
  if(maximum == 0 || kept.size() <= maximum)
    return kept;
  const std::size_t k = (kept.size() + maximum - 1) / maximum;
  std::vector<std::size_t> thinned;
  for(std::size_t i = 0; i < kept.size(); i += k)
    thinned.push_back(kept[i]);
  return thinned;
}

// The coordinates of `points`, in plain doubles.
template <class Point_3>
std::vector<Eigen::Vector3d> coordinates_of(const std::vector<Point_3>& points)
{
  std::vector<Eigen::Vector3d> coordinates;
  coordinates.reserve(points.size());
  for(const Point_3& p : points)
    coordinates.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  return coordinates;
}

// The points of `points` (through `point_map`) at `indices` (increasing).
template <class Point_3, class PointRange, class PointMap>
std::vector<Point_3> points_at(const PointRange& points, const PointMap& point_map,
                               const std::vector<std::size_t>& indices)
{
  std::vector<Point_3> selected;
  selected.reserve(indices.size());
  std::size_t i = 0, next = 0;
  for(auto it = points.begin(); it != points.end() && next < indices.size(); ++it, ++i)
    if(indices[next] == i)
    {
      selected.push_back(get(point_map, *it));
      ++next;
    }
  return selected;
}

// `model` with the curves of all its blending regions held (`held` true) or
// released (Blended_shape::hold_blending_region()).
template <class GeomTraits>
Deformable_blended_model<GeomTraits> with_blending_regions_held(const Deformable_blended_model<GeomTraits>& model,
                                                               bool held)
{
  Blended_shape<GeomTraits> shape = model.shape();
  for(std::size_t b = 0; b < shape.number_of_blends(); ++b)
    shape.hold_blending_region(b, held);
  return Deformable_blended_model<GeomTraits>(shape, model.translation(), model.quaternion());
}

// Passes the hooks of an evolution on normalized points to `visitor` with
// the events and models in the frame of the input.
template <class Visitor, class GeomTraits>
class Input_frame_visitor final : public Evolution_listener_of<Visitor, Deformable_blended_model<GeomTraits>>
{
public:
  typedef Deformable_blended_model<GeomTraits> Model;

  Input_frame_visitor(Visitor& visitor, const Point_normalization<GeomTraits>& normalization, double number_of_points)
    : Evolution_listener_of<Visitor, Model>(visitor), m_normalization(normalization),
      m_number_of_points(number_of_points)
  {}

  void on_split(const Evolution_event& e, const Model& model) override { notify(e, model); }
  void on_undo(const Evolution_event& e, const Model& model) override { notify(e, model); }
  void on_remove(const Evolution_event& e, const Model& model) override { notify(e, model); }

private:
  void notify(const Evolution_event& e, const Model& model)
  {
    notify_event(this->m_visitor, event_in_input_unit(e, m_normalization.scale(), m_number_of_points),
                 m_normalization.model_from_normalized(model));
  }

  const Point_normalization<GeomTraits>& m_normalization;
  double m_number_of_points;
};

// The visitor of an evolution run that goes on concurrently with others: it
// records what it hears (the fits' hooks, and evolution's phases and events
// with their models), and the caller's visitor then hears of the runs one
// after the other (replay()), the same at any number of threads
// (Recorded_fitting_visitor does this for the fits of one superquadric,
// which know no evolution events).
template <class Model>
class Recorded_evolution_visitor final : public Evolution_listener<Model>
{
public:
  void on_phase(Fitting_phase phase, std::size_t iteration) override
  {
    record([=](Evolution_listener<Model>& v) { v.on_phase(phase, iteration); });
  }
  void on_iteration(std::size_t iteration, double energy, std::size_t points_used) override
  {
    record([=](Evolution_listener<Model>& v) { v.on_iteration(iteration, energy, points_used); });
  }
  void on_evolution_phase(Evolution_phase phase, std::size_t parts) override
  {
    record([=](Evolution_listener<Model>& v) { v.on_evolution_phase(phase, parts); });
  }
  void on_split(const Evolution_event& e, const Model& model) override
  {
    record_event(&Evolution_listener<Model>::on_split, e, model);
  }
  void on_undo(const Evolution_event& e, const Model& model) override
  {
    record_event(&Evolution_listener<Model>::on_undo, e, model);
  }
  void on_remove(const Evolution_event& e, const Model& model) override
  {
    record_event(&Evolution_listener<Model>::on_remove, e, model);
  }

  void replay(Evolution_listener<Model>& visitor) const
  {
    for(const auto& heard : m_heard)
      heard(visitor);
  }

private:
  typedef void (Evolution_listener<Model>::*Event_hook)(const Evolution_event&, const Model&);

  template <class F>
  void record(F&& f)
  {
    m_heard.emplace_back(std::forward<F>(f));
  }
  // An event is replayed with a copy of the model it was heard with.
  void record_event(Event_hook hook, const Evolution_event& e, const Model& model)
  {
    record([hook, e, model](Evolution_listener<Model>& v) { (v.*hook)(e, model); });
  }

  std::vector<std::function<void(Evolution_listener<Model>&)>> m_heard;
};

} // namespace internal

/// \ingroup PkgBlendedShapeEvolution
/// What fit_blended_shape() returns: the evolved model and the record of its evolution.
template <class GeomTraits>
struct Blended_fit_result
{
  typedef Deformable_blended_model<GeomTraits> Model; ///< the model type
  Model model;                          ///< the evolved model, in the frame of the input points
  /// The events (splits kept or undone, parts removed), in order. Their RMS distances are in
  /// the unit of the input points, their description lengths those of the
  /// points in that unit (see Part_evolution).
  std::vector<Evolution_event> events;
  Evolution_status status;              ///< how evolution ended (of the run kept, see fit_blended_shape(); its iterations do not count the first fit's)
  /// The fit figures of the model (compute_fit_metrics(), in the unit of
  /// the input; relative RMS in the frame of the initial ellipsoid of all
  /// the points, as in eq. 14): those of the fit of one superquadric the
  /// model is (see fit_blended_shape()), or after a kept split, those of
  /// the least-squares fit of all the points not isolated (evolution's, or
  /// with a sample the final fit's).
  /// `iterations` and `seconds` count the whole call.
  Fit_metrics metrics;
  /// The indices (in the input order, increasing) of the points the model
  /// leaves out: with one part, the stray points of its fit
  /// (Fit_result::stray_points, none for a least-squares fit); after a kept
  /// split, the isolated points (Part_evolution::isolated_points(), or
  /// with a sample, see fit_blended_shape(), those of all the points).
  std::vector<std::size_t> stray_points;
  /// The fit of one superquadric evolution started from: by least squares
  /// (`robust_weighting` `Robust_weighting::None`), as evolution's fits are,
  /// of the points evolution sees (with a sample, see fit_blended_shape(),
  /// of the sample alone); with `maximum_number_of_parts` 1,
  /// fit_superquadric() of all the points as asked for.
  Fit_result<GeomTraits> first_fit;
  /// The run of evolution kept (Evolution_settings::evolution_runs; 0 with one run).
  std::size_t evolution_run = 0;
  /// The description length of evolution's points given each run's evolved
  /// model, in the unit of the input points, in the order of the runs (none
  /// without evolution); the run kept has the smallest.
  std::vector<double> run_description_lengths;
  /// The number of parts of the model (its components).
  std::size_t number_of_parts() const { return model.shape().number_of_components(); }
  /// The number of splits kept (a part removed later counts too: see number_of_parts()).
  std::size_t number_of_splits() const
  {
    std::size_t n = 0;
    for(const Evolution_event& e : events)
      n += e.accepted() ? 1 : 0;
    return n;
  }
};

/*!
\ingroup PkgBlendedShapeEvolution

Fits a blended shape to `points` in one call: one superquadric first
(fit_superquadric() by least squares, of the points evolution sees), then part evolution
(Part_evolution::run(): splits where the forces at rest say the model
cannot fit the data, each kept only if it pays for its parameters).

Evolution's fits are least-squares fits of the points that are not
isolated (see Part_evolution), so it starts from the least-squares fit: a
robust fit of an object made of parts fits its largest part and takes the
others for strays. When evolution ends with one part (no split kept, or
every part split off removed again), the model is that of
fit_superquadric() of all the points with the named parameters as given
(robust to stray points by default), bit for bit, unless that fit judged
more than half of the points stray: a fit that explains a minority of the
points fits one part of an object made of several (the box/cylinder scan:
70 % "strays"), and the least-squares fit of all the points stays. With `maximum_number_of_parts` 1,
evolution is skipped and the model is always fit_superquadric()'s.

Of more points than `maximum_evolution_points` (4000 by default),
evolution sees an even sample: every `k`-th point of those not isolated, in
input order, and so does the first fit (evolution fits the sample again at
once: a first fit of all the points would only cost time, 0.7 of the
box/cylinder scan's first second). Its split test still counts all of them
(Part_evolution::set_described_points()), and the evolved model is then
fitted to rest on all of them, each projection starting from the foot
point of the nearest point of the sample
(Deformable_model_fitter::start_from_chart_points()), with the curves of
the blending regions held where evolution left them
(Blended_shape::hold_blending_region(); released in the result). Fewer points are not
sampled (the result is that of `maximum_evolution_points` 0, bit for bit).

Like fit_superquadric(), evolution works on a copy of the points centred at
the origin at about unit size, and the model is mapped back exactly: the
result does not depend on the unit of the points or on where they are.

With `evolution_runs` N > 1, evolution runs N times from the same first
fit, run `r` on that copy scaled by `1 + r 2^-23` (the same data, rounded
otherwise: its fits take other paths, see the manual, Inputs changed by
1e-7), and the run whose evolved model has the shortest description length
of evolution's points is kept (Blended_fit_result::evolution_run,
Blended_fit_result::run_description_lengths); the final fit on all points
is that run's. The runs go on concurrently on the threads of the fits
(`number_of_threads`): the result is the same bits at any number. The
visitor hears of run 0 as it goes (from the thread that runs it, never of
two runs at once), then of every other run in turn, once all have ended;
`status` is the kept run's. The callback is called one call at a time;
once it has returned false it is not called again and every run stops at
its next iteration. A run stopped by the callback ends the runs: after
the first, the run kept is the best of those before it.

\param points the input points (see check_points())
\param np optional named parameters:
  - every member of Fitting_settings (settings_from_named_parameters()),
    for the first fit and for evolution's fits;
  - every member of Evolution_settings (evolution_settings_from_named_parameters()):
    `maximum_number_of_parts` (1: one superquadric), `target_accuracy`,
    `maximum_split_tries`, `threshold_factor`, `analysis_resolution`,
    `maximum_evolution_points`, `split_source`, `blend_stages`,
    `intermediate_stage_iterations`, `first_split_blend_stages`,
    `first_split_stage_iterations`, `evolution_runs`;
  - `point_map`, `geom_traits`, `try_all_axes`: as for fit_superquadric();
  - `reference_mesh` (a pointer to a `CGAL::Surface_mesh<Point_3>`): the
    result's metrics then hold the symmetric Chamfer distance of the model
    to it, whatever its parts (symmetric_chamfer_distance() of a
    Deformable_blended_model; `first_fit`'s metrics do not);
  - `visitor`: a fitting visitor (Default_fitting_visitor), whose
    `on_split()` and `on_undo()` are called too if it has them, and
    `on_remove()` if it has it (Default_evolution_visitor), with the event
    and the model in the frame and unit of the input, as in the result;
  - `callback`: as for fit_superquadric(), passed to every fit; when it
    stops evolution, the model is the last one kept (see Part_evolution).

\throws Input_error if the points are unusable; std::invalid_argument on invalid parameters
        (a reference mesh without faces, with faces that are not triangles, or with a coordinate that is not finite or beyond `maximum_coordinate_magnitude` too).
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
  const typename Types::Point_map point_map = Types::point_map(np);
  const std::function<bool(double)> callback = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, CGAL::internal_np::callback), std::function<bool(double)>());
  auto visitor = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::visitor),
                                                    Default_evolution_visitor());
  // The Chamfer distance to a reference mesh is measured once, of the
  // result (at the end, untimed), not by the fits of one superquadric.
  typedef CGAL::Surface_mesh<typename Geom_traits::Point_3> Mesh;
  const Mesh* reference = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, internal_np::reference_mesh), static_cast<const Mesh*>(nullptr));
  if(reference != nullptr) // (refused before any fitting)
    internal::check_reference_mesh(*reference, "fit_blended_shape");
  const auto single_np = parameters::reference_mesh(static_cast<const Mesh*>(nullptr), np);

  const bool evolve = evolution_settings.maximum_number_of_parts > 1;
  const Fitting_settings fitting = settings_from_named_parameters(np);
  const bool robust = fitting.robust_weighting != Robust_weighting::None;
  typedef typename Geom_traits::Point_3 Point_3;
  typedef typename Part_evolution<Geom_traits>::Fitter Fitter;

  // Evolution works on the points centred at about unit size; of more points
  // not isolated than evolution_settings.maximum_evolution_points, on an
  // even sample of them (`sample`, their indices; empty: all the points),
  // and the evolved model is then fitted to all of them.
  std::unique_ptr<const internal::Point_normalization<Geom_traits>> normalization;
  std::vector<Point_3> normalized;
  std::vector<Eigen::Vector3d> coordinates;
  std::vector<bool> isolated;
  std::vector<std::size_t> sample;
  std::size_t fitted = 0; // the points not isolated, with a sample
  if(evolve)
  {
    normalization = std::make_unique<const internal::Point_normalization<Geom_traits>>(points, point_map);
    normalized = normalization->normalized_points(points, point_map);
    const std::size_t maximum = evolution_settings.maximum_evolution_points;
    if(maximum > 0 && normalized.size() > maximum)
    {
      coordinates = internal::coordinates_of(normalized);
      isolated = internal::isolated_points(coordinates);
      fitted = std::size_t(std::count(isolated.begin(), isolated.end(), false));
      if(fitted > maximum)
        sample = internal::evolution_sample(isolated, maximum);
    }
  }
  const bool sampled = !sample.empty();

  // Evolution fits by least squares (see Part_evolution), so it starts from
  // the least-squares fit of one superquadric: a robust fit of an object made
  // of parts fits the largest part and takes the others for strays (on the
  // box/cylinder scan, 70 % of the points), a start that no split repairs.
  // (Its rest, the start of evolution, is not settled early: see Part_evolution.)
  // With a sample, that fit is of the sample: evolution fits it again at
  // once, and a fit of all the points would only cost time (on the
  // box/cylinder scan 0.7 of 1 s).
  const auto least_squares_np = parameters::settling_tolerance(
    Part_evolution<Geom_traits>::settling_tolerance, parameters::robust_weighting(Robust_weighting::None, single_np));
  Fit_result<Geom_traits> first_fit =
    !evolve   ? fit_superquadric(points, single_np)
    : sampled ? fit_superquadric(internal::points_at<Point_3>(points, point_map, sample),
                                 least_squares_np.point_map(CGAL::Identity_property_map<Point_3>()))
              : fit_superquadric(points, least_squares_np);
  Result result{make_blended_model(first_fit.model), {}, {}, first_fit.metrics, first_fit.stray_points, std::move(first_fit), 0, {}};
  const Fit_result<Geom_traits>& first = result.first_fit;
  result.status.converged = first.metrics.converged;
  result.status.aborted = first.metrics.aborted; // the model is then the first fit's, as far as it went
  result.status.part_limit_reached = !evolve;
  std::size_t iterations = first.metrics.iterations;
  // (with a sample, none of the first fit's iterations used all the points)
  std::size_t iterations_on_all_points = sampled ? 0 : first.metrics.iterations_on_all_points;
  if(evolve && !result.status.aborted)
  {
    // Run r evolves the points normalized with the scale times 1 + r 2^-23
    // (Evolution_settings::evolution_runs): the same data, rounded
    // otherwise, on which the fits take other paths. The runs go on
    // concurrently, on the threads of the fits (each run's fits give the
    // same bits at any number of threads, so the runs do too); run 0 tells
    // the visitor as it goes, the others record, and the visitor hears
    // them after it, in order. The run kept (its normalization and
    // normalized points replace run 0's) is the one whose evolved model
    // describes evolution's points in the fewest nats, in the unit of the
    // input (Part_evolution::description_length() plus n ln(scale)).
    typedef typename Part_evolution<Geom_traits>::Model Model;
    typedef internal::Input_frame_visitor<decltype(visitor), Geom_traits> Frame_visitor;
    struct Run
    {
      std::unique_ptr<const internal::Point_normalization<Geom_traits>> normalization; // (run 0: `normalization`)
      std::vector<Point_3> normalized;
      std::unique_ptr<Part_evolution<Geom_traits>> evolution;
      Evolution_status status;
      internal::Recorded_evolution_visitor<Model> heard; // (run 0: nothing)
    };
    const std::size_t number_of_runs = evolution_settings.evolution_runs;
    // (it outlives the runs: their fitters run their blocks on its threads)
    const internal::Point_blocks run_threads(fitting.number_of_threads);
    std::vector<Run> runs(number_of_runs);
    internal::Shared_callback run_callback(callback);
    const auto frame_of = [&](std::size_t r) -> const internal::Point_normalization<Geom_traits>& {
      return r > 0 ? *runs[r].normalization : *normalization;
    };
    run_threads.for_each_task_sharing_threads(number_of_runs, [&](std::size_t r) {
      Run& run = runs[r];
      if(r > 0)
      {
        run.normalization = std::make_unique<const internal::Point_normalization<Geom_traits>>(
          points, point_map, 1. + std::ldexp(double(r), -23));
        run.normalized = run.normalization->normalized_points(points, point_map);
      }
      const std::vector<Point_3>& frame_points = r > 0 ? run.normalized : normalized;
      run.evolution = std::make_unique<Part_evolution<Geom_traits>>(
        sampled ? internal::points_at<Point_3>(frame_points, CGAL::Identity_property_map<Point_3>(), sample)
                : frame_points,
        make_blended_model(frame_of(r).model_to_normalized(first.model)), fitting, evolution_settings);
      // The split test asks as much of a split as on all the points
      // (Part_evolution::set_described_points()).
      if(sampled)
        run.evolution->set_described_points(fitted);
      if(r == 0)
      {
        Frame_visitor live(visitor, *normalization, double(run.evolution->described_points()));
        run.status = run.evolution->run(live, run_callback.function());
      }
      else
        run.status = run.evolution->run(run.heard, run_callback.function());
    });
    std::unique_ptr<Part_evolution<Geom_traits>> evolution;
    for(std::size_t r = 0; r < number_of_runs; ++r)
    {
      Run& run = runs[r];
      const double n = double(run.evolution->described_points());
      Frame_visitor run_visitor(visitor, frame_of(r), n);
      run.heard.replay(run_visitor);
      const Evolution_status& status = run.status;
      iterations += status.iterations;
      // Evolution fits all its points at every step, but with the branches
      // (which it fits a few at a time).
      if(!sampled && evolution_settings.split_source != Split_source::Branch_segments)
        iterations_on_all_points += status.iterations;
      if(status.aborted && r > 0)
      {
        result.status.aborted = true; // the runs before it stand
        break;
      }
      const double length = run.evolution->description_length() + n * std::log(frame_of(r).scale());
      result.run_description_lengths.push_back(length);
      if(r == 0 || length < result.run_description_lengths[result.evolution_run])
      {
        evolution = std::move(run.evolution);
        result.evolution_run = r;
        result.status = status;
        if(r > 0)
        {
          normalization = std::move(run.normalization);
          normalized = std::move(run.normalized);
        }
      }
      if(status.aborted)
        break;
    }
    if(sampled && result.evolution_run > 0) // (the final fit's starts are found among the kept run's points)
      coordinates = internal::coordinates_of(normalized);
    const double n = double(evolution->described_points());
    Frame_visitor frame_visitor(visitor, *normalization, n);
    // (the fits' code is compiled for this type already: that of evolution's visitors)
    internal::Evolution_listener<Model>& input_visitor = frame_visitor;
    for(const Evolution_event& e : evolution->events())
      result.events.push_back(internal::event_in_input_unit(e, normalization->scale(), n));
    if(evolution->model().shape().number_of_components() > 1)
    {
      Fitter* rest_fitter = &evolution->fitter();
      Fitting_status rest;
      rest.converged = result.status.converged;
      rest.aborted = result.status.aborted;
      std::unique_ptr<Fitter> final_fit;
      if(sampled)
      {
        // The evolved model fitted to rest on all the points not isolated,
        // by least squares as evolution fits, each projection starting from
        // the foot point of the nearest point evolution fitted: a search
        // from the tessellation alone misses many foot points of a model of
        // several parts (on the box/cylinder scan its RMS was 4 times the
        // true one).
        std::vector<Point_3> kept;
        std::vector<Eigen::Vector3d> kept_coordinates;
        result.stray_points.clear();
        for(std::size_t i = 0; i < normalized.size(); ++i)
          if(isolated[i])
            result.stray_points.push_back(i);
          else
          {
            kept.push_back(normalized[i]);
            kept_coordinates.push_back(coordinates[i]);
          }
        const std::vector<Chart_point> foot = rest_fitter->foot_points();
        std::vector<Chart_point> starts;
        starts.reserve(kept.size());
        for(std::size_t k : internal::nearest_points(rest_fitter->points(), kept_coordinates))
          starts.push_back(foot[k]);
        // The blending regions' curves stay where evolution left them at
        // rest on the sample (a sampling error away from their rest on all
        // points): free, they are the parameters that keep the fit from rest
        // (Blended_shape::hold_blending_region()); held, the final fit on
        // the box/cylinder scan rests in 28 iterations, not 51.
        // Its rest decides nothing more: settled as the caller asks (evolution's were not).
        Fitting_settings final_settings = rest_fitter->settings();
        final_settings.settling_tolerance = fitting.settling_tolerance;
        final_fit = std::make_unique<Fitter>(kept, internal::with_blending_regions_held(evolution->model(), true),
                                             final_settings);
        final_fit->start_from_chart_points(starts);
        if(!result.status.aborted)
        {
          internal::notify_phase(input_visitor, Evolution_phase::Fit_to_rest,
                                 evolution->model().shape().number_of_components());
          rest = final_fit->run(input_visitor, callback);
          iterations += rest.iterations;
          iterations_on_all_points += rest.iterations;
          result.status.converged = rest.converged;
          result.status.aborted = rest.aborted;
        }
        rest_fitter = final_fit.get();
      }
      else
        result.stray_points = evolution->isolated_points();
      result.model = normalization->model_from_normalized(internal::with_blending_regions_held(rest_fitter->model(), false));
      // (eq. 14's frame: the initial ellipsoid of all the points, as in a fit of one superquadric)
      result.metrics = normalization->from_normalized(compute_fit_metrics(
        *rest_fitter, sampled ? initialize_from_moments(normalized) : normalization->to_normalized(first.initial_ellipsoid),
        rest));
    }
    else if((robust || sampled) && !result.status.aborted)
    {
      // One part after all: the fit of one superquadric as asked for
      // (robust, or of all the points where the first fit saw a sample),
      // unless a robust fit takes most points for strays: then it fits one
      // part of an object made of several, and the least-squares fit of all
      // the points, which fits them all, stays.
      // (each such fit counts in the call's iterations; an aborted one ends the call)
      auto counted = [&](Fit_result<Geom_traits>&& fit) {
        iterations += fit.metrics.iterations;
        iterations_on_all_points += fit.metrics.iterations_on_all_points;
        result.status.aborted = fit.metrics.aborted;
        return std::move(fit);
      };
      Fit_result<Geom_traits> single = counted(fit_superquadric(points, single_np));
      bool kept = !(robust && 2 * single.stray_points.size() > single.metrics.number_of_points);
      if(!kept && sampled && !result.status.aborted)
      {
        single = counted(fit_superquadric(points, parameters::robust_weighting(Robust_weighting::None, single_np)));
        kept = true;
      }
      if(kept)
      {
        result.model = make_blended_model(single.model);
        result.metrics = single.metrics;
        result.stray_points = single.stray_points;
      }
    }
  }
  result.metrics.iterations = iterations;
  result.metrics.iterations_on_all_points = iterations_on_all_points;
  result.metrics.aborted = result.status.aborted;
  result.metrics.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if(reference != nullptr)
    result.metrics.chamfer_distance = symmetric_chamfer_distance(result.model, *reference);
  return result;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_EVOLUTION_FIT_BLENDED_SHAPE_H
