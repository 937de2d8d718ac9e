// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_FITTING_VISITOR_H
#define CGAL_BLENDED_SHAPE_FITTING_FITTING_VISITOR_H

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeFitting
/// The stages of a fit, in order (see Deformable_model_fitter::run()).
enum class Fitting_phase
{
  Rigid,          ///< only translation and rotation move (parameter scheduling)
  Subset,         ///< all parameters, forces from a fixed random subset of the points
  All_points,     ///< all parameters, forces from every point
  Steady_state    ///< the fit came to rest
};

/// \ingroup PkgBlendedShapeFitting
/// A lower-case name of `p` for messages: "rigid", "subset", "all points" or "steady state".
inline const char* phase_name(Fitting_phase p)
{
  switch(p)
  {
    case Fitting_phase::Rigid: return "rigid";
    case Fitting_phase::Subset: return "subset";
    case Fitting_phase::All_points: return "all points";
    default: return "steady state";
  }
}

/*!
\ingroup PkgBlendedShapeFitting
A visitor with empty hooks: derive from it and override what you need
(it models the concept `BlendedShapeFittingVisitor`). Later stages of the
package call more hooks (splits, holes); they will have empty defaults too.
*/
struct Default_fitting_visitor
{
  /// Called when the fit enters `phase`, before iteration `iteration`.
  void on_phase(Fitting_phase /*phase*/, std::size_t /*iteration*/) {}
  /// Called after each iteration, accepted or not, with the fit energy after it
  /// (Step_report::energy_after: `(1/2) sum_i |p_i - x(u_i)|^2` over the points
  /// in use, or the Cauchy loss in place of the squares with robust weighting).
  void on_iteration(std::size_t /*iteration*/, double /*energy*/, std::size_t /*points_used*/) {}
};

namespace internal {

// A fitting visitor that records what it hears, to pass it on later
// (replay()): fits that run concurrently record, and their visitor then
// hears of them one fit after the other, in a fixed order.
class Recorded_fitting_visitor
{
public:
  void on_phase(Fitting_phase phase, std::size_t iteration) { m_heard.push_back({true, phase, iteration, 0., 0}); }
  void on_iteration(std::size_t iteration, double energy, std::size_t points_used)
  {
    m_heard.push_back({false, Fitting_phase::Rigid, iteration, energy, points_used});
  }
  template <class Visitor>
  void replay(Visitor& visitor) const
  {
    for(const Heard& h : m_heard)
      if(h.is_phase)
        visitor.on_phase(h.phase, h.iteration);
      else
        visitor.on_iteration(h.iteration, h.energy, h.points_used);
  }

private:
  struct Heard
  {
    bool is_phase;
    Fitting_phase phase;
    std::size_t iteration;
    double energy;
    std::size_t points_used;
  };
  std::vector<Heard> m_heard;
};

} // namespace internal

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_FITTING_VISITOR_H
