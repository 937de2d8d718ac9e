// SPDX-License-Identifier: LGPL-3.0-or-later
// The quotient domain (eq. 1, 2) as a graph over the chart meshes: its
// topological distance against independent references -- the exact
// great-circle distance on the unit sphere, and Dijkstra (Boost.Graph) on the
// closed single mesh of the same surface made by make_unified_mesh() -- across
// the ellipsoid's chart seam, across blends (a split over the seam and a
// gradual part) and around a handle (a torus-like model whose points are close
// in space and far on the surface); metric properties; bad input. Both
// supported kernels.
#ifndef BLENDED_SHAPE_QUOTIENT_DOMAIN_CHECKS_H
#define BLENDED_SHAPE_QUOTIENT_DOMAIN_CHECKS_H
// Part of test_blended_shape (one program, one compilation of the blended
// shape for each kernel; CTest runs it as `test_blended_shape_quotient_domain`).
#include "test_kernels.h"
#include "test_util.h"
#include "blended_shape_test_util.h"

#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Blending/Quotient_domain.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace quotient_domain_checks {

namespace BS = CGAL::Blended_shapes;

using blended_shape_test::set_parameter;
using blended_shape_test::perturb_component;

typedef BS::Ellipse_blending_region Region;

#ifdef BLENDED_SHAPE_REDUCED_TESTS
const int resolution = 12;    // sanitizer builds: same checks, coarser meshes, fewer pairs
const int sources = 2, targets = 8;
#else
const int resolution = 16;
const int sources = 6, targets = 20;
#endif

template <class K>
using Shape = BS::Blended_shape<K>;

template <class K>
Eigen::Vector3d eig(const typename K::Point_3& p)
{
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

// The set-ups of test_blended_shape.
template <class K>
Shape<K> ellipsoid()
{
  return Shape<K>(BS::Superquadric_ellipsoid<K>(1.0, 0.9, 1.1, 0.8, 1.1));
}

// A split whose region crosses the equator (in chart 0's margin), and a
// tilted gradual part on chart 1, half expressed.
template <class K>
Shape<K> seam_split_and_part()
{
  Shape<K> s = ellipsoid<K>();
  s.split(0, 0, Region::make_parameters(0.93, 0.1, 0.12, 0.16, 0.2, 0.8, 0.), 0.035);
  perturb_component(s, 1, 0.2);
  s.add_part(0, 1, Region::make_parameters(-0.2, 0.25, 0.32, 0.28, -0.4, 0.85, 1.), 0.07,
             BS::Superquadric_ellipsoid<K>(0.5, 0.45, 0.8, 0.6, 1.2), "superquadric_ellipsoid",
             Eigen::Vector3d(0.1, -0.2, -0.9), Eigen::Vector4d(0.95, 0.2, -0.1, 0.05), 0,
             Region::make_parameters(0.05, 0., 0.55, 0.5, 0.1, 1., 0.), 0.1);
  set_parameter(s, "b1.h", 0.4);
  return s;
}

// A unit sphere with an open hole (a tunnel from pole to pole): genus 1.
template <class K>
Shape<K> sphere_with_tunnel()
{
  Shape<K> s(BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1.));
  s.add_hole(BS::Shape_point(0, BS::Chart_point(0, 0.05, 0.)), BS::Shape_point(0, BS::Chart_point(1, 0., 0.05)), 0.3,
             0.08, 0.1);
  blended_shape_test::open_pole_hole(s);
  return s;
}

// A uniform random point of a random chart of component k, on the surface.
template <class K>
BS::Shape_point random_surface_point(const Shape<K>& s, std::size_t k, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u01(0., 1.);
  const BS::Component_shape& cs = s.component(k).shape();
  for(;;)
  {
    const std::size_t c = std::size_t(u01(rng) * double(cs.number_of_charts())) % cs.number_of_charts();
    const BS::Chart_domain d = cs.chart_domain(c);
    double x, y;
    if(d.kind == BS::Chart_kind::Disk)
    {
      x = d.radius * (2. * u01(rng) - 1.);
      y = d.radius * (2. * u01(rng) - 1.);
      if(!d.contains(x, y))
        continue;
    }
    else
    {
      x = 2. * M_PI * u01(rng);
      y = d.y_min + (d.y_max - d.y_min) * u01(rng);
    }
    const BS::Shape_point p(k, BS::Chart_point(c, x, y));
    if(s.is_on_surface(p))
      return p;
  }
}

template <class K>
BS::Shape_point random_surface_point(const Shape<K>& s, std::mt19937& rng)
{
  return random_surface_point(s, std::size_t(rng() % s.number_of_components()), rng);
}

// The reference: Dijkstra (Boost.Graph) on one closed mesh of the surface,
// over the same kind of distance graph (every vertex to every vertex within
// `rings` edges, weighted by the distance in space); a query point is tied to
// the corners of the mesh face nearest to it (AABB tree), two points on one
// face also directly. Written independently of Quotient_domain.
// The mesh must be a sane tessellation: no edge ten times longer than the
// median (a vertex evaluated somewhere else on the surface would make one).
template <class K>
class Mesh_reference
{
public:
  typedef CGAL::Surface_mesh<typename K::Point_3> Mesh;
  typedef typename Mesh::Vertex_index Vertex;
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> Tree;
  typedef boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                boost::property<boost::edge_weight_t, double>>
    Graph;

  struct Query
  {
    typename Mesh::Face_index face;
    Eigen::Vector3d x;
    std::vector<std::pair<std::size_t, double>> corners;
  };

  Mesh_reference(const Mesh& m, int rings) : m_mesh(m), m_graph(m.number_of_vertices() + 1)
  {
    CGAL::Polygon_mesh_processing::build_AABB_tree(m_mesh, m_tree);
    std::vector<double> lengths;
    for(auto e : m_mesh.edges())
      lengths.push_back(length(e));
    std::nth_element(lengths.begin(), lengths.begin() + std::ptrdiff_t(lengths.size() / 2), lengths.end());
    m_median_edge = lengths[lengths.size() / 2];
    m_vertex_ring.assign(m_mesh.number_of_vertices(), 0.);
    for(auto e : m_mesh.edges())
    {
      const double l = length(e);
      m_max_edge = std::max(m_max_edge, l);
      for(int k = 0; k < 2; ++k)
      {
        double& r = m_vertex_ring[std::size_t(m_mesh.vertex(e, k))];
        r = std::max(r, l);
      }
    }
    const std::size_t n = m_mesh.number_of_vertices();
    std::vector<std::size_t> seen(n, n);
    for(Vertex v : m_mesh.vertices())
    {
      const std::size_t i = std::size_t(v);
      seen[i] = i;
      std::vector<Vertex> front(1, v);
      for(int r = 0; r < rings; ++r)
      {
        std::vector<Vertex> next;
        for(Vertex u : front)
          for(Vertex w : CGAL::vertices_around_target(u, m_mesh))
            if(seen[std::size_t(w)] != i)
            {
              seen[std::size_t(w)] = i;
              next.push_back(w);
              if(std::size_t(w) > i)
                boost::add_edge(i, std::size_t(w), (pos(v) - pos(w)).norm(), m_graph);
            }
        front.swap(next);
      }
    }
  }

  double max_edge_length() const { return m_max_edge; }
  double median_edge_length() const { return m_median_edge; }

  Query query(const Eigen::Vector3d& x) const
  {
    Query q;
    q.x = x;
    const auto loc = CGAL::Polygon_mesh_processing::locate_with_AABB_tree(typename K::Point_3(x.x(), x.y(), x.z()),
                                                                          m_tree, m_mesh);
    q.face = loc.first;
    for(Vertex v : CGAL::vertices_around_face(m_mesh.halfedge(q.face), m_mesh))
      q.corners.push_back(std::make_pair(std::size_t(v), (pos(v) - x).norm()));
    return q;
  }

  // Distances from q to every vertex: a virtual source vertex tied to q's corners.
  std::vector<double> distances(const Query& q)
  {
    const std::size_t source = m_mesh.number_of_vertices();
    boost::clear_vertex(source, m_graph);
    for(const auto& c : q.corners)
      boost::add_edge(source, c.first, c.second, m_graph);
    std::vector<double> d(boost::num_vertices(m_graph));
    // (an iterator property map, not d.data(): the raw pointer's get() is
    // found by a lookup that depends on which Boost headers came first)
    boost::dijkstra_shortest_paths(m_graph, source, boost::distance_map(
      boost::make_iterator_property_map(d.begin(), boost::get(boost::vertex_index, m_graph))));
    return d;
  }

  static double distance(const Query& a, const std::vector<double>& from_a, const Query& b)
  {
    double best = (a.face == b.face) ? (a.x - b.x).norm() : HUGE_VAL;
    for(const auto& c : b.corners)
      best = std::min(best, from_a[c.first] + c.second);
    return best;
  }

  // One ring of the mesh at both ends of a query: the longest mesh edge at
  // the corners of a's and b's faces.
  double endpoint_ring(const Query& a, const Query& b) const
  {
    double ring = 0.;
    for(const Query* q : {&a, &b})
      for(const auto& c : q->corners)
        ring = std::max(ring, m_vertex_ring[c.first]);
    return ring;
  }

private:
  Eigen::Vector3d pos(Vertex v) const { return eig<K>(m_mesh.point(v)); }
  double length(typename Mesh::Edge_index e) const { return (pos(m_mesh.vertex(e, 0)) - pos(m_mesh.vertex(e, 1))).norm(); }

  Mesh m_mesh;
  Tree m_tree;
  Graph m_graph;
  double m_max_edge = 0., m_median_edge = 0.;
  std::vector<double> m_vertex_ring; // the longest mesh edge at each vertex
};

// The reference of a set-up: its unified mesh, at the same resolution.
template <class K>
Mesh_reference<K> make_reference(const Shape<K>& s, int rings, const std::string& name)
{
  Mesh_reference<K> ref(BS::make_unified_mesh(s, resolution, 3), rings);
  BS_CHECK(ref.max_edge_length() <= 10. * ref.median_edge_length(),
           name << ": the unified mesh has an edge of " << ref.max_edge_length() << ", median " << ref.median_edge_length());
  return ref;
}

struct Agreement
{
  double max_difference = 0., max_relative = 0.;
  double max_rings = 0.;        // the largest |quotient - single mesh| / local ring
  double max_global_rings = 0.; // the same against the longest edge of either graph (reported only)
  double smallest_ring = HUGE_VAL, largest_ring = 0.;
  double relative_distance = 0., relative_ring = 0.; // the single-mesh distance and local ring of the max relative
  std::size_t pairs = 0;
};

// The quotient graph's own ring around a point: the longest quotient edge
// at the nodes nearest to the point in space (a point of a chart overlap
// has a node in each covering piece, all at one place).
template <class K>
class Quotient_rings
{
public:
  explicit Quotient_rings(const BS::Quotient_domain<K>& q)
  {
    for(std::size_t i = 0; i < q.number_of_nodes(); ++i)
    {
      m_x.push_back(eig<K>(q.node(i).position));
      double r = 0.;
      for(const auto& nb : q.neighbors(i))
        r = std::max(r, nb.length);
      m_ring.push_back(r);
    }
  }
  double at(const Eigen::Vector3d& x) const
  {
    double nearest = HUGE_VAL;
    for(const Eigen::Vector3d& y : m_x)
      nearest = std::min(nearest, (y - x).norm());
    double ring = 0.;
    for(std::size_t i = 0; i < m_x.size(); ++i)
      if((m_x[i] - x).norm() <= nearest + 1e-12)
        ring = std::max(ring, m_ring[i]);
    return ring;
  }

private:
  std::vector<Eigen::Vector3d> m_x;
  std::vector<double> m_ring;
};

// Quotient distances from `sources` random points (drawn by `first`) to
// `targets` random points (drawn by `second`) against the reference: they
// agree within one LOCAL ring, the longest edge of either graph at the two
// points (Mesh_reference::endpoint_ring(), Quotient_rings::at()), not the
// longest edge anywhere (a coarse strip elsewhere would let short distances
// be off by several times their length). Also checks distances_from()
// against topological_distance(). `global_ring` (the longest edge of either
// graph) is only reported, for comparison.
template <class K, class FirstPoint, class SecondPoint>
Agreement compare_with_mesh(const BS::Quotient_domain<K>& q, Mesh_reference<K>& ref, const FirstPoint& first,
                            const SecondPoint& second, double global_ring, const std::string& name)
{
  const Shape<K>& s = q.shape();
  const Quotient_rings<K> qrings(q);
  Agreement ag;
  for(int i = 0; i < sources; ++i)
  {
    const BS::Shape_point a = first();
    const Eigen::Vector3d xa = eig<K>(s.point(a));
    const auto ra = ref.query(xa);
    const auto from_a = ref.distances(ra);
    const auto map = q.distances_from(a);
    const double qa = qrings.at(xa);
    for(int j = 0; j < targets; ++j)
    {
      const BS::Shape_point b = second();
      const Eigen::Vector3d xb = eig<K>(s.point(b));
      const auto rb = ref.query(xb);
      const double dq = q.topological_distance(a, b);
      const double dr = Mesh_reference<K>::distance(ra, from_a, rb);
      const double diff = std::abs(dq - dr);
      const double ring = std::max({qa, qrings.at(xb), ref.endpoint_ring(ra, rb)});
      ++ag.pairs;
      ag.max_difference = std::max(ag.max_difference, diff);
      if(diff / std::max(dr, 1e-12) > ag.max_relative)
      {
        ag.max_relative = diff / std::max(dr, 1e-12);
        ag.relative_distance = dr;
        ag.relative_ring = ring;
      }
      ag.max_rings = std::max(ag.max_rings, diff / ring);
      ag.max_global_rings = std::max(ag.max_global_rings, diff / global_ring);
      ag.smallest_ring = std::min(ag.smallest_ring, ring);
      ag.largest_ring = std::max(ag.largest_ring, ring);
      BS_CHECK(std::isfinite(dq) && diff <= ring,
               name << ": quotient distance " << dq << ", single mesh " << dr << ", difference " << diff
                    << " > one local ring " << ring << " (from component " << a.component << " chart " << a.u.chart
                    << " (" << a.u.x << ", " << a.u.y << ") to component " << b.component << " chart " << b.u.chart
                    << " (" << b.u.x << ", " << b.u.y << "))");
      const double dm = map(b);
      BS_CHECK(dm == dq || std::abs(dm - dq) <= 1e-12 * (1. + dq), name << ": distances_from " << dm << " vs topological_distance " << dq);
    }
  }
  return ag;
}

template <class K>
void report_agreement(const std::string& name, const Agreement& a, double ring)
{
  std::cout << "  " << name << ": " << a.pairs << " pairs, max |quotient - single mesh| " << a.max_difference
            << " = " << a.max_rings << " local rings (local rings " << a.smallest_ring << " to " << a.largest_ring
            << "; " << a.max_global_rings << " of the global ring " << ring << "), max relative " << a.max_relative
            << " (at distance " << a.relative_distance << ", local ring " << a.relative_ring << ")" << std::endl;
}

// Every node reachable from node 0; some edges glue different charts or components.
template <class K>
void check_connected(const BS::Quotient_domain<K>& q, const std::string& name)
{
  const auto map = q.distances_from(q.node(0).point);
  std::size_t unreachable = 0;
  for(double d : map.node_distances())
    unreachable += std::isfinite(d) ? 0 : 1;
  BS_CHECK(unreachable == 0, name << ": " << unreachable << " of " << q.number_of_nodes() << " nodes unreachable");
  std::size_t glued = 0, across = 0;
  for(std::size_t i = 0; i < q.number_of_nodes(); ++i)
    for(const auto& nb : q.neighbors(i))
    {
      glued += nb.glued ? 1 : 0;
      const auto& a = q.node(i).point;
      const auto& b = q.node(nb.node).point;
      across += (a.component != b.component || a.u.chart != b.u.chart) ? 1 : 0;
      BS_CHECK(nb.length <= q.max_edge_length(), name << ": an edge longer than max_edge_length()");
      const auto& back = q.neighbors(nb.node);
      BS_CHECK(std::any_of(back.begin(), back.end(), [&](const auto& x) { return x.node == i && x.length == nb.length; }),
               name << ": the adjacency is not symmetric");
    }
  BS_CHECK(glued > 0 && across > 0, name << ": no gluing edges");
  std::cout << "  " << name << ": " << q.number_of_nodes() << " nodes, " << glued / 2 << " gluing edges, one ring "
            << q.max_edge_length() << std::endl;
}

double since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// (1) The ellipsoid's two charts glued at the equator seam: against the exact
// geodesic on the unit sphere, and against the closed single mesh.
template <class K>
void test_seam(std::mt19937& rng)
{
  // Unit sphere: the great-circle distance is the exact geodesic.
  {
    const Shape<K> s(BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1.));
    const BS::Blended_shape_pieces<K> pieces(s, resolution);
    for(int rings = 1; rings <= 3; ++rings)
    {
      const BS::Quotient_domain<K> q(s, pieces, rings);
      double worst_excess = 0., worst_below = 0., worst_relative = 0., worst_absolute = 0.;
      for(int i = 0; i < 3 * sources * targets; ++i)
      {
        const BS::Shape_point a = random_surface_point(s, 0, rng), b = random_surface_point(s, 0, rng);
        const double g = std::acos(std::max(-1., std::min(1., eig<K>(s.point(a)).dot(eig<K>(s.point(b))))));
        const double d = q.topological_distance(a, b);
        worst_excess = std::max(worst_excess, (d - g - q.max_edge_length()) / std::max(g, 1e-9));
        worst_below = std::max(worst_below, (g - d) / std::max(g, 1e-9));
        worst_absolute = std::max(worst_absolute, d - g);
        if(g > 2.)
          worst_relative = std::max(worst_relative, (d - g) / g);
        BS_CHECK(d >= (eig<K>(s.point(a)) - eig<K>(s.point(b))).norm() - 1e-12, "sphere: shorter than the chord");
      }
      // Chords of at most `rings` edges: each at most (rings h)^2 / 24 shorter than its arc (radius 1).
      const double chord_bound = std::pow(rings * q.max_edge_length(), 2) / 24.;
      std::cout << "  unit sphere, " << rings << " ring(s), one ring h = " << q.max_edge_length()
                << ": distance - geodesic <= " << worst_absolute << ", <= " << worst_relative
                << " x geodesic beyond 2, <= h + " << worst_excess << " x geodesic; geodesic - distance <= "
                << worst_below << " x geodesic (chord bound " << chord_bound << ")" << std::endl;
      BS_CHECK(worst_below <= chord_bound, "sphere: below the geodesic by " << worst_below << " x geodesic");
      // Documented in Quotient_domain: with the default rings, within one ring plus a few percent.
      if(rings == BS::Quotient_domain<K>::default_rings)
        BS_CHECK(worst_excess <= 0.03, "sphere, default rings: relative excess beyond one ring " << worst_excess);
    }
  }
  // Ellipsoid: points of chart 0 against points of chart 1 (and of the margins).
  const Shape<K> s = ellipsoid<K>();
  const BS::Blended_shape_pieces<K> pieces(s, resolution);
  const auto t = std::chrono::steady_clock::now();
  const BS::Quotient_domain<K> q(s, pieces);
  const double built = since(t);
  const auto t2 = std::chrono::steady_clock::now();
  const auto all = q.distances_from(q.node(0).point);
  std::cout << "  ellipsoid at resolution " << resolution << ": built in " << built << " s, one source to all nodes in "
            << since(t2) << " s (" << all.node_distances().size() << " nodes)" << std::endl;
  check_connected(q, "ellipsoid");
  Mesh_reference<K> ref = make_reference(s, q.rings(), "ellipsoid");
  const double ring = std::max(q.max_edge_length(), ref.max_edge_length());
  auto in_chart = [&](std::size_t chart) {
    return [&, chart] {
      for(;;)
      {
        BS::Shape_point p = random_surface_point(s, 0, rng);
        if(p.u.chart == chart)
          return p;
      }
    };
  };
  report_agreement<K>("ellipsoid, chart 0 to chart 1",
                      compare_with_mesh(q, ref, in_chart(0), in_chart(1), ring, "ellipsoid seam"), ring);
}

// (2) A split across the seam and a gradual part: gluing across strips and disks.
template <class K>
void test_blends(std::mt19937& rng)
{
  const Shape<K> s = seam_split_and_part<K>();
  const BS::Blended_shape_pieces<K> pieces(s, resolution);
  const BS::Quotient_domain<K> q(s, pieces);
  check_connected(q, "split and part");
  Mesh_reference<K> ref = make_reference(s, q.rings(), "split and part");
  const double ring = std::max(q.max_edge_length(), ref.max_edge_length());
  auto any = [&] { return random_surface_point(s, rng); };
  // Points of the split-off cap and of the part against anywhere.
  auto on_added = [&] { return random_surface_point(s, 1 + rng() % 2, rng); };
  report_agreement<K>("split over the seam and a part, anywhere",
                      compare_with_mesh(q, ref, any, any, ring, "split and part"), ring);
  report_agreement<K>("split over the seam and a part, from the added components",
                      compare_with_mesh(q, ref, on_added, any, ring, "split and part, added"), ring);

  // (4) Metric properties on random points, spread over all components.
  const int n = sources * targets;
  double worst_triangle = 0.;
  for(int i = 0; i < n; ++i)
  {
    const BS::Shape_point a = any(), b = any(), c = any();
    const double ab = q.topological_distance(a, b), ba = q.topological_distance(b, a);
    const double bc = q.topological_distance(b, c), ac = q.topological_distance(a, c);
    BS_CHECK(ab == ba, "symmetry: " << ab << " != " << ba);
    BS_CHECK(q.topological_distance(a, a) == 0., "d(a, a) = " << q.topological_distance(a, a));
    // The same point given through another chart (the other ellipsoid chart, in the margin).
    BS::Shape_point a2 = a;
    if(s.component(a.component).shape().to_chart(a.u, 1 - a.u.chart, a2.u) && a2.u.chart != a.u.chart)
      BS_CHECK(q.topological_distance(a, a2) <= 1e-9, "same point in two charts: " << q.topological_distance(a, a2));
    worst_triangle = std::max(worst_triangle, ac - ab - bc);
    BS_CHECK(ac <= ab + bc + 1e-12 * (1. + ac), "triangle inequality: " << ac << " > " << ab << " + " << bc);
    BS_CHECK(ab >= (eig<K>(s.point(a)) - eig<K>(s.point(b))).norm() - 1e-12, "shorter than the straight segment");
  }
  std::cout << "  metric: " << n << " triples, max d(a,c) - d(a,b) - d(b,c) = " << worst_triangle << std::endl;

  // A closed hole half blended in (Two_disks domain, gradual): the hole's
  // disks glue into the base's disks around both poles.
  Shape<K> h(BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1.));
  h.add_hole(BS::Shape_point(0, BS::Chart_point(0, 0.05, 0.)), BS::Shape_point(0, BS::Chart_point(1, 0., 0.05)), 0.3,
             0.08, 0.1);
  set_parameter(h, "b0.h", 0.5);
  set_parameter(h, "b1.h", 0.3);
  const BS::Blended_shape_pieces<K> hole_pieces(h, resolution);
  const BS::Quotient_domain<K> hq(h, hole_pieces);
  check_connected(hq, "pinched hole");
  Mesh_reference<K> href = make_reference(h, hq.rings(), "pinched hole");
  const double hring = std::max(hq.max_edge_length(), href.max_edge_length());
  auto on_hole = [&] { return random_surface_point(h, 1, rng); };
  auto anywhere = [&] { return random_surface_point(h, rng); };
  report_agreement<K>("pinched hole (gradual), from the hole component",
                      compare_with_mesh(hq, href, on_hole, anywhere, hring, "pinched hole"), hring);
}

// (3) A handle: points on the tunnel's wall and on the outer surface facing
// them are close in space, far on the surface.
template <class K>
void test_handle(std::mt19937& rng)
{
  const Shape<K> s = sphere_with_tunnel<K>();
  const BS::Blended_shape_pieces<K> pieces(s, resolution);
  const BS::Quotient_domain<K> q(s, pieces);
  check_connected(q, "tunnel");
  Mesh_reference<K> ref = make_reference(s, q.rings(), "tunnel");
  const double ring = std::max(q.max_edge_length(), ref.max_edge_length());
  const Quotient_rings<K> qrings(q);
  double min_ratio = HUGE_VAL, worst = 0., worst_rings = 0.;
  const int n = 12;
  for(int k = 0; k < n; ++k)
  {
    const double theta = 2. * M_PI * (k + 0.37) / n;
    const BS::Shape_point wall(1, BS::Chart_point(0, theta, 0.)); // the middle of the tube
    const Eigen::Vector3d x = eig<K>(s.point(wall));
    const double omega = std::atan2(x.y(), x.x());
    const BS::Shape_point outside(0, BS::Chart_point(0, std::cos(omega), std::sin(omega))); // the equator
    const BS::Shape_point across(1, BS::Chart_point(0, theta + M_PI, 0.)); // the wall facing it
    for(const BS::Shape_point& b : {outside, across})
    {
      const double dq = q.topological_distance(wall, b);
      const double euclid = (x - eig<K>(s.point(b))).norm();
      const auto ra = ref.query(x);
      const auto rb = ref.query(eig<K>(s.point(b)));
      const double dr = Mesh_reference<K>::distance(ra, ref.distances(ra), rb);
      const double local = std::max({ref.endpoint_ring(ra, rb), qrings.at(x), qrings.at(eig<K>(s.point(b)))});
      worst = std::max(worst, std::abs(dq - dr));
      worst_rings = std::max(worst_rings, std::abs(dq - dr) / local);
      BS_CHECK(std::abs(dq - dr) <= local,
               "tunnel: quotient " << dq << " vs single mesh " << dr << " (one local ring " << local << ")");
      if(b.component == 0)
      {
        min_ratio = std::min(min_ratio, dq / euclid);
        BS_CHECK(dq > 2. * euclid, "tunnel: wall to outside " << dq << " on the surface, " << euclid << " in space");
      }
      else
        BS_CHECK(dq > 1.2 * euclid, "tunnel: across the tunnel " << dq << " on the surface, " << euclid << " in space");
    }
  }
  std::cout << "  tunnel wall to outer surface: surface / space distance >= " << min_ratio
            << "; max |quotient - single mesh| " << worst << " = " << worst_rings << " local rings (global ring "
            << ring << ")" << std::endl;
  auto any = [&] { return random_surface_point(s, rng); };
  report_agreement<K>("tunnel, anywhere", compare_with_mesh(q, ref, any, any, ring, "tunnel"), ring);
}

// (5) Bad input.
template <class K>
void test_bad_input()
{
  const Shape<K> s = seam_split_and_part<K>();
  const BS::Blended_shape_pieces<K> pieces(s, 6);
  const BS::Quotient_domain<K> q(s, pieces, 2);
  const BS::Shape_point good(0, BS::Chart_point(0, 0., 0.));
  auto expect = [&](const BS::Shape_point& p, const std::string& what, const std::string& name) {
    for(int order = 0; order < 2; ++order)
    {
      bool thrown = false;
      try
      {
        if(order == 0)
          q.topological_distance(p, good);
        else
          q.distances_from(good)(p);
      }
      catch(const std::invalid_argument& e)
      {
        thrown = std::string(e.what()).find(what) != std::string::npos;
        BS_CHECK(thrown, name << ": message '" << e.what() << "' does not say '" << what << "'");
        thrown = true;
      }
      BS_CHECK(thrown, name << ": no std::invalid_argument");
    }
  };
  expect(BS::Shape_point(7, BS::Chart_point(0, 0., 0.)), "no such component", "component out of range");
  expect(BS::Shape_point(0, BS::Chart_point(2, 0., 0.)), "no such chart", "chart out of range");
  expect(BS::Shape_point(0, BS::Chart_point(0, NAN, 0.)), "non-finite", "NaN");
  expect(BS::Shape_point(0, BS::Chart_point(0, 1.5, 0.)), "outside the chart", "outside the domain");
  // The split's region centre on the base is discarded: not on the surface.
  expect(BS::Shape_point(0, BS::Chart_point(0, 0.93, 0.1)), "not on the surface", "discarded point");
  bool thrown = false;
  try
  {
    BS::Quotient_domain<K>(s, BS::Blended_shape_pieces<K>(ellipsoid<K>(), 6));
  }
  catch(const std::invalid_argument& e)
  {
    thrown = std::string(e.what()).find("pieces do not match") != std::string::npos;
  }
  BS_CHECK(thrown, "pieces of another shape accepted");
  for(int rings : {0, 9})
  {
    thrown = false;
    try
    {
      BS::Quotient_domain<K>(s, pieces, rings);
    }
    catch(const std::invalid_argument&)
    {
      thrown = true;
    }
    BS_CHECK(thrown, "rings " << rings << " accepted");
  }
  thrown = false;
  try
  {
    q.node(q.number_of_nodes());
  }
  catch(const std::out_of_range&)
  {
    thrown = true;
  }
  BS_CHECK(thrown, "node out of range accepted");
}

template <class K>
void run(const char* kernel)
{
  std::cout << "kernel " << kernel << std::endl;
  std::mt19937 rng(11);
  auto t = std::chrono::steady_clock::now();
  test_seam<K>(rng);
  std::cout << "  (seam: " << since(t) << " s)" << std::endl;
  t = std::chrono::steady_clock::now();
  test_blends<K>(rng);
  std::cout << "  (blends: " << since(t) << " s)" << std::endl;
  t = std::chrono::steady_clock::now();
  test_handle<K>(rng);
  std::cout << "  (handle: " << since(t) << " s)" << std::endl;
  test_bad_input<K>();
}

// Every check of this part.
void run_all()
{
  blended_shape_test::for_each_kernel([](auto kernel, const char* name) { run<decltype(kernel)>(name); });
}

} // namespace quotient_domain_checks

#endif // BLENDED_SHAPE_QUOTIENT_DOMAIN_CHECKS_H
