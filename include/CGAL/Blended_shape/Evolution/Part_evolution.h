// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_EVOLUTION_PART_EVOLUTION_H
#define CGAL_BLENDED_SHAPE_EVOLUTION_PART_EVOLUTION_H

#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Blending/Quotient_domain.h>
#include <CGAL/Blended_shape/Evolution/Force_regions.h>
#include <CGAL/Blended_shape/Evolution/Split_proposal.h>
#include <CGAL/Blended_shape/Evolution/internal/isolated_points.h>
#include <CGAL/Blended_shape/Fitting/Deformable_blended_model.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model_fitter.h>
#include <CGAL/Blended_shape/Fitting/Fitting_settings.h>
#include <CGAL/Blended_shape/Fitting/Fitting_visitor.h>
#include <CGAL/Blended_shape/IO/check_points.h>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeEvolution
/// The settings of part evolution (Part_evolution, fit_blended_shape()).
struct Evolution_settings
{
  /// No split is tried once the model has this many components (1: no evolution).
  std::size_t maximum_number_of_parts = 8;
  /// Evolution stops once the RMS distance of the points to the model, over
  /// the diagonal of their bounding box, is at most this (0: never).
  double target_accuracy = 0.;
  /// At each rest state, at most this many boundaries (in decreasing order of
  /// their flux difference) are tried before evolution ends.
  std::size_t maximum_split_tries = 3;
  /// `eps_F` of the force classes, in standard errors of the noise (Force_regions).
  double threshold_factor = 3.;
  /// The resolution of the chart meshes of the force analysis (Blended_shape_pieces).
  int analysis_resolution = 16;
};

/// \ingroup PkgBlendedShapeEvolution
/// What happened to the model's structure.
enum class Evolution_event_kind
{
  Split, ///< a split that paid for its parameters: kept
  Undo   ///< a split that did not: the model was restored exactly
};

/// \ingroup PkgBlendedShapeEvolution
/// One structural change tried by Part_evolution.
struct Evolution_event
{
  Evolution_event_kind kind = Evolution_event_kind::Split; ///< kept or undone
  std::size_t iteration = 0;  ///< fitting iterations done before the split
  std::size_t component = 0;  ///< the component split
  std::size_t new_component = 0; ///< the component the split added (gone again after an undo)
  std::size_t boundary = 0;   ///< the boundary curve of the force analysis it came from
  Split_proposal proposal;    ///< where
  double description_length_before = 0.; ///< of the model at rest before the split (see Part_evolution)
  double description_length_after = 0.;  ///< of the split model at rest
  double rms_before = 0.;     ///< RMS distance of the points to the model before the split
  double rms_after = 0.;      ///< the same after fitting the split model to rest
  bool accepted() const { return kind == Evolution_event_kind::Split; } ///< whether the split was kept
};

/// \ingroup PkgBlendedShapeEvolution
/// A visitor of part evolution with empty hooks: derive from it and override
/// what you need. The hooks of Default_fitting_visitor are called by every fit to rest.
struct Default_evolution_visitor : Default_fitting_visitor
{
  /// A split was kept; the model is the split one, at rest.
  void on_split(const Evolution_event& /*event*/) {}
  /// A split did not pay for its parameters and was undone.
  void on_undo(const Evolution_event& /*event*/) {}
};

/// \ingroup PkgBlendedShapeEvolution
/// How Part_evolution::run() ended.
struct Evolution_status
{
  std::size_t iterations = 0; ///< fitting iterations, over all fits to rest
  bool converged = false;     ///< the last fit to rest came to rest
  bool aborted = false;       ///< the callback returned false (the model is the last one kept)
  bool target_reached = false; ///< Evolution_settings::target_accuracy reached
  bool part_limit_reached = false; ///< Evolution_settings::maximum_number_of_parts reached
};

/*!
\ingroup PkgBlendedShapeEvolution

Part evolution (sec. 4.1, 5.4): a blended model fitted to points grows parts
where the forces at its rest state say it cannot fit the data. run() repeats,
until no split is kept:

1. fit to rest (Deformable_model_fitter);
2. the force analysis (Force_regions, equilibrated parts kept as regions)
   and up to `maximum_split_tries` split proposals (propose_split()), from
   the boundary with the largest flux difference down;
3. for each proposal in turn: split (apply_split(), `h = 0`: no point of the
   surface moves), fit to rest, and keep the split if it pays for its
   parameters, otherwise restore the model exactly and try the next one.

Whether a split pays for its parameters is a description-length test (the
paper has no stopping rule). With Gaussian residuals of unknown variance,
the two-part description length of the points given a model with `k` free
parameters is, up to terms that do not depend on the model,

  `L = (n/2) ln(MSD) + (k/2) ln(n)`,

`n` the number of points, `MSD` their mean squared distance to the model
at rest (Rissanen's MDL, which coincides with the Bayesian information
criterion). A split adds a component and a blend, about twenty parameters:
it is kept only if `L` falls. On 10000 points it must lower the mean
squared distance by 1.5 % or more; a split that only fits noise does not.

Stray points: the fits of evolution are least-squares fits (the paper's)
of the points that are not isolated: a point is isolated when its distance
to its 8th nearest neighbour is over four times the median of that distance
(stray points spread through a volume are far from their neighbours, the
points of a scanned surface are not). A robust fit's weights would not do:
they take the points of a part the model does not reach yet for strays,
which is exactly what must pull the model into a split.

Each phase is driven by run(), or step by step with fit_to_rest(),
propose_splits() and try_split(). The abort callback is passed to every fit;
when it stops the fit of a split model, the split is undone, so the model is
always one that was kept.

\tparam GeomTraits a CGAL kernel
*/
template <class GeomTraits>
class Part_evolution
{
public:
  typedef Deformable_blended_model<GeomTraits> Model; ///< the evolving model
  typedef Deformable_model_fitter<Model> Fitter;      ///< its fitter
  typedef typename GeomTraits::Point_3 Point_3;       ///< the point type

  /// Evolution of `initial` fitted to `points` (copied). The fits use
  /// `fitting` with least-squares weighting (see the class description).
  /// \throws Input_error if the points are unusable (check_points()).
  /// \throws std::invalid_argument on invalid settings.
  template <class PointRange, class PointMap = CGAL::Identity_property_map<Point_3>>
  Part_evolution(const PointRange& points, const Model& initial, const Fitting_settings& fitting = Fitting_settings(),
                 const Evolution_settings& evolution = Evolution_settings(), PointMap point_map = PointMap())
    : m_settings(evolution)
  {
    check_settings(evolution);
    check_points(points, point_map);
    std::vector<Eigen::Vector3d> all;
    for(const auto& item : points)
    {
      const auto& p = get(point_map, item);
      all.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }
    const std::vector<bool> isolated = internal::isolated_points(all);
    for(std::size_t i = 0; i < all.size(); ++i)
      if(isolated[i])
        m_isolated.push_back(i);
      else
        m_kept.push_back(Point_3(all[i].x(), all[i].y(), all[i].z()));
    Fitting_settings least_squares = fitting;
    least_squares.robust_weighting = Robust_weighting::None;
    m_fitter = std::make_unique<Fitter>(m_kept, initial, least_squares);
  }

  /// The current model: the last one kept.
  const Model& model() const { return m_fitter->model(); }
  /// The fitter of the current model (its points: those not isolated).
  Fitter& fitter() { return *m_fitter; }
  /// The settings.
  const Evolution_settings& settings() const { return m_settings; }
  /// The splits tried so far, kept or undone, in order.
  const std::vector<Evolution_event>& events() const { return m_events; }
  /// The indices (in the input order, increasing) of the points judged isolated: not fitted.
  const std::vector<std::size_t>& isolated_points() const { return m_isolated; }
  /// Fitting iterations done so far.
  std::size_t iterations() const { return m_iterations; }

  /// Fits the current model to rest; `callback` as for Deformable_model_fitter::run().
  template <class Visitor = Default_evolution_visitor>
  Fitting_status fit_to_rest(Visitor&& visitor = Visitor(),
                             const std::function<bool(double)>& callback = std::function<bool(double)>())
  {
    m_last_fit = m_fitter->run(visitor, callback);
    m_iterations += m_last_fit.iterations;
    m_rest_converged = m_last_fit.converged;
    return m_last_fit;
  }

  /// The description length `L = (n/2) ln(MSD) + (k/2) ln(n)` of the
  /// points given the current model (see the class description).
  double description_length()
  {
    const double n = double(m_fitter->number_of_points());
    // A floor far below any noise keeps the logarithm finite on exact data.
    const double msd = (std::max)(m_fitter->mean_squared_distance(true), 1e-300);
    return 0.5 * n * std::log(msd) + 0.5 * double(free_parameters()) * std::log(n);
  }

  /// The split proposals of the current model (which should be at rest):
  /// up to `maximum_split_tries`, from the boundaries of the force analysis
  /// in decreasing order of their flux difference (boundaries that give no
  /// valid region are skipped).
  std::vector<Split_proposal> propose_splits() const
  {
    const Model& model = m_fitter->model();
    const Blended_shape_pieces<GeomTraits> pieces(model.shape(), m_settings.analysis_resolution);
    const Quotient_domain<GeomTraits> domain(model.shape(), pieces, 1);
    const Force_regions<GeomTraits> regions(domain, normal_forces(*m_fitter, false), m_settings.threshold_factor,
                                            Equilibrated_regions::Kept);
    std::vector<Split_proposal> proposals;
    for(std::size_t b = 0; b < regions.boundaries().size() && proposals.size() < m_settings.maximum_split_tries; ++b)
      if(const std::optional<Split_proposal> p = propose_split(regions, b))
        proposals.push_back(*p);
    return proposals;
  }

  /*!
  Splits the current model (at rest) as `proposal` says, fits it to rest and
  keeps it if its description length falls; otherwise (or if the split is
  refused, or `callback` stops the fit) restores the model exactly. Records
  the event (not for a refused split) and calls the visitor's on_split() or
  on_undo(). Returns whether the split was kept.
  */
  template <class Visitor = Default_evolution_visitor>
  bool try_split(const Split_proposal& proposal, Visitor&& visitor = Visitor(),
                 const std::function<bool(double)>& callback = std::function<bool(double)>())
  {
    const Model before = m_fitter->model();
    const bool converged_before = m_rest_converged;
    Evolution_event e;
    e.iteration = m_iterations;
    e.component = proposal.component;
    e.new_component = before.shape().number_of_components();
    e.boundary = proposal.boundary;
    e.proposal = proposal;
    e.description_length_before = description_length();
    e.rms_before = std::sqrt(m_fitter->mean_squared_distance(true));
    try
    {
      m_fitter->restructure(apply_split(before, proposal));
    }
    catch(const std::invalid_argument&)
    {
      return false; // a region the shape refuses: nothing changed
    }
    const Fitting_status status = fit_to_rest(visitor, callback);
    e.description_length_after = description_length();
    e.rms_after = std::sqrt(m_fitter->mean_squared_distance(true));
    if(!status.aborted && e.description_length_after < e.description_length_before)
    {
      e.kind = Evolution_event_kind::Split;
      m_events.push_back(e);
      visitor.on_split(m_events.back());
      return true;
    }
    // Exactly the model before: its parameters and structure, and a fitter in
    // the state of a new one (Deformable_model_fitter::restructure()).
    m_fitter->restructure(before);
    m_rest_converged = converged_before;
    e.kind = Evolution_event_kind::Undo;
    m_events.push_back(e);
    visitor.on_undo(m_events.back());
    return false;
  }

  /// Evolves until no split is kept, the part limit, the target accuracy, or
  /// until `callback` returns false (see the class description).
  template <class Visitor = Default_evolution_visitor>
  Evolution_status run(Visitor&& visitor = Visitor(),
                       const std::function<bool(double)>& callback = std::function<bool(double)>())
  {
    Evolution_status status;
    const std::size_t start = m_iterations;
    fit_to_rest(visitor, callback);
    while(!m_last_fit.aborted)
    {
      if(m_settings.target_accuracy > 0. &&
         std::sqrt(m_fitter->mean_squared_distance(true)) <= m_settings.target_accuracy * m_fitter->bounding_box_diagonal())
      {
        status.target_reached = true;
        break;
      }
      if(model().shape().number_of_components() >= m_settings.maximum_number_of_parts)
      {
        status.part_limit_reached = true;
        break;
      }
      bool kept = false;
      for(const Split_proposal& p : propose_splits())
        if((kept = try_split(p, visitor, callback)) || m_last_fit.aborted)
          break;
      if(!kept)
        break;
    }
    status.iterations = m_iterations - start;
    status.aborted = m_last_fit.aborted;
    // After an undo the model is the one at rest before the split.
    status.converged = !status.aborted && m_rest_converged;
    return status;
  }

private:
  // The parameters that move in a fit (the fixed ones are not described).
  std::size_t free_parameters() const
  {
    const Model& m = m_fitter->model();
    std::size_t k = 0;
    for(std::size_t i = 0; i < m.number_of_parameters(); ++i)
      k += m.is_fixed_parameter(i) ? 0 : 1;
    return k;
  }

  static void check_settings(const Evolution_settings& s)
  {
    if(s.maximum_number_of_parts < 1)
      throw std::invalid_argument("Part_evolution: maximum_number_of_parts must be at least 1 (1: no evolution)");
    if(!(s.target_accuracy >= 0.) || !std::isfinite(s.target_accuracy))
      throw std::invalid_argument("Part_evolution: target_accuracy must be finite and >= 0 (0: no target), not " +
                                  std::to_string(s.target_accuracy));
    if(s.maximum_split_tries < 1)
      throw std::invalid_argument("Part_evolution: maximum_split_tries must be at least 1");
    if(!(s.threshold_factor > 0.) || !std::isfinite(s.threshold_factor))
      throw std::invalid_argument("Part_evolution: threshold_factor must be finite and > 0");
    if(s.analysis_resolution < 4)
      throw std::invalid_argument("Part_evolution: analysis_resolution must be at least 4");
  }

  Evolution_settings m_settings;
  std::vector<Point_3> m_kept;          // the points fitted (not isolated)
  std::vector<std::size_t> m_isolated;  // indices of the others
  std::unique_ptr<Fitter> m_fitter;
  std::vector<Evolution_event> m_events;
  std::size_t m_iterations = 0;
  Fitting_status m_last_fit;    // of the last fit to rest
  bool m_rest_converged = false; // whether the current model's fit came to rest
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_EVOLUTION_PART_EVOLUTION_H
