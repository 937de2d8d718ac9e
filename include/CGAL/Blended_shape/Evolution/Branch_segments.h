// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_EVOLUTION_BRANCH_SEGMENTS_H
#define CGAL_BLENDED_SHAPE_EVOLUTION_BRANCH_SEGMENTS_H

#include <CGAL/Blended_shape/Evolution/Crease_segments.h>
#include <CGAL/Blended_shape/internal/point_spacing.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeEvolution
/// The settings of branch_segments().
struct Branch_segment_settings
{
  std::size_t neighbours = 16; ///< `k` of the neighbourhoods
  double edge_factor = 3.;     ///< neighbours farther than this times the median spacing are not joined
  /// The width of the bands of geodesic distance, in median distances of
  /// the points to their `k`-th nearest neighbour.
  double band_width = 1.5;
  /// A branch holds at least this share of the points (smaller side
  /// branches stay with the piece they grow from).
  double minimum_branch_share = 0.01;
};

namespace internal {

// Geodesic distances over the graph `adjacent` (symmetric lists of
// (neighbour, length)) from `source`, written into `d`, which holds
// infinity at every point `source` reaches (the points of its piece) on
// entry: one piece's search costs that piece, not all the points.
inline void geodesic_distances(const std::vector<std::vector<std::pair<std::size_t, double>>>& adjacent,
                               std::size_t source, std::vector<double>& d)
{
  typedef std::pair<double, std::size_t> Entry;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  d[source] = 0.;
  queue.emplace(0., source);
  while(!queue.empty())
  {
    const auto [di, i] = queue.top();
    queue.pop();
    if(di > d[i])
      continue;
    for(const auto& [j, length] : adjacent[i])
      if(di + length < d[j])
      {
        d[j] = di + length;
        queue.emplace(d[j], j);
      }
  }
}

// Of `members`, the one with the largest value of `d` (the first on a tie).
inline std::size_t farthest(const std::vector<std::size_t>& members, const std::vector<double>& d)
{
  std::size_t best = members.front();
  for(std::size_t i : members)
    if(d[i] > d[best])
      best = i;
  return best;
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeEvolution

The points of a scanned surface grouped into its branches: the arms of a
cross or a tripod, the limbs and the head of a body, the head and the
handle of a hammer. Where parts meet without a concave crease (a limb seen
from the front), crease_segments() keeps them together; their branches
still part.

The branches are those of the Reeb graph of the geodesic distance from the
surface's centre:

1. the neighbour graph of crease_segments() (the `k` nearest neighbours,
   edges no longer than `edge_factor` times the median distance to the
   `k`-th), made symmetric, each edge weighted by its length;
2. in each connected piece, its centre: the point `c` whose largest
   geodesic distance (Dijkstra) to four extremes of the piece is least, the
   extremes chosen by farthest-point sampling (the first farthest from the
   piece's first point, each next the farthest from those before: the
   ends of a bar, the tips of a cross's arms, the hands, feet and head of
   a body);
3. the bands of geodesic distance from `c`, `band_width` times the median
   distance to the `k`-th neighbour wide, and the connected pieces of each band:
   the nodes of the Reeb graph, each linked to the adjacent nodes of the
   band below it (or, where its edges down span more than one band, of the
   highest band below it they reach);
4. each node continues the branch of its parent (of its parents, the one
   that leads to most points: the points of a node are shared equally
   among its parents), unless the parent has two or more children leading
   to at least `minimum_branch_share` of the points each: then each of
   these starts a branch of its own, whose `parent` is the parent's branch;
5. sibling branches that meet again (a node whose parents lie in both: the
   two sides of a loop around a hole, or of a gap in the sampling) are
   made one.

A segment is a branch; Crease_segments::parent gives the tree of branches
(the first branch of each connected piece, the one at its centre, has
none). Deterministic (no threads, ties broken by index); segments are
numbered by decreasing size, equal sizes by their smallest point index.
Costs: the k-d tree, six Dijkstra searches over each connected piece,
linear passes otherwise.

\throws std::invalid_argument if a point is not finite, `k` is 0, or a width or factor is not positive.
*/
inline Crease_segments branch_segments(const std::vector<Eigen::Vector3d>& points,
                                       const Branch_segment_settings& settings = Branch_segment_settings())
{
  if(settings.neighbours < 1 || !(settings.edge_factor > 0.) || !(settings.band_width > 0.) ||
     !(settings.minimum_branch_share > 0.))
    throw std::invalid_argument(
      "branch_segments: neighbours, edge_factor, band_width and minimum_branch_share must be positive");
  const std::size_t n = points.size();
  internal::check_finite_points(points, "branch_segments");
  Crease_segments result;
  result.label.assign(n, 0);
  if(n == 0)
    return result;
  const std::size_t k = (std::min)(settings.neighbours, n - 1);

  const internal::Neighbourhoods near = internal::k_nearest_neighbourhoods(points, k);
  std::vector<double> spacing(n);
  for(std::size_t i = 0; i < n; ++i)
    spacing[i] = near.radius(i);
  const double longest_edge = settings.edge_factor * internal::median_of(spacing);
  const double band = settings.band_width * internal::median_of(spacing);

  std::vector<std::vector<std::pair<std::size_t, double>>> adjacent(n);
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t j : near.neighbours(i))
    {
      const double length = (points[i] - points[j]).norm();
      if(length <= longest_edge)
      {
        adjacent[i].emplace_back(j, length);
        adjacent[j].emplace_back(i, length);
      }
    }
  for(auto& a : adjacent) // each edge once, in index order
  {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end(), [](const auto& x, const auto& y) { return x.first == y.first; }),
            a.end());
  }


  // 2. the connected pieces and the geodesic distance from each one's centre
  constexpr int extremes = 4;
  internal::Index_union_find pieces(n);
  for(std::size_t i = 0; i < n; ++i)
    for(const auto& e : adjacent[i])
      pieces.join(i, e.first);
  std::vector<std::size_t> piece(n);
  std::vector<std::vector<std::size_t>> members;
  std::vector<std::size_t> piece_index(n, std::size_t(-1));
  for(std::size_t i = 0; i < n; ++i)
  {
    piece[i] = pieces.find(i);
    if(piece_index[piece[i]] == std::size_t(-1))
    {
      piece_index[piece[i]] = members.size();
      members.emplace_back();
    }
    members[piece_index[piece[i]]].push_back(i);
  }
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<double> d(n, infinity), from(n, infinity), nearest_extreme(n), farthest_extreme(n);
  auto search_from = [&](const std::vector<std::size_t>& in, std::size_t source) {
    for(std::size_t i : in)
      from[i] = infinity;
    internal::geodesic_distances(adjacent, source, from);
  };
  for(const std::vector<std::size_t>& in : members)
  {
    // extremes by farthest-point sampling, from the piece's first point:
    // each the farthest (geodesically) from those before
    search_from(in, in.front());
    for(std::size_t i : in)
    {
      nearest_extreme[i] = from[i];
      farthest_extreme[i] = 0.;
    }
    for(int e = 0; e < extremes; ++e)
    {
      search_from(in, internal::farthest(in, nearest_extreme));
      for(std::size_t i : in)
      {
        nearest_extreme[i] = e == 0 ? from[i] : (std::min)(nearest_extreme[i], from[i]);
        farthest_extreme[i] = (std::max)(farthest_extreme[i], from[i]);
      }
    }
    std::size_t centre = in.front();
    for(std::size_t i : in)
      if(farthest_extreme[i] < farthest_extreme[centre])
        centre = i;
    search_from(in, centre);
    for(std::size_t i : in)
      d[i] = from[i];
  }

  // 3. the nodes: connected pieces of each band
  std::vector<std::size_t> level(n);
  for(std::size_t i = 0; i < n; ++i)
    level[i] = band > 0. ? std::size_t(d[i] / band) : 0;
  internal::Index_union_find bands(n);
  for(std::size_t i = 0; i < n; ++i)
    for(const auto& e : adjacent[i])
      if(piece[i] == piece[e.first] && level[i] == level[e.first])
        bands.join(i, e.first);
  std::vector<std::size_t> node_of(n), node_index(n, std::size_t(-1)), node_root;
  for(std::size_t i = 0; i < n; ++i)
  {
    const std::size_t r = bands.find(i);
    if(node_index[r] == std::size_t(-1))
    {
      node_index[r] = node_root.size();
      node_root.push_back(r);
    }
    node_of[i] = node_index[r];
  }
  const std::size_t nodes = node_root.size();
  std::vector<double> weight(nodes, 0.);
  for(std::size_t i = 0; i < n; ++i)
    weight[node_of[i]] += 1.;
  // The links of the Reeb graph: between adjacent nodes of consecutive
  // bands, or, for a node with no neighbour in the band below (an edge
  // may span more than one band), to its neighbours of the highest band below.
  std::vector<std::size_t> below(nodes, 0); // the highest band below a node that a neighbour is in, plus 1
  for(std::size_t i = 0; i < n; ++i)
    for(const auto& e : adjacent[i])
      if(level[e.first] < level[i])
        below[node_of[i]] = (std::max)(below[node_of[i]], level[e.first] + 1);
  std::vector<std::vector<std::size_t>> children(nodes), parents(nodes);
  for(std::size_t i = 0; i < n; ++i)
    for(const auto& e : adjacent[i])
      if(level[e.first] > level[i] && level[i] + 1 == below[node_of[e.first]])
      {
        children[node_of[i]].push_back(node_of[e.first]);
        parents[node_of[e.first]].push_back(node_of[i]);
      }
  for(std::size_t c = 0; c < nodes; ++c)
  {
    for(auto* list : {&children[c], &parents[c]})
    {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
  }
  // nodes by band (then by root index): parents before children
  std::vector<std::size_t> order(nodes);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return level[node_root[a]] < level[node_root[b]]; });
  // the points each node leads to (shared equally among a node's parents)
  std::vector<double> leads = weight;
  for(auto it = order.rbegin(); it != order.rend(); ++it)
    for(std::size_t p : parents[*it])
      leads[p] += leads[*it] / double(parents[*it].size());

  // 4. branches
  const double significant = settings.minimum_branch_share * double(n);
  std::vector<std::size_t> branch(nodes, 0), branch_parent;
  std::size_t branches = 0;
  for(std::size_t c : order)
  {
    if(!parents[c].empty())
    {
      std::size_t p = parents[c].front();
      for(std::size_t q : parents[c])
        if(leads[q] > leads[p])
          p = q;
      std::size_t large = 0;
      for(std::size_t q : children[p])
        large += leads[q] >= significant ? 1 : 0;
      if(large < 2 || leads[c] < significant)
      {
        branch[c] = branch[p];
        continue;
      }
      branch_parent.push_back(branch[p]);
    }
    else
      branch_parent.push_back(std::size_t(-1));
    branch[c] = branches++;
  }

  // 5. sibling branches that meet again (a node reached from both: the two
  // sides of a loop around a hole, or of a gap in the sampling) are one
  internal::Index_union_find same(branches);
  for(std::size_t c = 0; c < nodes; ++c)
    for(std::size_t p : parents[c])
      for(std::size_t q : parents[c])
      {
        const std::size_t a = same.find(branch[p]), b = same.find(branch[q]);
        if(a != b && branch_parent[a] == branch_parent[b] && branch_parent[a] != std::size_t(-1))
          same.join(a, b);
      }
  for(std::size_t c = 0; c < nodes; ++c)
    branch[c] = same.find(branch[c]);

  // numbered by decreasing size, ties by smallest index
  std::vector<std::size_t> count(branches, 0), smallest(branches, n);
  for(std::size_t i = 0; i < n; ++i)
  {
    const std::size_t b = branch[node_of[i]];
    ++count[b];
    smallest[b] = (std::min)(smallest[b], i);
  }
  std::vector<std::size_t> ids;
  for(std::size_t b = 0; b < branches; ++b)
    if(same.find(b) == b)
      ids.push_back(b);
  std::sort(ids.begin(), ids.end(), [&](std::size_t a, std::size_t b) {
    return count[a] != count[b] ? count[a] > count[b] : smallest[a] < smallest[b];
  });
  std::vector<std::size_t> number(branches, 0);
  for(std::size_t s = 0; s < ids.size(); ++s)
  {
    number[ids[s]] = s;
    result.size.push_back(count[ids[s]]);
  }
  for(std::size_t i = 0; i < n; ++i)
    result.label[i] = number[branch[node_of[i]]];
  result.parent.assign(ids.size(), std::size_t(-1));
  for(std::size_t b : ids)
    if(branch_parent[b] != std::size_t(-1))
      result.parent[number[b]] = number[same.find(branch_parent[b])];
  return result;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_EVOLUTION_BRANCH_SEGMENTS_H
