// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_NEAREST_POINTS_H
#define CGAL_BLENDED_SHAPE_INTERNAL_NEAREST_POINTS_H

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>
#include <Eigen/Core>
#include <boost/iterator/counting_iterator.hpp>
#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// For each of `queries`, the indices of its min(k, sites.size()) nearest
// points among `sites`, nearest first, one query after the other (a k-d
// tree; ties as CGAL's search breaks them, the same at every run).
inline std::vector<std::size_t> k_nearest_points(const std::vector<Eigen::Vector3d>& sites,
                                                 const std::vector<Eigen::Vector3d>& queries, std::size_t k)
{
  if(sites.empty() || k == 0)
    throw std::invalid_argument("k_nearest_points: no site to search, or k = 0");
  typedef CGAL::Simple_cartesian<double> K;
  typedef K::Point_3 Point;
  typedef CGAL::Pointer_property_map<Point>::type Point_map;
  typedef CGAL::Search_traits_adapter<std::size_t, Point_map, CGAL::Search_traits_3<K>> Traits;
  typedef CGAL::Orthogonal_k_neighbor_search<Traits> Search;
  std::vector<Point> points;
  points.reserve(sites.size());
  for(const Eigen::Vector3d& p : sites)
    points.emplace_back(p.x(), p.y(), p.z());
  const Point_map point_map(points.data());
  const Search::Tree tree(boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(points.size()),
                          Search::Tree::Splitter(), Traits(point_map));
  const Search::Distance distance(point_map);
  std::vector<std::size_t> nearest;
  nearest.reserve(queries.size() * (std::min)(k, sites.size()));
  for(const Eigen::Vector3d& q : queries)
  {
    const Search search(tree, Point(q.x(), q.y(), q.z()), unsigned(k), 0., true, distance);
    for(const auto& neighbour : search)
      nearest.push_back(neighbour.first);
  }
  return nearest;
}

// For each of `queries`, the index of its nearest point among `sites`.
inline std::vector<std::size_t> nearest_points(const std::vector<Eigen::Vector3d>& sites,
                                               const std::vector<Eigen::Vector3d>& queries)
{
  return k_nearest_points(sites, queries, 1);
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_INTERNAL_NEAREST_POINTS_H
