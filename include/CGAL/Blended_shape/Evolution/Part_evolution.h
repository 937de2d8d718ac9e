// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_EVOLUTION_PART_EVOLUTION_H
#define CGAL_BLENDED_SHAPE_EVOLUTION_PART_EVOLUTION_H

#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Blending/Quotient_domain.h>
#include <CGAL/Blended_shape/Evolution/Branch_segments.h>
#include <CGAL/Blended_shape/Evolution/Crease_segments.h>
#include <CGAL/Blended_shape/Evolution/Evolution_settings.h>
#include <CGAL/Blended_shape/Evolution/Force_regions.h>
#include <CGAL/Blended_shape/Evolution/Split_proposal.h>
#include <CGAL/Blended_shape/Fitting/Deformable_blended_model.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model_fitter.h>
#include <CGAL/Blended_shape/Fitting/Fitting_settings.h>
#include <CGAL/Blended_shape/Fitting/Fitting_visitor.h>
#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <CGAL/Blended_shape/IO/check_points.h>
#include <CGAL/Blended_shape/internal/isolated_points.h>

#include <CGAL/centroid.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeEvolution
/// What happened to the model's structure.
enum class Evolution_event_kind
{
  Split, ///< a split that paid for its parameters: kept
  Undo,  ///< a split that did not: the model was restored exactly
  Remove, ///< a part that no longer paid for its parameters: merged back into its base (Blended_shape::merge_split())
  /// Split_source::Branch_segments: the evolved model did not pay for its
  /// parameters against the model the evolution was made with, fitted to
  /// rest on all the points: that model replaced it (see Part_evolution)
  Revert
};

/// \ingroup PkgBlendedShapeEvolution
/// One structural change tried by Part_evolution: a split kept or undone,
/// or a part removed.
struct Evolution_event
{
  Evolution_event_kind kind = Evolution_event_kind::Split; ///< kept, undone, removed or reverted
  std::size_t iteration = 0;  ///< fitting iterations done before the event
  std::size_t component = 0;  ///< the component split (Remove: the component removed; Revert: 0)
  std::size_t new_component = 0; ///< the component the split added (gone again after an undo; Remove: 0)
  std::size_t boundary = 0;   ///< the boundary curve of the force analysis it came from (Remove: 0; from a crease segment: Split_proposal::none, see `proposal.segment`)
  Split_proposal proposal;    ///< where (Remove: the default)
  double description_length_before = 0.; ///< of the model at rest before the event (see Part_evolution)
  double description_length_after = 0.;  ///< of the split model at rest (Remove: of the model without the part, not refitted; Revert: of the model that replaced the evolved one, at rest)
  double rms_before = 0.;     ///< RMS distance of the points to the model before the event
  double rms_after = 0.;      ///< the same after it (for a split, after fitting the split model to rest)
  bool accepted() const { return kind == Evolution_event_kind::Split; } ///< whether it is a split that was kept
};

/// \ingroup PkgBlendedShapeEvolution
/// The name of an event kind, for output: "split", "undo", "remove", "revert".
inline const char* evolution_event_name(Evolution_event_kind k)
{
  switch(k)
  {
  case Evolution_event_kind::Split: return "split";
  case Evolution_event_kind::Undo: return "undo";
  case Evolution_event_kind::Remove: return "remove";
  case Evolution_event_kind::Revert: return "revert";
  }
  return "unknown";
}

/// \ingroup PkgBlendedShapeEvolution
/// The phases of Part_evolution::run(), as Default_evolution_visitor::on_evolution_phase() hears of them.
enum class Evolution_phase
{
  Fit_to_rest,     ///< the current model is fitted to rest (Part_evolution::fit_to_rest()): at the start, and after parts were removed
  Split_proposals, ///< the model at rest is analysed and splits proposed (Part_evolution::propose_splits(): force regions or crease segments, Evolution_settings::split_source)
  Split_fit        ///< a split model is fitted to rest, to be kept or undone (Part_evolution::try_split())
};

/// \ingroup PkgBlendedShapeEvolution
/// The name of a phase, for progress output: "fit to rest", "split proposals", "fit of a split model".
inline const char* evolution_phase_name(Evolution_phase p)
{
  switch(p)
  {
  case Evolution_phase::Fit_to_rest: return "fit to rest";
  case Evolution_phase::Split_proposals: return "split proposals";
  default: return "fit of a split model";
  }
}

/// \ingroup PkgBlendedShapeEvolution
/// A visitor of part evolution with empty hooks: derive from it and override
/// what you need. The hooks of Default_fitting_visitor are called by every fit to rest.
struct Default_evolution_visitor : Default_fitting_visitor
{
  /// Evolution enters `phase`; `parts` is the number of components of the current model.
  void on_evolution_phase(Evolution_phase /*phase*/, std::size_t /*parts*/) {}
  /// A split was kept; `model` (a Deformable_blended_model) is the split one, at rest.
  template <class Model>
  void on_split(const Evolution_event& /*event*/, const Model& /*model*/) {}
  /// A split did not pay for its parameters and was undone, or (Evolution_event_kind::Revert)
  /// the evolved model did not pay against the one evolution started from; `model` is the one restored.
  template <class Model>
  void on_undo(const Evolution_event& /*event*/, const Model& /*model*/) {}
  /// A part no longer paid for its parameters and was removed; `model` is the one without it (not yet refitted).
  template <class Model>
  void on_remove(const Evolution_event& /*event*/, const Model& /*model*/) {}
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

namespace internal {

// The evolution hooks of a visitor, called if it has them: any fitting
// visitor (Default_fitting_visitor) can watch an evolution.
template <class Visitor, class Model, class = void>
struct Has_evolution_hooks : std::false_type
{};
template <class Visitor, class Model>
struct Has_evolution_hooks<
  Visitor, Model,
  std::void_t<decltype(std::declval<Visitor&>().on_split(std::declval<const Evolution_event&>(), std::declval<const Model&>())),
              decltype(std::declval<Visitor&>().on_undo(std::declval<const Evolution_event&>(), std::declval<const Model&>()))>>
  : std::true_type
{};

template <class Visitor, class Model, class = void>
struct Has_remove_hook : std::false_type
{};
template <class Visitor, class Model>
struct Has_remove_hook<Visitor, Model,
                       std::void_t<decltype(std::declval<Visitor&>().on_remove(std::declval<const Evolution_event&>(),
                                                                               std::declval<const Model&>()))>>
  : std::true_type
{};

template <class Visitor, class Model>
void notify_event(Visitor& visitor, const Evolution_event& e, const Model& model)
{
  if(e.kind == Evolution_event_kind::Remove)
  {
    if constexpr(Has_remove_hook<Visitor, Model>::value)
      visitor.on_remove(e, model);
  }
  else if constexpr(Has_evolution_hooks<Visitor, Model>::value)
  {
    if(e.accepted())
      visitor.on_split(e, model);
    else
      visitor.on_undo(e, model);
  }
}

template <class Visitor, class = void>
struct Has_evolution_phase_hook : std::false_type
{};
template <class Visitor>
struct Has_evolution_phase_hook<Visitor, std::void_t<decltype(std::declval<Visitor&>().on_evolution_phase(
                                           Evolution_phase::Fit_to_rest, std::size_t(0)))>> : std::true_type
{};

template <class Visitor>
void notify_phase(Visitor& visitor, Evolution_phase phase, std::size_t parts)
{
  if constexpr(Has_evolution_phase_hook<Visitor>::value)
    visitor.on_evolution_phase(phase, parts);
}

// The hooks of an evolution visitor behind one virtual interface: evolution
// (and the fits it makes) hears every visitor through it, so that its code
// is compiled once per model type whatever the visitors (the cost: an
// indirect call per hook, a few per fitting iteration).
template <class Model>
class Evolution_listener
{
public:
  virtual ~Evolution_listener() = default;
  virtual void on_phase(Fitting_phase phase, std::size_t iteration) = 0;
  virtual void on_iteration(std::size_t iteration, double energy, std::size_t points_used) = 0;
  virtual void on_evolution_phase(Evolution_phase phase, std::size_t parts) = 0;
  virtual void on_split(const Evolution_event& e, const Model& model) = 0;
  virtual void on_undo(const Evolution_event& e, const Model& model) = 0;
  virtual void on_remove(const Evolution_event& e, const Model& model) = 0;
};

// A visitor heard through Evolution_listener: its evolution hooks are
// called if it has them (notify_phase(), notify_event()).
template <class Visitor, class Model>
class Evolution_listener_of : public Evolution_listener<Model>
{
public:
  explicit Evolution_listener_of(Visitor& visitor) : m_visitor(visitor) {}
  void on_phase(Fitting_phase phase, std::size_t iteration) override { m_visitor.on_phase(phase, iteration); }
  void on_iteration(std::size_t iteration, double energy, std::size_t points_used) override
  {
    m_visitor.on_iteration(iteration, energy, points_used);
  }
  void on_evolution_phase(Evolution_phase phase, std::size_t parts) override { notify_phase(m_visitor, phase, parts); }
  void on_split(const Evolution_event& e, const Model& model) override { notify_event(m_visitor, e, model); }
  void on_undo(const Evolution_event& e, const Model& model) override { notify_event(m_visitor, e, model); }
  void on_remove(const Evolution_event& e, const Model& model) override { notify_event(m_visitor, e, model); }

protected:
  Visitor& m_visitor;
};

// `f(listener)`, with `visitor` as an Evolution_listener (itself if it is one).
template <class Model, class Visitor, class F>
decltype(auto) with_listener(Visitor& visitor, const F& f)
{
  if constexpr(std::is_base_of_v<Evolution_listener<Model>, Visitor>)
    return f(static_cast<Evolution_listener<Model>&>(visitor));
  else
  {
    Evolution_listener_of<Visitor, Model> listener(visitor);
    return f(static_cast<Evolution_listener<Model>&>(listener));
  }
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeEvolution

Part evolution (sec. 4.1, 5.4): a blended model fitted to points grows parts
where its rest state says it cannot fit the data. run() repeats, until no
split is kept:

1. fit to rest (Deformable_model_fitter);
2. up to `maximum_split_tries` split proposals, from where
   Evolution_settings::split_source says: the crease segments of the data
   (the default: a part fitted to a piece of the data between concave
   creases, propose_segment_split(), blended in gradually, see
   propose_splits()), or the force analysis (Force_regions, equilibrated
   parts kept as regions; propose_split(), from the boundary with the
   largest flux difference down, one per pair of regions), or both;
3. for each proposal in turn: split (apply_split(), `h = 0`: no point of the
   surface moves; a crease segment's part comes in over
   Evolution_settings::blend_stages stages, first_split_blend_stages for
   the first split), fit to rest, and keep the split if it pays for its
   parameters, otherwise restore the model exactly and try the next one;
4. after a split is kept, remove the parts that no longer pay for their
   parameters (remove_unpaid_parts()) and fit to rest again if any went.

Whether a split pays for its parameters is a description-length test (the
paper has no stopping rule). With Gaussian residuals of unknown variance,
the two-part description length of the points given a model with `k` free
parameters is, up to terms that do not depend on the model,

  `L = (n/2) ln(MSD) + (k/2) ln(n)`,

`n` the number of points (described_points()), `MSD` their mean squared distance to the model
at rest (as mean_squared_distance() measures it) (Rissanen's MDL, which coincides with the Bayesian information
criterion). A split adds a component and a blend, about twenty parameters:
it is kept only if `L` falls. On 10000 points it must lower the mean
squared distance by 1.5 % or more; a split that only fits noise does not.
The same test removes a part: a part whose region has shrunk to nothing,
or that hides inside its base, or that later parts made redundant, is
merged back into its base (Blended_shape::merge_split()) when the model
without it, as it is, has a description length no larger.

Stray points: the fits of evolution are least-squares fits (the paper's)
of the points that are not isolated: a point is isolated when its distance
to its 8th nearest neighbour is over four times the median of that distance
(stray points spread through a volume are far from their neighbours, the
points of a scanned surface are not). A robust fit's weights would not do:
they take the points of a part the model does not reach yet for strays,
which is exactly what must pull the model into a split.

Branches (Split_source::Branch_segments): a body's limbs meet it without a
concave crease, and a model fitted to all the points is pulled by every
limb it does not have yet (a body fitted with its arms is a plate). With
this source the fits see the points of the branches joined so far
(branch_segments(), joined_points()): the central branch (the largest
branch without a parent; branches of fewer than `minimum_segment_share`
of the points belong to their nearest larger ancestor, the other
connected pieces grow from the central branch) when the evolution is
made, fitted with a superquadric of its own at the start of the first run()
(fit_superquadric(), least squares; the model given serves the steps
driven by hand). propose_splits() proposes the largest branch not joined
whose parent is; try_split() first joins it (the model fitted to rest on
the points with it), then tries its split as for a crease segment and
keeps it if it pays: the split is judged against the model without a part
fitted to the same points, and an undone split leaves the branch joined
without a part. run() tries each branch once, in that order; the branches
left at the part limit or the target accuracy are joined without parts, so
that the model ends fitted to all the points. The description length then
counts the share of the points the fits see (described_points()). Fits that
start from a part of the points can end in a worse basin than one
superquadric fitted to all of them (a box seen from one side: its central
branch is a flat patch, whose superquadric grows to the size bound): at the
end of run(), the model the evolution was made with (in fit_blended_shape(),
the least-squares superquadric of all the points), fitted to rest on all the
points, replaces the evolved one if its description length is no larger
(an Evolution_event_kind::Revert event; the visitor's on_undo()).

Rest states: the fits of evolution (and the fit of a crease segment's
part) wait at a rest state for the damping to grow until the step is
negligible (Fitting_settings::settling_tolerance 0), whatever the settings
given say. Which splits are kept depends on the last bits of every rest
state, and the splits of the results in the manual were measured with
those rests: settled earlier (`settling_tolerance` 1e-3), evolution took
about half the time, but the box/cylinder scan's force splits ended at 2
parts and RMS_3 5.1 % (8 parts, 2.3 %), the mannequin's at RMS_3 6.7 %
(5.8 %), its crease splits at RMS_3 9.5 % (7.4 %). fit_blended_shape()
settles the final fit on all points, which decides nothing. A crease
segment's part (fit_superquadric(), robust) keeps the full fits' noise
ceiling in the rough fits of its search too
(Fitting_settings::candidate_noise_ceiling set to `noise_ceiling`): with
the wider default there, `reproduce_paper --evolve` gave the mannequin 2
parts at RMS_3 12.8 % (5 parts, 6.3 %) on 5 of 6 seeds; and it does not
mend missed surfaces (fit_superquadric()'s `mend_missed_surfaces` false):
a segment is cut at creases, and what its part leaves out stays with the
base or a later split; with the mend (`reproduce_paper --evolve`, seeds 0
to 5) the CAD mug got 4 parts on two seeds (2 without), the mannequin the
same parts, the real mug's parts and RMS moved both ways. Likewise
evolution's fresh closest-point sweeps (the measure of a model before and
after a split, a part removed) start from the tessellation alone
(Fitting_settings::projection_start_samples 0): with the sampled starts,
which find closer foot points on models with blends, the mannequin's
crease splits ended farther from the body on each of four seeds (see the
manual, Closest Points of a Blended Model).

Each phase is driven by run(), or step by step with fit_to_rest(),
propose_splits() and try_split(). The abort callback is passed to every fit;
when it stops the fit of a split model, the split is undone, so the model is
always one that was kept (or, if it stops the fit after a removal, the model
without the removed part, not yet at rest). The visitor is any fitting visitor
(Default_fitting_visitor); its `on_split()` and `on_undo()` are called if it
has both, its `on_remove()` if it has it (Default_evolution_visitor).

\tparam GeomTraits a CGAL kernel
*/
template <class GeomTraits>
class Part_evolution
{
public:
  typedef Deformable_blended_model<GeomTraits> Model; ///< the evolving model
  typedef Deformable_model_fitter<Model> Fitter;      ///< its fitter
  typedef typename GeomTraits::Point_3 Point_3;       ///< the point type

  /// The `settling_tolerance` of every fit of evolution (and of the first
  /// fit it starts from, fit_blended_shape()): 0, a rest state waits for the
  /// damping (see the class description).
  static constexpr double settling_tolerance = 0.;

  /// Evolution of `initial` fitted to `points` (copied). The fits use
  /// `fitting` with least-squares weighting and `settling_tolerance` 0 (see
  /// the class description), on all points at every step (no subset phase).
  /// \throws Input_error if the points are unusable (check_points()).
  /// \throws std::invalid_argument on invalid settings.
  template <class PointRange, class PointMap = CGAL::Identity_property_map<Point_3>>
  Part_evolution(const PointRange& points, const Model& initial, const Fitting_settings& fitting = Fitting_settings(),
                 const Evolution_settings& evolution = Evolution_settings(), PointMap point_map = PointMap())
    : m_settings(evolution)
  {
    check_evolution_settings(evolution, "Part_evolution");
    check_points(points, point_map);
    std::vector<Eigen::Vector3d> all;
    for(const auto& item : points)
    {
      const auto& p = get(point_map, item);
      all.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }
    const std::vector<bool> isolated = internal::isolated_points(all);
    std::vector<Eigen::Vector3d> kept;
    for(std::size_t i = 0; i < all.size(); ++i)
      if(isolated[i])
        m_isolated.push_back(i);
      else
      {
        m_kept.push_back(Point_3(all[i].x(), all[i].y(), all[i].z()));
        kept.push_back(all[i]);
      }
    if(m_settings.split_source == Split_source::Branch_segments)
    {
      m_initial = initial;
      join_central_branch(kept);
    }
    else
    {
      m_joined.resize(m_kept.size());
      std::iota(m_joined.begin(), m_joined.end(), std::size_t(0));
      m_points = m_kept;
    }
    Fitting_settings least_squares = fitting;
    least_squares.robust_weighting = Robust_weighting::None;
    least_squares.subset_size = 0;
    least_squares.settling_tolerance = settling_tolerance;
    // Evolution's decisions were settled with the tessellation's starts
    // alone; the sampled ones, closer foot points of fresh sweeps, took the
    // mannequin's model farther from the body (see the manual, Closest Points
    // of a Blended Model).
    least_squares.projection_start_samples = 0;
    m_fitter = std::make_unique<Fitter>(m_points, initial, least_squares);
  }

  /// The current model: the last one kept.
  const Model& model() const { return m_fitter->model(); }
  /// The fitter of the current model (its points: those not isolated; with
  /// Split_source::Branch_segments, those of the branches joined so far).
  Fitter& fitter()
  {
    ++m_version; // the caller may move the model
    return *m_fitter;
  }
  /// The settings.
  const Evolution_settings& settings() const { return m_settings; }
  /// The events so far (splits kept or undone, parts removed), in order.
  const std::vector<Evolution_event>& events() const { return m_events; }
  /// The indices (in the input order, increasing) of the points judged isolated: not fitted.
  const std::vector<std::size_t>& isolated_points() const { return m_isolated; }
  /// Fitting iterations done so far.
  std::size_t iterations() const { return m_iterations; }

  /// The number of points `n` the description length counts (see the class
  /// description): the points fitted, unless set_described_points() set it.
  /// With Split_source::Branch_segments, the share of them in the branches
  /// joined so far (the points the split test compares the models on).
  std::size_t described_points() const
  {
    const std::size_t n = m_described_points > 0 ? m_described_points : m_kept.size();
    if(m_points.size() == m_kept.size())
      return n;
    return std::size_t(std::llround(double(n) * double(m_points.size()) / double(m_kept.size())));
  }
  /// The indices (in the order of the points not isolated, increasing) of
  /// the points the fits see now: all of them, except with
  /// Split_source::Branch_segments, where they are the branches joined so far.
  const std::vector<std::size_t>& joined_points() const { return m_joined; }
  /// Counts `n` points in the description length instead of the points
  /// fitted (0: those), as when the points given are an even sample of `n`
  /// (fit_blended_shape() with Evolution_settings::maximum_evolution_points):
  /// a split must then lower the mean squared distance as much as on all of
  /// them. Call it before run().
  void set_described_points(std::size_t n) { m_described_points = n; }

  /// Fits the current model to rest; `callback` as for Deformable_model_fitter::run().
  template <class Visitor = Default_evolution_visitor>
  Fitting_status fit_to_rest(Visitor&& visitor = Visitor(),
                             const std::function<bool(double)>& callback = std::function<bool(double)>())
  {
    return internal::with_listener<Model>(visitor, [&](Listener& l) { return fit_to_rest_heard(l, callback); });
  }

  /// The mean squared distance of the points to the current model, as
  /// evolution measures it: the smaller of the fitter's (its closest points
  /// followed from the last fit) and that of a fresh search (from the
  /// model's mesh, as a new fitter finds them). Both are distances to points
  /// of the surface, so the smaller is the closer to the true value. Either
  /// alone misses some closest points by about 1 % of the mean squared
  /// distance, as much as a split must gain, and a split model's search
  /// starts afresh: measured by one method before a split and by the other
  /// after it, splits would be judged on search errors.
  double mean_squared_distance()
  {
    // The fresh search costs as much as a fitter: measured once per state of
    // the current fitter (the proposals of one rest state share the measure
    // before their split; an undo brings it back with the fitter).
    if(m_measured.version != m_version)
      m_measured = Measure{m_version, mean_squared_distance_of(*m_fitter)};
    return m_measured.value;
  }

  /// The description length `L = (n/2) ln(MSD) + (k/2) ln(n)` of the
  /// points given the current model (see the class description), with the
  /// mean squared distance of mean_squared_distance().
  double description_length() { return description_length_of(mean_squared_distance(), m_fitter->model()); }

  /*!
  Removes the parts that no longer pay for their parameters: for each
  component added by a split on which no blend is based (last first), the
  model without it (Blended_shape::merge_split(), the other parameters as
  they are) replaces the current one if its description length is no
  larger. Records an `Evolution_event_kind::Remove` event and calls the
  visitor's on_remove() for each. The model is then no longer at rest: fit
  it again (run() does). Returns the number of parts removed.

  The model with the part is measured as mean_squared_distance() does (the
  smaller of the followed and a fresh search), the one without it by a
  fresh search only (its fitter is new): this leans towards keeping a part,
  by the search errors that the class description puts at about 1 % of the
  mean squared distance.
  */
  template <class Visitor = Default_evolution_visitor>
  std::size_t remove_unpaid_parts(Visitor&& visitor = Visitor())
  {
    return internal::with_listener<Model>(visitor, [&](Listener& l) { return remove_unpaid_parts_heard(l); });
  }

  /// The split proposals of the current model (which should be at rest),
  /// up to `maximum_split_tries`, from the sources `split_source` says:
  /// - crease segments (first, if both): the segments of at least
  ///   minimum_segment_share of the points in decreasing size, except the
  ///   largest (the body the others grow from), each giving the split of
  ///   propose_segment_split(); the segments are those of the points and
  ///   the model when proposals were first asked for (crease_segments(),
  ///   outward directions: the model's normals at the points' closest points;
  ///   if that gives no segment to split off, the normals oriented
  ///   consistently, Crease_segment_settings::propagate_orientation: a
  ///   model far from the points can turn some normals inwards, and kept
  ///   for all proposals, the propagated orientation would join the
  ///   mannequin's limbs, which the model's normals cut apart);
  /// - force regions: the boundaries of the force analysis in decreasing
  ///   order of their flux difference, one per pair of regions (the curves
  ///   between the same two regions give the same centre: propose_split());
  ///
  /// each shrunk about its centre where the shape refuses its region
  /// (shrink_to_fit()); those that give no region the shape accepts are skipped.
  std::vector<Split_proposal> propose_splits() const
  {
    std::vector<Split_proposal> proposals;
    if(m_settings.split_source == Split_source::Branch_segments)
    {
      if(const std::optional<std::size_t> s = next_branch())
        proposals.push_back(branch_proposal(*s));
      return proposals;
    }
    if(m_settings.split_source != Split_source::Force_regions)
      proposals = propose_segment_splits();
    if(m_settings.split_source == Split_source::Crease_segments)
      return proposals;
    const Model& model = m_fitter->model();
    const Blended_shape_pieces<GeomTraits> pieces(model.shape(), m_settings.analysis_resolution);
    const Quotient_domain<GeomTraits> domain(model.shape(), pieces, 1);
    const Force_regions<GeomTraits> regions(domain, normal_forces(*m_fitter, false), m_settings.threshold_factor,
                                            Equilibrated_regions::Kept);
    for(std::size_t b = 0; b < regions.boundaries().size() && proposals.size() < m_settings.maximum_split_tries; ++b)
    {
      // The curves between the same two regions give one proposal (the
      // centre is the new part's region's, the ellipse is fitted to all of
      // them): only the first is tried.
      const auto& pair = regions.boundaries()[b].regions;
      bool seen = false;
      for(std::size_t a = 0; a < b && !seen; ++a)
        seen = regions.boundaries()[a].regions == pair;
      if(seen)
        continue;
      if(const std::optional<Split_proposal> p = propose_split(regions, b))
        if(const std::optional<Split_proposal> fitted = shrink_to_fit(model.shape(), *p))
          proposals.push_back(*fitted);
    }
    return proposals;
  }

  /// Crease segments smaller than this share of the points give no split proposal.
  static constexpr double minimum_segment_share = 0.03;

  /*!
  Splits the current model (at rest) as `proposal` says, fits it to rest and
  keeps it if its description length falls; otherwise (or if the split is
  refused, or `callback` stops the fit) restores the model exactly. With
  Split_source::Branch_segments, a proposal of a branch not yet joined joins
  it first (the current model fitted to rest on the points with it; stopped
  by `callback`, the model and its points as before and `false`), and the
  model restored is that one. A
  proposal from a crease segment (`proposal.segment`) first gives the model
  a base that fits the points outside the segment: when the model is one
  superquadric, a new one fitted to those points (fit_superquadric(), least
  squares) with its poles turned towards the segment (pole_towards());
  otherwise the model fitted to rest on them (each projection starting from
  the point's foot point on the model). Then it adds a superquadric fitted
  to the segment's points as a gradual part (add_gradual_part(), in the
  region where the part meets the base, region_inside_part(), or where that
  has none the region propose_segment_split() gives on the base) and lowers
  its `h` in `blend_stages` stages (`first_split_blend_stages` for the first
  split), each fitted with `h` and the part held
  (for at most `intermediate_stage_iterations` iterations, or
  `first_split_stage_iterations`), then fits to rest
  with `h` and the part free, the region's curve held where the proposal
  put it: the part comes in by steps of `h` of `1 / blend_stages` (each
  moves the surface inside the region that share of the way from the base
  towards the part), never all at once. (The first split's new base does
  replace the one superquadric at once, before the part comes in.) Any other
  proposal is a split at `h = 0` (apply_split()). Records
  the event (not for a refused split) and calls the visitor's on_split() or
  on_undo(). Returns whether the split was kept.
  */
  template <class Visitor = Default_evolution_visitor>
  bool try_split(const Split_proposal& proposal, Visitor&& visitor = Visitor(),
                 const std::function<bool(double)>& callback = std::function<bool(double)>())
  {
    return internal::with_listener<Model>(visitor, [&](Listener& l) { return try_split_heard(proposal, l, callback); });
  }

  /// Evolves until no split is kept, the part limit, the target accuracy, or
  /// until `callback` returns false (see the class description).
  template <class Visitor = Default_evolution_visitor>
  Evolution_status run(Visitor&& visitor = Visitor(),
                       const std::function<bool(double)>& callback = std::function<bool(double)>())
  {
    return internal::with_listener<Model>(visitor, [&](Listener& l) { return run_heard(l, callback); });
  }

private:
  typedef internal::Evolution_listener<Model> Listener;

  // The bodies of fit_to_rest(), remove_unpaid_parts(), try_split() and
  // run(), which hear every visitor through a Listener.
  Fitting_status fit_to_rest_heard(Listener& visitor, const std::function<bool(double)>& callback)
  {
    m_last_fit = m_fitter->run(visitor, callback);
    ++m_version;
    m_iterations += m_last_fit.iterations;
    m_rest_converged = m_last_fit.converged;
    return m_last_fit;
  }

  std::size_t remove_unpaid_parts_heard(Listener& visitor)
  {
    std::size_t removed = 0;
    double msd_before = -1.; // measured when first needed
    for(std::size_t c = model().shape().number_of_components(); c-- > 1;)
    {
      Blended_shape<GeomTraits> without = model().shape();
      try
      {
        without.merge_split(c);
      }
      catch(const std::logic_error&)
      {
        continue; // not a split part, or others are built on it
      }
      auto merged = std::make_unique<Fitter>(m_points, Model(without, model().translation(), model().quaternion()),
                                             m_fitter->settings());
      Evolution_event e;
      e.kind = Evolution_event_kind::Remove;
      e.iteration = m_iterations;
      e.component = c;
      if(msd_before < 0.)
        msd_before = mean_squared_distance();
      // `merged` is new: its search is the fresh one (mean_squared_distance_of()
      // would make an identical second fitter).
      const double msd_after = merged->mean_squared_distance(true);
      set_measures(e, msd_before, model(), msd_after, merged->model());
      if(!(e.description_length_after <= e.description_length_before))
        continue;
      m_fitter = std::move(merged);
      ++m_version;
      m_rest_converged = false;
      msd_before = msd_after;
      m_events.push_back(e);
      internal::notify_event(visitor, m_events.back(), model());
      ++removed;
    }
    return removed;
  }

  bool try_split_heard(const Split_proposal& proposal, Listener& visitor, const std::function<bool(double)>& callback)
  {
    // A branch not yet joined is joined first: the split is then judged
    // against the model without it fitted to the same points.
    if(m_settings.split_source == Split_source::Branch_segments && proposal.segment < m_branch_joined.size() &&
       !m_branch_joined[proposal.segment])
    {
      internal::notify_phase(visitor, Evolution_phase::Fit_to_rest, model().shape().number_of_components());
      if(join_branches({proposal.segment}, visitor, callback).aborted)
        return false;
    }
    const bool converged_before = m_rest_converged;
    Evolution_event e;
    e.iteration = m_iterations;
    e.component = proposal.component;
    e.new_component = m_fitter->model().shape().number_of_components();
    e.boundary = proposal.boundary;
    e.proposal = proposal;
    const double msd_before = mean_squared_distance();
    e.description_length_before = description_length_of(msd_before, model());
    e.rms_before = std::sqrt(msd_before);
    const std::size_t version_before = m_version;
    const Measure measured_before = m_measured;
    // The split model gets a fitter of its own; the one at rest before stays
    // as it is, to come back to.
    std::unique_ptr<Fitter> before;
    const bool gradual = proposal.segment != Split_proposal::none;
    std::vector<Chart_point> base_foot_points; // of a gradual part's base: where its fits start
    std::optional<Stage_plan> plan;              // of a gradual part's stages
    if(gradual) // (its fits start with the base's)
      internal::notify_phase(visitor, Evolution_phase::Split_fit, m_fitter->model().shape().number_of_components() + 1);
    try
    {
      std::optional<Model> split = gradual ? with_gradual_part(proposal, base_foot_points, visitor, callback)
                                           : std::optional<Model>(apply_split(m_fitter->model(), proposal));
      if(!split)
        return false; // stopped before anything changed
      std::unique_ptr<Fitter> next;
      if(gradual)
      {
        plan = stage_plan(*split);
        next = stage_fitter(*split, 1, *plan, m_fitter->settings());
        next->start_from_chart_points(base_foot_points);
      }
      else
        next = std::make_unique<Fitter>(m_points, *split, m_fitter->settings());
      before = std::exchange(m_fitter, std::move(next));
    }
    catch(const std::invalid_argument&)
    {
      return false; // a region the shape refuses: nothing changed
    }
    ++m_version;
    if(!gradual) // the same surface: its closest points still are
    {
      m_fitter->start_from_foot_points_of(
        *before, charts_moved_by_split(before->model(), m_fitter->model(), proposal.component));
      internal::notify_phase(visitor, Evolution_phase::Split_fit, m_fitter->model().shape().number_of_components());
    }
    const Fitting_status status =
      gradual ? blend_in_stages(*plan, before->settings(), visitor, callback) : fit_to_rest_heard(visitor, callback);
    const double msd_after = mean_squared_distance();
    e.description_length_after = description_length_of(msd_after, model());
    e.rms_after = std::sqrt(msd_after);
    if(!status.aborted && e.description_length_after < e.description_length_before)
    {
      e.kind = Evolution_event_kind::Split;
      m_events.push_back(e);
      internal::notify_event(visitor, m_events.back(), m_fitter->model());
      return true;
    }
    // Exactly as before: the model (parameters and structure) and its fitter
    // with the closest points it followed.
    m_fitter = std::move(before);
    m_version = version_before;
    m_measured = measured_before;
    m_rest_converged = converged_before;
    e.kind = Evolution_event_kind::Undo;
    m_events.push_back(e);
    internal::notify_event(visitor, m_events.back(), m_fitter->model());
    return false;
  }

  Evolution_status run_heard(Listener& visitor, const std::function<bool(double)>& callback)
  {
    Evolution_status status;
    const std::size_t start = m_iterations;
    const bool branches = m_settings.split_source == Split_source::Branch_segments;
    internal::notify_phase(visitor, Evolution_phase::Fit_to_rest, model().shape().number_of_components());
    if(branches && !m_central_branch_fitted)
      start_from_central_branch_fit(callback);
    if(!m_last_fit.aborted)
      fit_to_rest_heard(visitor, callback);
    while(!m_last_fit.aborted)
    {
      if(m_settings.target_accuracy > 0. &&
         std::sqrt(mean_squared_distance()) <= m_settings.target_accuracy * m_fitter->bounding_box_diagonal())
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
      const std::size_t parts_before = model().shape().number_of_components();
      internal::notify_phase(visitor, Evolution_phase::Split_proposals, parts_before);
      const std::vector<Split_proposal> proposals = propose_splits();
      for(const Split_proposal& p : proposals)
        if((kept = try_split_heard(p, visitor, callback)) || m_last_fit.aborted)
          break;
      if(m_last_fit.aborted)
        break;
      if(!kept)
      {
        // A branch whose split did not pay is joined all the same: the next one.
        if(branches && !proposals.empty())
          continue;
        break;
      }
      if(remove_unpaid_parts_heard(visitor) > 0)
      {
        internal::notify_phase(visitor, Evolution_phase::Fit_to_rest, model().shape().number_of_components());
        fit_to_rest_heard(visitor, callback);
        // No more parts than before the split (the split part itself went):
        // no progress, and the next round could propose the same split again.
        if(model().shape().number_of_components() <= parts_before)
          break;
      }
    }
    // The branches left (at the part limit or the target accuracy) are joined
    // without parts, so that the model ends fitted to all the points.
    if(branches && !m_last_fit.aborted && m_points.size() < m_kept.size())
    {
      std::vector<std::size_t> rest;
      for(std::size_t s = 0; s < m_branch_joined.size(); ++s)
        if(!m_branch_joined[s])
          rest.push_back(s);
      internal::notify_phase(visitor, Evolution_phase::Fit_to_rest, model().shape().number_of_components());
      join_branches(rest, visitor, callback);
    }
    if(branches && !m_last_fit.aborted && model().shape().number_of_components() > 1)
      revert_if_unpaid(visitor, callback);
    status.iterations = m_iterations - start;
    status.aborted = m_last_fit.aborted;
    // After an undo the model is the one at rest before the split.
    status.converged = !status.aborted && m_rest_converged;
    return status;
  }

  // The current model with a gradual part for the crease segment of
  // `proposal`, made in two steps. First the base takes the shape of the
  // points outside the segment, not of both (on the box/cylinder scan,
  // without this step the base stays the double pyramid over box and
  // cylinder and the RMS stays 4 times the paper's):
  // - the first split (the model is one superquadric): a new superquadric
  //   fitted to them, its poles towards the segment (pole_towards()). The
  //   one-part model fitted to them instead rests in a basin that depends
  //   on how its first fit ordered its axes, which the seed of the first
  //   fit's subsets decides: on the box/cylinder scan, over seeds 0-5, the
  //   box on one seed only, a slab with two semi-axes at their bound on
  //   the others (and the split then rests at RMS 0.14 to 1.6 % of the
  //   diagonal instead of 0.02 %). The new base replaces the model at
  //   once: a jump of the surface, but before the part comes in, and to a
  //   rest of the points it fits;
  // - later splits: the model fitted to rest on them (the surface moves
  //   by a fit; each projection starts from the point's foot point).
  // Then the superquadric fitted to the segment's points (fit_superquadric(),
  // lengthened into its base: lengthened_into_base()) joins the base at
  // h = 1 (add_gradual_part()), in the region where it meets the base
  // (region_inside_part(); where it has none, the region
  // propose_segment_split() gives for the segment on the base). Nothing if
  // the base's fit is stopped by `callback` (m_last_fit then says how it
  // ended); throws std::invalid_argument if no region holds the segment on
  // the base, or the shape refuses it.
  std::optional<Model> with_gradual_part(const Split_proposal& proposal, std::vector<Chart_point>& base_foot_points,
                                         Listener& visitor, const std::function<bool(double)>& callback)
  {
    const std::vector<std::size_t> member_indices = segment_members(proposal.segment);
    const std::vector<Chart_point> foot = m_fitter->foot_points();
    std::vector<Point_3> members, others;
    std::vector<Chart_point> others_foot; // where the base's fit starts its projections
    for(std::size_t i = 0, next = 0; i < m_points.size(); ++i)
      if(next < member_indices.size() && member_indices[next] == i)
      {
        members.push_back(m_points[i]);
        ++next;
      }
      else
      {
        others.push_back(m_points[i]);
        others_foot.push_back(foot[i]);
      }
    const std::size_t threads = m_fitter->settings().number_of_threads;
    std::optional<Model> base;
    if(m_fitter->model().shape().number_of_components() == 1)
    {
      const auto fitted = least_squares_superquadric(others, callback);
      if(!m_last_fit.aborted)
      {
        const Point_3 c = CGAL::centroid(members.begin(), members.end());
        base = make_blended_model(pole_towards(
          fitted.model, Eigen::Vector3d(CGAL::to_double(c.x()), CGAL::to_double(c.y()), CGAL::to_double(c.z())) -
                          fitted.model.translation()));
      }
    }
    else
    {
      Fitter base_fit(others, m_fitter->model(), m_fitter->settings());
      base_fit.start_from_chart_points(others_foot);
      m_last_fit = base_fit.run(visitor, callback);
      if(!m_last_fit.aborted)
        base = base_fit.model();
    }
    m_iterations += m_last_fit.iterations;
    if(!base)
      return std::nullopt;
    Fitter on_all_points(m_points, *base, m_fitter->settings());
    base_foot_points = on_all_points.foot_points();
    std::optional<Split_proposal> where = propose_segment_split(*base, base_foot_points, member_indices);
    if(where)
      where = shrink_to_fit(base->shape(), *where);
    if(!where)
      throw std::invalid_argument("Part_evolution: no region on the base holds crease segment " +
                                  std::to_string(proposal.segment));
    where->segment = proposal.segment;
    // the full fits' noise ceiling in its rough fits too, no mend (see the class description)
    const auto part = fit_superquadric(
      members,
      parameters::area_weight(
        m_fitter->settings().area_weight,
        parameters::settling_tolerance(
          settling_tolerance,
          parameters::candidate_noise_ceiling(m_fitter->settings().noise_ceiling,
                                              parameters::mend_missed_surfaces(false, parameters::number_of_threads(threads))))));
    const auto lengthened = lengthened_into_base(*base, where->component, part.model, members);
    if(const std::optional<Split_proposal> footprint = region_inside_part(*base, *where, lengthened))
      if(const std::optional<Split_proposal> fitted = shrink_to_fit(base->shape(), *footprint))
        where = fitted;
    return add_gradual_part(*base, *where, lengthened);
  }

  // The indices (increasing) among the points fitted (m_points) of the
  // points in segment `s`, which must be joined (always, but with
  // Split_source::Branch_segments).
  std::vector<std::size_t> segment_members(std::size_t s) const
  {
    std::vector<std::size_t> members;
    for(std::size_t j = 0; j < m_joined.size(); ++j)
      if(m_segments->label[m_joined[j]] == s)
        members.push_back(j);
    return members;
  }

  struct Stage_plan
  {
    std::size_t stages;     // of blend_in_stages()
    std::size_t iterations; // the iteration limit of each stage but the last
  };

  // The stages of the gradual part of `split` (the model whose last blend
  // is that part): Evolution_settings::first_split_blend_stages and
  // first_split_stage_iterations for the first split (a part on a one-part
  // base, which with_gradual_part() fitted afresh to the points outside the
  // part), blend_stages and intermediate_stage_iterations for later ones.
  Stage_plan stage_plan(const Model& split) const
  {
    if(split.shape().number_of_components() == 2)
      return {m_settings.first_split_blend_stages, m_settings.first_split_stage_iterations};
    return {m_settings.blend_stages, m_settings.intermediate_stage_iterations};
  }

  // Fits the model whose last blend is a gradual part at h = 1 to rest in
  // plan.stages stages (stage_plan() of that model): h held at
  // 1 - k / stages while the rest fits, then free from 0. Each stage moves
  // the surface by a bounded amount (the evolution stays gradual). The
  // steepness w is held with h (at 1, the smoothest blend): left free, the
  // first stage drives it to its bound (a sharp step, as at a crease), and
  // the later stages then stall in about one run of three on the same scan
  // at other scales. The part (its placement and shape) is held with h: it
  // is fitted to its points already, and with h held the fit would push it
  // past them, so that the surface a share 1 - h of the way from the base
  // reaches the points (on the box/cylinder scan, at h = 0.75, the cylinder
  // grew to its size bound and the last stage rested at 0.14 to 0.5 % of
  // the diagonal, 0.02 % held). The region's curve is held in every stage,
  // the last one too (Blended_shape::hold_blending_region(); it stays where
  // with_gradual_part() put it on the base): free, the fits creep
  // along it (on the box/cylinder scan: the curve's turn and radius with
  // the part's exponent, about 0.5 % of the energy an iteration, still
  // going at the 100-iteration limit). Each stage's projections start
  // from the foot points of the stage before (the first stage's, which
  // try_split() makes, from the foot points of the base alone, which the
  // part at h = 1 does not hide): a search from the tessellation alone
  // misses foot points next to the blend, whose faces straddle the cut.
  // When this came in (2026-11-29) a stage started that way rested far from
  // the points (the box/cylinder scan's third stage at 1.8 times the
  // energy); since the fits recheck their foot points at rest, the later
  // stages started from the tessellation give that scan the same model to
  // the 9th digit of its RMS, with one iteration more (2026-12-02): what
  // the carried foot points still save is the first step's search, so no
  // test can tell them apart by the result. The stages before the last stop
  // after plan.iterations (the last fits to rest). `m_fitter` is the first
  // stage's fitter (stage_fitter(), with the same plan);
  // `fit_settings` are those of the fits before the split. Returns the last
  // fit's status (an aborted stage ends it).
  Fitting_status blend_in_stages(const Stage_plan& plan, const Fitting_settings& fit_settings, Listener& visitor,
                                 const std::function<bool(double)>& callback)
  {
    for(std::size_t k = 1;; ++k)
    {
      const Fitting_status status = fit_to_rest_heard(visitor, callback);
      if(status.aborted || k >= plan.stages)
        return status;
      std::unique_ptr<Fitter> next = stage_fitter(m_fitter->model(), k + 1, plan, fit_settings);
      next->start_from_foot_points_of(*m_fitter);
      m_fitter = std::move(next);
    }
  }

  // The fitter of stage k (from 1 to plan.stages) of blend_in_stages(),
  // from `from` (the split model at h = 1 for the first stage, else the
  // last stage's model) and the settings of the fits before the split.
  std::unique_ptr<Fitter> stage_fitter(const Model& from, std::size_t k, const Stage_plan& plan,
                                       const Fitting_settings& fit_settings) const
  {
    const std::size_t stages = plan.stages;
    Blended_shape<GeomTraits> shape = from.shape();
    const std::size_t blend = shape.number_of_blends() - 1;
    const std::size_t h = shape.blend_offset(blend) + Ellipse_blending_region::H;
    const std::size_t w = shape.blend_offset(blend) + Ellipse_blending_region::W;
    Eigen::VectorXd q = shape.parameters();
    q[Eigen::Index(h)] = double(stages - k) / double(stages);
    shape.hold_parameter(h, false);
    shape.set_parameters(q);
    shape.hold_parameter(h, k < stages);
    shape.hold_parameter(w, k < stages);
    shape.hold_component(shape.blend(blend).added_component(), k < stages);
    shape.hold_blending_region(blend, true);
    Fitting_settings settings = fit_settings;
    if(k < stages)
      settings.maximum_iterations = (std::min)(settings.maximum_iterations, plan.iterations);
    return std::make_unique<Fitter>(m_points, Model(shape, from.translation(), from.quaternion()), settings);
  }

  // The proposals from crease segments (see propose_splits()); the segments
  // are computed at the first call.
  std::vector<Split_proposal> propose_segment_splits() const
  {
    const std::vector<Chart_point> foot = m_fitter->foot_points();
    const std::size_t n = foot.size();
    if(!m_segments)
    {
      std::vector<Eigen::Vector3d> outward(n);
      for(std::size_t i = 0; i < n; ++i)
      {
        const auto normal = model().normal(foot[i]);
        outward[i] = Eigen::Vector3d(normal.x(), normal.y(), normal.z());
      }
      m_segments = crease_segments(m_fitter->points(), outward);
      // None to split off: perhaps the model's normals are wrong in places
      // (see crease_segments()); then the normals oriented consistently.
      if(!(m_segments->size.size() > 1 && double(m_segments->size[1]) >= minimum_segment_share * double(n)))
      {
        Crease_segment_settings propagated;
        propagated.propagate_orientation = true;
        m_segments = crease_segments(m_fitter->points(), outward, propagated);
      }
    }
    std::vector<Split_proposal> proposals;
    for(std::size_t s = 1; s < m_segments->size.size() && proposals.size() < m_settings.maximum_split_tries; ++s)
    {
      if(double(m_segments->size[s]) < minimum_segment_share * double(n))
        break;
      if(std::optional<Split_proposal> p = propose_segment_split(model(), foot, segment_members(s)))
      {
        p->segment = s;
        if(const std::optional<Split_proposal> fitted = shrink_to_fit(model().shape(), *p))
          proposals.push_back(*fitted);
      }
    }
    return proposals;
  }

  // A superquadric fitted to `points` by least squares (fit_superquadric(),
  // the fits' area weight and threads, evolution's rests); m_last_fit says
  // how the fit ended.
  auto least_squares_superquadric(const std::vector<Point_3>& points, const std::function<bool(double)>& callback)
  {
    const auto fitted = fit_superquadric(
      points, parameters::area_weight(
                m_fitter->settings().area_weight,
                parameters::settling_tolerance(
                  settling_tolerance,
                  parameters::robust_weighting(Robust_weighting::None,
                                               parameters::number_of_threads(m_fitter->settings().number_of_threads)
                                                 .callback(callback)))));
    m_last_fit = Fitting_status();
    m_last_fit.iterations = fitted.metrics.iterations;
    m_last_fit.converged = fitted.metrics.converged;
    m_last_fit.aborted = fitted.metrics.aborted;
    return fitted;
  }

  // Split_source::Branch_segments: the branches of the points not isolated
  // (`kept`, their coordinates; branch_segments()) as m_segments, where a
  // branch of fewer than minimum_segment_share of them belongs to its
  // nearest ancestor that has more (or to the central branch), and a
  // branch of another connected piece grows from the central branch; the
  // central branch (the largest branch without a parent) is joined.
  void join_central_branch(const std::vector<Eigen::Vector3d>& kept)
  {
    Crease_segments b = branch_segments(kept);
    const std::size_t none = std::size_t(-1), count = b.size.size();
    std::size_t centre = none;
    for(std::size_t s = 0; s < count && centre == none; ++s)
      if(b.parent[s] == none)
        centre = s;
    if(centre == none) // (no points: check_points() refuses that before)
      throw std::invalid_argument("Part_evolution: no branch to start from");
    const auto large = [&](std::size_t s) {
      return double(b.size[s]) >= minimum_segment_share * double(kept.size());
    };
    // The branch whose points those of `s` join: `s` itself if large.
    std::vector<std::size_t> owner(count);
    for(std::size_t s = 0; s < count; ++s)
    {
      std::size_t t = s;
      while(t != centre && !large(t))
        t = b.parent[t] == none ? centre : b.parent[t];
      owner[s] = t;
    }
    std::vector<std::size_t> parent(count, none), size(count, 0);
    for(std::size_t s = 0; s < count; ++s)
      if(owner[s] == s && s != centre)
        parent[s] = b.parent[s] == none ? centre : owner[b.parent[s]];
    for(std::size_t& l : b.label)
    {
      l = owner[l];
      ++size[l];
    }
    b.parent = parent;
    b.size = size;
    m_segments = b;
    m_branch_joined.assign(count, false);
    m_branch_joined[centre] = true;
    update_joined_points();
  }

  // m_joined and m_points from m_branch_joined.
  void update_joined_points()
  {
    m_joined.clear();
    m_points.clear();
    for(std::size_t i = 0; i < m_kept.size(); ++i)
      if(m_branch_joined[m_segments->label[i]])
      {
        m_joined.push_back(i);
        m_points.push_back(m_kept[i]);
      }
  }

  // The largest branch not joined whose parent is, if any.
  std::optional<std::size_t> next_branch() const
  {
    std::optional<std::size_t> next;
    for(std::size_t s = 0; s < m_branch_joined.size(); ++s)
      if(!m_branch_joined[s] && m_segments->size[s] > 0 && m_branch_joined[m_segments->parent[s]] &&
         (!next || m_segments->size[s] > m_segments->size[*next]))
        next = s;
    return next;
  }

  // The split proposal of branch `s` (not joined): propose_segment_split()
  // on the current model with the closest points of the joined points and
  // of those of `s` (found afresh), or where that gives none (the branch
  // is most of its component's points) a proposal naming the branch only
  // (try_split() joins it, then finds no region: no split).
  Split_proposal branch_proposal(std::size_t s) const
  {
    std::vector<Point_3> points;
    std::vector<std::size_t> members;
    for(std::size_t i = 0; i < m_kept.size(); ++i)
      if(m_branch_joined[m_segments->label[i]] || m_segments->label[i] == s)
      {
        if(m_segments->label[i] == s)
          members.push_back(points.size());
        points.push_back(m_kept[i]);
      }
    Fitter with_branch(points, model(), m_fitter->settings());
    Split_proposal p;
    if(std::optional<Split_proposal> q = propose_segment_split(model(), with_branch.foot_points(), members))
      if(std::optional<Split_proposal> fitted = shrink_to_fit(model().shape(), *q))
        p = *fitted;
    p.boundary = Split_proposal::none;
    p.segment = s;
    return p;
  }

  // Split_source::Branch_segments, at the start of run(): the model becomes
  // a superquadric fitted to the central branch (fit_superquadric(), least
  // squares), not the model the evolution was made with, which fitted all
  // the points: a body fitted with its limbs is a plate that no part repairs.
  void start_from_central_branch_fit(const std::function<bool(double)>& callback)
  {
    const auto fitted = least_squares_superquadric(m_points, callback);
    m_iterations += fitted.metrics.iterations;
    if(m_last_fit.aborted)
      return;
    m_fitter = std::make_unique<Fitter>(m_points, make_blended_model(fitted.model), m_fitter->settings());
    ++m_version;
    m_central_branch_fitted = true;
  }

  // Split_source::Branch_segments, at the end of run(): the model the
  // evolution was made with, fitted to rest on all the points, replaces the
  // current one (fitted to them too) if its description length is no larger
  // (see the class description). A stopped fit changes nothing.
  void revert_if_unpaid(Listener& visitor, const std::function<bool(double)>& callback)
  {
    auto initial = std::make_unique<Fitter>(m_points, *m_initial, m_fitter->settings());
    const Fitting_status rest = initial->run(visitor, callback);
    m_iterations += rest.iterations;
    if(rest.aborted)
    {
      m_last_fit = rest;
      return;
    }
    Evolution_event e;
    e.kind = Evolution_event_kind::Revert;
    e.iteration = m_iterations;
    set_measures(e, mean_squared_distance(), model(), mean_squared_distance_of(*initial), initial->model());
    if(!(e.description_length_after <= e.description_length_before))
      return;
    m_fitter = std::move(initial);
    ++m_version;
    m_last_fit = rest;
    m_rest_converged = rest.converged;
    m_events.push_back(e);
    internal::notify_event(visitor, m_events.back(), model());
  }

  // Joins the branches `segments` to the points fitted and fits the
  // current model to rest on them, the projections of the points joined
  // before starting from their foot points. If `callback` stops the fit,
  // the model and its points are restored.
  Fitting_status join_branches(const std::vector<std::size_t>& segments, Listener& visitor,
                               const std::function<bool(double)>& callback)
  {
    const std::vector<Chart_point> foot = m_fitter->foot_points();
    const std::vector<std::size_t> joined_before = m_joined;
    const std::vector<Point_3> points_before = m_points;
    const std::vector<bool> branches_before = m_branch_joined;
    const std::size_t version_before = m_version;
    const Measure measured_before = m_measured;
    const bool converged_before = m_rest_converged;
    for(std::size_t s : segments)
      m_branch_joined[s] = true;
    update_joined_points();
    auto next = std::make_unique<Fitter>(m_points, m_fitter->model(), m_fitter->settings());
    std::vector<Chart_point> starts = next->foot_points();
    for(std::size_t j = 0, k = 0; j < m_joined.size() && k < joined_before.size(); ++j)
      if(m_joined[j] == joined_before[k])
        starts[j] = foot[k++];
    next->start_from_chart_points(starts);
    std::unique_ptr<Fitter> before = std::exchange(m_fitter, std::move(next));
    ++m_version;
    const Fitting_status status = fit_to_rest_heard(visitor, callback);
    if(status.aborted)
    {
      m_fitter = std::move(before);
      m_joined = joined_before;
      m_points = points_before;
      m_branch_joined = branches_before;
      m_version = version_before;
      m_measured = measured_before;
      m_rest_converged = converged_before;
    }
    return status;
  }

  // See mean_squared_distance().
  double mean_squared_distance_of(Fitter& fitter) const
  {
    Fitter fresh(m_points, fitter.model(), fitter.settings());
    return (std::min)(fitter.mean_squared_distance(true), fresh.mean_squared_distance(true));
  }

  // The description lengths and RMS distances of `e`: before it `model_before`
  // at mean squared distance `msd_before`, after it `model_after` at `msd_after`.
  void set_measures(Evolution_event& e, double msd_before, const Model& model_before, double msd_after,
                    const Model& model_after) const
  {
    e.description_length_before = description_length_of(msd_before, model_before);
    e.description_length_after = description_length_of(msd_after, model_after);
    e.rms_before = std::sqrt(msd_before);
    e.rms_after = std::sqrt(msd_after);
  }

  // L of `model` at mean squared distance `msd`.
  double description_length_of(double msd, const Model& model) const
  {
    const double n = double(described_points());
    // A floor far below any noise keeps the logarithm finite on exact data.
    return 0.5 * n * std::log((std::max)(msd, 1e-300)) + 0.5 * double(free_parameters(model)) * std::log(n);
  }

  // The parameters that move in a fit (the fixed ones are not described).
  static std::size_t free_parameters(const Model& m)
  {
    std::size_t k = 0;
    for(std::size_t i = 0; i < m.number_of_parameters(); ++i)
      k += m.is_fixed_parameter(i) ? 0 : 1;
    return k;
  }

  Evolution_settings m_settings;
  std::size_t m_described_points = 0;   // see set_described_points(); 0: the points fitted
  std::vector<Point_3> m_kept;          // the points not isolated
  std::vector<std::size_t> m_joined;    // those fitted now (indices in m_kept, increasing): see joined_points()
  std::vector<Point_3> m_points;        // the points fitted now: m_kept[m_joined[j]]
  std::vector<bool> m_branch_joined;    // Split_source::Branch_segments: whether each segment is joined
  std::vector<std::size_t> m_isolated;  // indices of the others
  std::unique_ptr<Fitter> m_fitter;
  std::vector<Evolution_event> m_events;
  std::size_t m_iterations = 0;
  Fitting_status m_last_fit;    // of the last fit to rest
  bool m_rest_converged = false; // whether the current model's fit came to rest
  // The state of the current fitter: changes whenever its model may have
  // moved or it was replaced (restored with it by an undo).
  std::size_t m_version = 0;
  // The last mean_squared_distance(), and the state it measured.
  struct Measure
  {
    std::size_t version = std::size_t(-1);
    double value = 0.;
  };
  Measure m_measured;
  mutable std::optional<Crease_segments> m_segments; // see propose_segment_splits()
  std::optional<Model> m_initial; // Split_source::Branch_segments: the model given, see revert_if_unpaid()
  bool m_central_branch_fitted = false; // Split_source::Branch_segments: whether run() fitted the central branch
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_EVOLUTION_PART_EVOLUTION_H
