// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_EVOLUTION_CREASE_SEGMENTS_H
#define CGAL_BLENDED_SHAPE_EVOLUTION_CREASE_SEGMENTS_H

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeEvolution
/// A partition of scanned points into the pieces of surface between concave
/// creases (crease_segments()).
struct Crease_segments
{
  /// The segment of each point: 0 for the largest segment, 1 for the next, ...
  std::vector<std::size_t> label;
  /// The number of points of each segment, decreasing.
  std::vector<std::size_t> size;
  /// branch_segments(): the segment each segment branches from
  /// (`std::size_t(-1)` for the first segment of each connected piece of
  /// the points); crease_segments(): empty.
  std::vector<std::size_t> parent;
};

/// \ingroup PkgBlendedShapeEvolution
/// The settings of crease_segments().
struct Crease_segment_settings
{
  std::size_t neighbours = 16; ///< `k` of the neighbourhoods (normals and edges)
  double crease_angle = 30.;   ///< degrees: a concave edge turns the normal by more than this
  double edge_factor = 3.;     ///< neighbours farther than this times the median spacing are not joined
  /// How the normals are oriented: `false`, each along its own `outward[i]`;
  /// `true`, consistently over the edges (from each piece's first point,
  /// across the edge that turns the normal least first, as Hoppe et al.,
  /// SIGGRAPH 1992, orient tangent planes), then each connected piece of
  /// the edges turned as most of its points' `outward[i]` say.
  bool propagate_orientation = false;
};

namespace internal {

// Throws std::invalid_argument, the message starting with `who`, naming the
// first point of `points` that is not finite.
inline void check_finite_points(const std::vector<Eigen::Vector3d>& points, const std::string& who)
{
  for(std::size_t i = 0; i < points.size(); ++i)
    if(!points[i].allFinite())
      throw std::invalid_argument(who + ": point " + std::to_string(i) +
                                  " is not finite; remove it or give finite coordinates");
}

// Union-find over the indices 0, ..., n - 1, the smallest index of each
// set its root (the same roots in any order of the joins).
struct Index_union_find
{
  std::vector<std::size_t> parent;

  explicit Index_union_find(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t(0)); }
  std::size_t find(std::size_t x)
  {
    while(parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(std::size_t a, std::size_t b)
  {
    a = find(a);
    b = find(b);
    if(a != b)
      parent[(std::max)(a, b)] = (std::min)(a, b);
  }
};

// The `k` nearest neighbours of each of `points` (a CGAL k-d tree), nearest
// first: `hit[i]` the point itself and its `k` neighbours, in the order of
// the search, `distance[i]` their distances; the same lists at every run
// (ties as CGAL's search breaks them).
struct Neighbourhoods
{
  std::vector<std::vector<std::size_t>> hit;
  std::vector<std::vector<double>> distance;

  // The neighbours of point `i`, without itself.
  std::vector<std::size_t> neighbours(std::size_t i) const
  {
    std::vector<std::size_t> result;
    for(std::size_t j : hit[i])
      if(j != i)
        result.push_back(j);
    return result;
  }
  // The distance of point `i` to its farthest (`k`-th) neighbour.
  double radius(std::size_t i) const
  {
    double r = 0.;
    for(double d : distance[i])
      r = (std::max)(r, d);
    return r;
  }
};

inline Neighbourhoods k_nearest_neighbourhoods(const std::vector<Eigen::Vector3d>& points, std::size_t k)
{
  typedef CGAL::Simple_cartesian<double> K;
  typedef K::Point_3 Point;
  typedef CGAL::Search_traits_3<K> Base_traits;
  typedef CGAL::Pointer_property_map<Point>::const_type Point_map;
  typedef CGAL::Search_traits_adapter<std::size_t, Point_map, Base_traits> Traits;
  typedef CGAL::Orthogonal_k_neighbor_search<Traits> Search;
  const std::size_t n = points.size();
  Neighbourhoods result;
  result.hit.resize(n);
  result.distance.resize(n);
  if(n == 0)
    return result;
  std::vector<Point> copy;
  copy.reserve(n);
  for(const Eigen::Vector3d& p : points)
    copy.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::size_t> indices(n);
  std::iota(indices.begin(), indices.end(), std::size_t(0));
  const Point_map point_map = CGAL::make_property_map(static_cast<const std::vector<Point>&>(copy));
  const typename Search::Tree tree(indices.begin(), indices.end(), typename Search::Splitter(), Traits(point_map));
  const typename Search::Distance metric(point_map);
  for(std::size_t i = 0; i < n; ++i)
  {
    const Search search(tree, copy[i], unsigned(k + 1), 0., true, metric);
    for(const auto& h : search)
    {
      result.hit[i].push_back(h.first);
      result.distance[i].push_back(std::sqrt(h.second));
    }
  }
  return result;
}

// Crease_segment_settings::propagate_orientation: the normals oriented over
// the edges (neighbours[i] with is_edge(i, j)), within each piece reached
// from its smallest index, across the edge of least turn (smallest
// 1 - |n_i . n_j|, ties by index) first (Prim's order), each normal along
// the one it is reached from; then each piece flipped if more of its
// normals point against `outward` than along it.
template <class IsEdge>
void propagate_orientation(const std::vector<std::vector<std::size_t>>& neighbours, const IsEdge& is_edge,
                           const std::vector<Eigen::Vector3d>& outward, std::vector<Eigen::Vector3d>& normal)
{
  const std::size_t n = normal.size();
  std::vector<bool> reached(n, false);
  typedef std::tuple<double, std::size_t, std::size_t> Edge; // turn, to, from
  for(std::size_t first = 0; first < n; ++first)
  {
    if(reached[first])
      continue;
    std::vector<std::size_t> piece;
    std::priority_queue<Edge, std::vector<Edge>, std::greater<Edge>> queue;
    queue.emplace(0., first, first);
    while(!queue.empty())
    {
      const auto [turn, i, from] = queue.top();
      queue.pop();
      if(reached[i])
        continue;
      reached[i] = true;
      piece.push_back(i);
      if(normal[i].dot(normal[from]) < 0.)
        normal[i] = -normal[i];
      for(std::size_t j : neighbours[i])
        if(!reached[j] && is_edge(i, j))
          queue.emplace(1. - std::abs(normal[i].dot(normal[j])), j, i);
    }
    std::ptrdiff_t vote = 0;
    for(std::size_t i : piece)
      vote += normal[i].dot(outward[i]) < 0. ? -1 : 1;
    if(vote < 0)
      for(std::size_t i : piece)
        normal[i] = -normal[i];
  }
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeEvolution

The points of a scanned surface grouped into the pieces between its concave
creases: where a part joins its base (a cylinder standing on a box, a
handle on a mug, a head on a body) the surface folds inwards, while each
part alone is nearly convex. Evolution (Part_evolution) proposes splits
from these pieces, as the paper's force regions (eq. 12, 13) cannot on a
least-squares superquadric that stretches over several parts.

`outward[i]` is any direction on the outer side of the surface at
`points[i]` (the normal of a model fitted to the points, at the point's
closest point): it orients the estimated normals. The segmentation:

1. the `k` nearest neighbours of each point (a CGAL kd-tree) and its normal
   `n_i`, the direction of least variance of these neighbours (PCA),
   oriented along `outward[i]`;
2. the edges: pairs of neighbours closer than `edge_factor` times the median
   distance to the `k`-th neighbour (none across a jump in depth); with
   `propagate_orientation`, the normals are then oriented over the edges
   (see Crease_segment_settings): where `outward` is wrong in places (a
   model far from the points: its closest point on a far side), the
   orientation of each point's own direction turns convex folds into
   concave ones there, while the propagated one does not, as long as most
   directions of each piece are right;
3. an edge `(i, j)` is concave if the normals turn by more than
   `crease_angle` and `(n_i - n_j) . (p_i - p_j) < 0` (the convexity test
   of locally convex connected patches, Stein et al., CVPR 2014: on a
   convex fold the normals diverge as the points do);
4. the ends of concave edges are crease points; the other points form
   segments, the connected components of the edges between them; then, ring
   after ring, each crease point joins the segment of its first neighbour
   (in neighbour order) already in one, and crease points left alone form
   their own segments.

Dropping the crease points rather than the concave edges alone is what cuts:
the normals estimated across a crease turn gradually, so the edges along it
are each only slightly bent and would join the two sides.

Deterministic (no threads, ties broken by index); segments are numbered by
decreasing size, equal sizes by their smallest point index.

\throws std::invalid_argument if the sizes differ, a point or direction is not
        finite, a direction is zero, `k` is 0, or an angle or factor is not positive.
*/
inline Crease_segments crease_segments(const std::vector<Eigen::Vector3d>& points,
                                       const std::vector<Eigen::Vector3d>& outward,
                                       const Crease_segment_settings& settings = Crease_segment_settings())
{
  if(points.size() != outward.size())
    throw std::invalid_argument("crease_segments: " + std::to_string(points.size()) + " points but " +
                                std::to_string(outward.size()) + " outward directions; give one per point");
  if(settings.neighbours < 1 || !(settings.crease_angle > 0.) || !(settings.edge_factor > 0.))
    throw std::invalid_argument("crease_segments: neighbours, crease_angle and edge_factor must be positive");
  const std::size_t n = points.size();
  internal::check_finite_points(points, "crease_segments");
  for(std::size_t i = 0; i < n; ++i)
    if(!outward[i].allFinite() || outward[i].squaredNorm() == 0.)
      throw std::invalid_argument("crease_segments: outward direction " + std::to_string(i) +
                                  " is zero or not finite; give a direction on the outer side of the surface");
  Crease_segments result;
  result.label.assign(n, 0);
  if(n == 0)
    return result;
  const std::size_t k = (std::min)(settings.neighbours, n - 1);

  // 1. neighbours (nearest first, without the point itself) and normals
  const internal::Neighbourhoods near = internal::k_nearest_neighbourhoods(points, k);
  std::vector<std::vector<std::size_t>> neighbours(n);
  std::vector<Eigen::Vector3d> normal(n);
  std::vector<double> spacing(n, 0.);
  for(std::size_t i = 0; i < n; ++i)
  {
    neighbours[i] = near.neighbours(i);
    spacing[i] = near.radius(i);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for(std::size_t j : near.hit[i])
      mean += points[j];
    mean /= double(near.hit[i].size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for(std::size_t j : near.hit[i])
      covariance += (points[j] - mean) * (points[j] - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance); // eigenvalues increasing
    normal[i] = eigen.eigenvectors().col(0);
    if(normal[i].dot(outward[i]) < 0.)
      normal[i] = -normal[i];
  }
  std::vector<double> sorted = spacing;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(n / 2), sorted.end());
  const double longest_edge = settings.edge_factor * sorted[n / 2];
  const double cos_crease = std::cos(settings.crease_angle * CGAL_PI / 180.);
  auto is_edge = [&](std::size_t i, std::size_t j) { return (points[i] - points[j]).norm() <= longest_edge; };
  if(settings.propagate_orientation)
    internal::propagate_orientation(neighbours, is_edge, outward, normal);

  // 3. crease points
  std::vector<bool> crease(n, false);
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t j : neighbours[i])
      if(is_edge(i, j) && normal[i].dot(normal[j]) < cos_crease &&
         (normal[i] - normal[j]).dot(points[i] - points[j]) < 0.)
        crease[i] = crease[j] = true;

  // 4. components of the other points (union-find, the smallest index as root)
  internal::Index_union_find sets(n);
  for(std::size_t i = 0; i < n; ++i)
    if(!crease[i])
      for(std::size_t j : neighbours[i])
        if(!crease[j] && is_edge(i, j))
          sets.join(i, j);
  // crease points join their neighbours' segments ring after ring
  for(bool changed = true; changed;)
  {
    changed = false;
    std::vector<std::size_t> joined;
    for(std::size_t i = 0; i < n; ++i)
      if(crease[i])
        for(std::size_t j : neighbours[i])
          if(!crease[j] && is_edge(i, j))
          {
            sets.join(j, i);
            joined.push_back(i);
            break;
          }
    for(std::size_t i : joined)
      crease[i] = false;
    changed = !joined.empty();
  }
  for(std::size_t i = 0; i < n; ++i) // crease points left alone: by themselves
    if(crease[i])
      for(std::size_t j : neighbours[i])
        if(crease[j] && is_edge(i, j))
          sets.join(i, j);

  // numbered by decreasing size, ties by smallest index (the root)
  std::vector<std::size_t> count(n, 0);
  for(std::size_t i = 0; i < n; ++i)
    ++count[sets.find(i)];
  std::vector<std::size_t> roots;
  for(std::size_t i = 0; i < n; ++i)
    if(count[i] > 0)
      roots.push_back(i);
  std::stable_sort(roots.begin(), roots.end(), [&](std::size_t a, std::size_t b) { return count[a] > count[b]; });
  std::vector<std::size_t> number(n, 0);
  for(std::size_t s = 0; s < roots.size(); ++s)
  {
    number[roots[s]] = s;
    result.size.push_back(count[roots[s]]);
  }
  for(std::size_t i = 0; i < n; ++i)
    result.label[i] = number[sets.find(i)];
  return result;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_EVOLUTION_CREASE_SEGMENTS_H
