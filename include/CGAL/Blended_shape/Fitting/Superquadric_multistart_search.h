// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_SUPERQUADRIC_MULTISTART_SEARCH_H
#define CGAL_BLENDED_SHAPE_FITTING_SUPERQUADRIC_MULTISTART_SEARCH_H

#include <CGAL/Blended_shape/Fitting/Deformable_model.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model_fitter.h>
#include <CGAL/Blended_shape/Fitting/Fitting_settings.h>
#include <CGAL/Blended_shape/Fitting/Fitting_visitor.h>
#include <CGAL/Blended_shape/Fitting/initialize_from_moments.h>
#include <CGAL/Blended_shape/Fitting/internal/Point_blocks.h>
#include <CGAL/Blended_shape/Fitting/internal/Shared_callback.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/internal/quaternion.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
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
    typedef Superquadric_ellipsoid<GeomTraits> Shape;
    e2 = (std::min)((std::max)(2. - q[4], 0.1), Shape::parameter_upper_bound(Shape::E2));
  }
  const Superquadric_ellipsoid<GeomTraits> shape(a[0], a[1], a[2], e1, e2);
  return Deformable_model<Superquadric_ellipsoid<GeomTraits>>(shape, model.translation(),
                                                              internal::quaternion_from_matrix(R));
}

/*!
\ingroup PkgBlendedShapeFitting

The multi-start search of fit_superquadric() among the basins of a
superquadric fit. Partial views often leave the fit of a superquadric in
the basin of a similar superquadric (its z axis exchanged with x or y, the
exponents swapped, its cross-section turned by 45 degrees, or both; see
similar_superquadric()), so the candidates are compared, as EMS iterates its
similarity search, by short fits:

- before the full fit, best_start(): a rough fit from each of the three
  choices of the primitive's z axis among the principal directions of the
  initial ellipsoid (make_initial_model()), then from the similar
  superquadrics of the closest; the closest of all is the start;
- after it, search_similar_basins(): each similar superquadric of the fit
  is fitted roughly; one clearly closer to the rough subset than the fit is
  fitted on the fit's subset, then, if closer there, on all points, and kept
  if it ends closer to all points (by more than 1 % of the mean squared
  distance, everywhere). At most three rounds. Skipped when best_start()
  already compared the start's similar superquadrics with it (none was
  closer) and the fit stayed in the start's basin (each semi-axis and the
  centre within 10 % of its largest semi-axis, the exponents within 0.25,
  the rotation within 10 degrees): its similar superquadrics are then
  those best_start() fitted roughly, each farther from the rough subset
  than the start, which the fit is about as close to; none would be
  "clearly closer" (below 80 % of the fit's distance). This saves about
  40 of the 100 short-fit iterations of most fits. On the 100 single views
  of 2000 points of benchmark/fit_single_superquadric (`--similar-search
  100`), the search was skipped for 80 fits, which had moved by at most 6 %
  and 0.07 from their start, and a search of their own would have
  corrected none of them; it ran for the other 20 and corrected 2.

With robust weighting (the default), the mean squared distances compared
cap each squared distance at `tau^2`, `tau` 5 % of the largest semi-axis of
the start (best_start()) or of the fit (search_similar_basins(), when
called alone): the strays far from all candidates add the same `tau^2` to
each, instead of making the candidate that reaches farthest towards them win.

The rough fits use a 16th of the subset (250 points by default; the same
points for every candidate), loose tolerances, at most 10 iterations and,
with robust weighting, a noise ceiling of
`Fitting_settings::candidate_noise_ceiling` (5 % of the points' diameter)
instead of the full fits' 2 %: at 2 %, the rough fits of a scanned cylinder
alone (its dense cap, its sparse side; no strays) each reached only the
points near their start, and the fit took part of the cylinder for strays.
Among 40 % strays that leaves about 150 points of the surface, enough to
tell the basins of a thin box seen from one view apart: with a 25th (160
points), one of 20 seeded clouds of the peer protocol over twice the box
ended among the strays (its true points' RMS 3.6 % of the diagonal, the
noise 0.2 %; 15 iterations instead of 10 did not help), none with
250 or 400 points; 400 points made the fit of 2000 points 1.9 times slower
than 160, 250 points 1.3 times. Every short fit counts in
candidate_iterations().

Threads: the short fits of a group (the three axes; the five similar
superquadrics of one fit) do not depend on each other, and run
concurrently on `Fitting_settings::number_of_threads` threads (with TBB);
each is then compared as before, in a fixed order, so the result is the
same bits at any number of threads. The visitor hears of every short fit
as of a full fit, but after its group, fit after fit in that fixed order
(the same hooks in the same order at any number of threads). The callback
is called while the fits run, one call at a time (under a lock); once it
has returned false it is not called again and every fit of the group stops.

\tparam GeomTraits the kernel of the points
\tparam PointRange the range of the points, kept by reference: it must outlive the search
\tparam PointMap the property map from the range's items to `GeomTraits::Point_3`
*/
template <class GeomTraits, class PointRange, class PointMap>
class Superquadric_multistart_search
{
public:
  typedef Deformable_model<Superquadric_ellipsoid<GeomTraits>> Model; ///< the model fitted
  typedef Deformable_model_fitter<Model> Fitter;                        ///< the fitter of one candidate
  typedef std::function<bool(double)> Callback; ///< see Deformable_model_fitter::run()

  /// A search for fits of `points` with the settings `settings` of the full fit.
  Superquadric_multistart_search(const PointRange& points, PointMap point_map, const Fitting_settings& settings)
    : m_points(points), m_point_map(point_map), m_settings(settings), m_rough(settings), m_challenger(settings),
      m_tasks(settings.number_of_threads)
  {
    m_rough.subset_size = (std::max<std::size_t>)(settings.subset_size / 16, 100);
    m_rough.energy_tolerance = (std::max)(settings.energy_tolerance, 1e-4);
    m_rough.force_tolerance = (std::max)(settings.force_tolerance, 1e-2);
    m_rough.maximum_iterations = (std::min<std::size_t>)(settings.maximum_iterations, 10);
    m_rough.mesh_resolution = (std::max)(2, settings.mesh_resolution / 2); // the mesh only seeds the analytic closest points
    m_rough.noise_ceiling = settings.candidate_noise_ceiling; // far from rest, see Fitting_settings
    // the challengers' fits on the subset: only to compare them
    m_challenger.energy_tolerance = (std::max)(settings.energy_tolerance, 1e-6);
    m_challenger.force_tolerance = (std::max)(settings.force_tolerance, 1e-3);
    m_challenger.maximum_iterations = (std::min<std::size_t>)(settings.maximum_iterations, 30);
  }

  /// The start of the full fit: the closest rough fit among the three z-axis
  /// choices of `initial` and the similar superquadrics of the closest of them
  /// (ties keep the earlier candidate). Stops early if the callback aborts a fit.
  template <class Visitor>
  Model best_start(const Ellipsoid_fit<GeomTraits>& initial, Visitor& visitor, const Callback& callback)
  {
    Model start = make_initial_model(initial, 2);
    set_truncation(start);
    double best_distance = HUGE_VAL;
    auto consider = [&](const std::vector<Model>& starts) {
      for(const Rough_fit& f : rough_fits(starts, visitor, callback))
        if(f.distance < best_distance) // strict: ties keep the earlier candidate, deterministically
        {
          best_distance = f.distance;
          start = f.model;
        }
    };
    consider({make_initial_model(initial, 0), make_initial_model(initial, 1), make_initial_model(initial, 2)});
    if(m_status.aborted)
      return start;
    const Model winner = start;
    const double winner_distance = best_distance;
    consider(similar_superquadrics(winner));
    // The similar superquadrics of the start were all compared with it (see search_similar_basins()).
    if(best_distance == winner_distance && !m_status.aborted)
      m_compared_basin = winner;
    return start;
  }

  /// After the full fit `fitter`, which ended with `status`: the fitter of a
  /// closer fit from a similar superquadric, if one is found, else `fitter`.
  /// Updates `status` (converged: that of the fit returned; aborted).
  template <class Visitor>
  std::unique_ptr<Fitter> search_similar_basins(std::unique_ptr<Fitter> fitter, Fitting_status& status,
                                                Visitor& visitor, const Callback& callback)
  {
    if(m_compared_basin && in_same_basin(*m_compared_basin, fitter->model()))
      return fitter;
    if(!(m_truncation < HUGE_VAL))
      set_truncation(fitter->model());
    double current = fitter->mean_squared_distance(true, m_truncation);
    for(int round = 0; round < 3 && !status.aborted && !status.timed_out; ++round)
    {
      const Model fitted = fitter->model();
      double reference;
      {
        Fitter probe(m_points, fitted, m_rough, m_point_map);
        reference = probe.mean_squared_distance(false, m_truncation);
      }
      std::unique_ptr<Fitter> better;
      for(const Rough_fit& f : rough_fits(similar_superquadrics(fitted), visitor, callback))
      {
        // Clearly closer: a rough fit of the subset alone beats the full
        // fit there by a little even in the same basin.
        if(m_status.aborted || !(f.distance < 0.8 * reference))
          continue;
        Fitting_status st;
        std::unique_ptr<Fitter> challenger = fit_challenger(f.model, better ? *better : *fitter, st, visitor, callback);
        if(!challenger)
          continue;
        if(st.aborted)
        {
          m_status.aborted = true;
          continue;
        }
        const double full = challenger->mean_squared_distance(true, m_truncation);
        if(full < 0.99 * current) // by more than 1 %: not the same rest state again
        {
          current = full;
          better = std::move(challenger);
          status.converged = st.converged;
        }
      }
      status.aborted = status.aborted || m_status.aborted;
      if(!better)
        break;
      fitter = std::move(better);
    }
    return fitter;
  }

  /// Whether best_start() compared the similar superquadrics of the start
  /// with it and none was closer: then search_similar_basins() skips a fit
  /// that stayed in the start's basin (see the class description). False
  /// before best_start() and after an aborted one.
  bool start_basin_compared() const { return m_compared_basin.has_value(); }

  /// Whether the fit `b` is still in the basin of the rough fit `a`, as
  /// search_similar_basins() decides whether to skip its search: each
  /// semi-axis and the centre within 10 % of a's largest semi-axis, each
  /// exponent within 0.25, the rotation within 10 degrees (see the class
  /// description for what fits moved by).
  static bool in_same_basin(const Model& a, const Model& b)
  {
    const auto qa = a.shape().parameters();
    const auto qb = b.shape().parameters();
    const double size = qa.template head<3>().maxCoeff();
    const double cos_half_angle = std::abs(a.quaternion().dot(b.quaternion()));
    return (qb.template head<3>() - qa.template head<3>()).cwiseAbs().maxCoeff() <= 0.1 * size &&
           (qb.template tail<2>() - qa.template tail<2>()).cwiseAbs().maxCoeff() <= 0.25 &&
           (b.translation() - a.translation()).norm() <= 0.1 * size &&
           cos_half_angle >= std::cos(0.5 * 10. * CGAL_PI / 180.);
  }

  /// The iterations of all the short fits so far.
  std::size_t candidate_iterations() const { return m_candidate_iterations; }
  /// Of candidate_iterations(), those whose steps used all points
  /// (Fitting_status::iterations_on_all_points).
  std::size_t candidate_iterations_on_all_points() const { return m_candidate_iterations_on_all_points; }
  /// How the last rough fit ended (default-constructed before the first).
  const Fitting_status& last_candidate_status() const { return m_status; }
  /// Whether the callback aborted a short fit.
  bool aborted() const { return m_status.aborted; }

private:
  void count_candidate_iterations(const Fitting_status& st)
  {
    m_candidate_iterations += st.iterations;
    m_candidate_iterations_on_all_points += st.iterations_on_all_points;
  }

  struct Rough_fit
  {
    Model model;     // fitted
    double distance; // its mean squared distance to the rough subset
  };

  static std::vector<Model> similar_superquadrics(const Model& m)
  {
    std::vector<Model> similar;
    for(int swap = 0; swap < number_of_similar_superquadrics; ++swap)
      similar.push_back(similar_superquadric(m, swap));
    return similar;
  }

  // The rough fits of `starts` on the rough subset, in order, concurrently
  // on the threads of the settings. The visitor hears of each fit's
  // iterations after the group, in the order of the starts, so at any number
  // of threads it hears the same; the callback is called as the fits run,
  // one call at a time, and once it has returned false it is not called
  // again and every fit of the group stops at its next iteration.
  template <class Visitor>
  std::vector<Rough_fit> rough_fits(const std::vector<Model>& starts, Visitor& visitor, const Callback& callback)
  {
    std::vector<Rough_fit> fits(starts.size());
    std::vector<Fitting_status> status(starts.size());
    std::vector<internal::Recorded_fitting_visitor> heard(starts.size());
    internal::Shared_callback shared(callback);
    const Callback shared_callback = shared.function();
    m_tasks.for_each_task(starts.size(), [&](std::size_t i) {
      Fitter candidate(m_points, starts[i], m_rough, m_point_map);
      status[i] = candidate.run(heard[i], shared_callback, Fitting_phase::Subset);
      fits[i] = Rough_fit{candidate.model(), candidate.mean_squared_distance(false, m_truncation)};
    });
    bool aborted = false;
    for(std::size_t i = 0; i < starts.size(); ++i)
    {
      heard[i].replay(visitor);
      count_candidate_iterations(status[i]);
      aborted = aborted || status[i].aborted;
    }
    m_status = status.back();
    m_status.aborted = aborted;
    return fits;
  }

  // A challenger from `m`, fitted on the subset first (with looser
  // tolerances: only to compare): only one that ends closer there than
  // `best` goes on to all points (a few hundred points can be fitted closely
  // by a superquadric that is far from the rest of a partial view). Null if
  // it does not; `st` says how its last fit ended.
  template <class Visitor>
  std::unique_ptr<Fitter> fit_challenger(const Model& m, Fitter& best, Fitting_status& st, Visitor& visitor,
                                         const Callback& callback)
  {
    std::unique_ptr<Fitter> challenger = std::make_unique<Fitter>(m_points, m, m_challenger, m_point_map);
    st = challenger->run(visitor, callback, Fitting_phase::Subset);
    count_candidate_iterations(st);
    if(st.aborted)
      return challenger;
    if(!(challenger->mean_squared_distance(false, m_truncation) <
         0.99 * best.mean_squared_distance(false, m_truncation)))
      return nullptr;
    challenger = std::make_unique<Fitter>(m_points, challenger->model(), m_settings, m_point_map);
    st = challenger->run(visitor, callback);
    count_candidate_iterations(st);
    return challenger;
  }

  // With robust weighting, the candidates' squared distances are capped at
  // (5 % of the largest semi-axis of `m`)^2: strays far from every candidate
  // then add the same to each instead of deciding which wins (a stray's
  // squared distance dwarfs the differences between candidates). Set once per
  // search, so that all its comparisons use the same cap.
  void set_truncation(const Model& m)
  {
    m_truncation = m_settings.robust_weighting == Robust_weighting::None
                     ? HUGE_VAL
                     : 0.05 * m.shape().parameters().template head<3>().maxCoeff();
  }

  const PointRange& m_points;
  PointMap m_point_map;
  Fitting_settings m_settings;   // of the full fits
  Fitting_settings m_rough;      // of the rough fits
  Fitting_settings m_challenger; // of the challengers' fits on the subset
  std::size_t m_candidate_iterations = 0;
  std::size_t m_candidate_iterations_on_all_points = 0;
  double m_truncation = HUGE_VAL; // see set_truncation()
  // The rough fit whose similar superquadrics best_start() compared with it
  // and found farther (none if one was closer, or without best_start()).
  std::optional<Model> m_compared_basin;
  Fitting_status m_status; // of the last rough fit (aborted: if any of its group was)
  internal::Point_blocks m_tasks; // runs the rough fits of a group concurrently
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_SUPERQUADRIC_MULTISTART_SEARCH_H
