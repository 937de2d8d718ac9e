// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_LABEL_CROSSINGS_H
#define CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_LABEL_CROSSINGS_H

// Where a label of the chart points (the domain or chart a point belongs to)
// changes along a curve segment: the cut points of the subdivision of A.2.1.

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// The parameters in (0, 1) where `label(curve(gamma))` changes: `curve` is
/// sampled at `samples + 1` values of `gamma`; in every sample interval whose
/// end labels differ, a binary search halves the bracket until it is shorter
/// than `tolerance` and its middle is a crossing. Crossings closer than
/// `tolerance` to an end of the segment are dropped.
template <class Curve, class LabelFunction>
std::vector<double> label_crossings(const Curve& curve, const LabelFunction& label, double tolerance,
                                    std::size_t samples)
{
  std::vector<double> cuts;
  auto previous = label(curve(0.));
  for(std::size_t s = 1; s <= samples; ++s)
  {
    double lo = double(s - 1) / double(samples), hi = double(s) / double(samples);
    auto current = label(curve(hi));
    if(!(current == previous))
    {
      while(hi - lo > tolerance)
      {
        const double mid = 0.5 * (lo + hi);
        if(label(curve(mid)) == previous)
          lo = mid;
        else
          hi = mid;
      }
      const double g = 0.5 * (lo + hi);
      if(g > tolerance && g < 1. - tolerance)
        cuts.push_back(g);
    }
    previous = current;
  }
  return cuts;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_INTERNAL_LABEL_CROSSINGS_H
