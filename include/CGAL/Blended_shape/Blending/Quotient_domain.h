// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_QUOTIENT_DOMAIN_H
#define CGAL_BLENDED_SHAPE_BLENDING_QUOTIENT_DOMAIN_H

#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

namespace internal {

// Point location in the chart coordinates of one Chart_mesh: a uniform grid
// of buckets over the domain's bounding box, each holding the faces whose
// (unwrapped) chart triangles overlap it. Periodic coordinates wrap.
template <class GeomTraits>
class Chart_face_locator
{
public:
  typedef Chart_mesh<GeomTraits> Mesh;
  typedef typename Mesh::face_descriptor face_descriptor;
  typedef typename Mesh::Chart_coordinates Chart_coordinates;

  // The face found, its barycentric coordinates (in the order of
  // Chart_mesh::face_vertices()), and whether the point is inside it (to
  // rounding); a point outside the tessellation (between the boundary
  // polygon of a disk mesh and its circle) gets the face with the largest
  // smallest barycentric coordinate.
  struct Location
  {
    std::size_t face = 0;
    std::array<double, 3> barycentric = {{1., 0., 0.}};
    bool inside = false;
  };

  explicit Chart_face_locator(const Mesh& m)
  {
    const Chart_domain& d = m.domain();
    m_period[0] = d.x_period();
    m_period[1] = d.y_period();
    if(d.kind == Chart_kind::Disk)
    {
      m_lo = {{-d.radius, -d.radius}};
      m_hi = {{d.radius, d.radius}};
    }
    else
    {
      m_lo = {{0., d.y_min}};
      m_hi = {{2. * M_PI, d.y_max}};
    }
    const std::size_t nf = m.mesh().number_of_faces();
    m_corners.reserve(nf);
    for(face_descriptor f : m.mesh().faces())
      m_corners.push_back(m.face_chart_coordinates(f));
    // About two faces per bucket.
    m_n = (std::max)(1, int(std::sqrt(double(nf) / 2.)));
    for(int k = 0; k < 2; ++k)
      m_size[k] = (m_hi[k] - m_lo[k]) / m_n;
    m_cells.assign(std::size_t(m_n) * std::size_t(m_n), std::vector<std::size_t>());
    for(std::size_t f = 0; f < nf; ++f)
    {
      std::array<int, 2> from, to;
      for(int k = 0; k < 2; ++k)
      {
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for(const Chart_coordinates& c : m_corners[f])
        {
          lo = (std::min)(lo, c[std::size_t(k)]);
          hi = (std::max)(hi, c[std::size_t(k)]);
        }
        from[std::size_t(k)] = cell_coordinate(k, lo);
        to[std::size_t(k)] = cell_coordinate(k, hi);
        if(m_period[k] == 0.)
        {
          from[std::size_t(k)] = clamp(from[std::size_t(k)]);
          to[std::size_t(k)] = clamp(to[std::size_t(k)]);
        }
      }
      for(int i = from[0]; i <= to[0]; ++i)
        for(int j = from[1]; j <= to[1]; ++j)
          m_cells[cell(i, j)].push_back(f);
    }
  }

  Location locate(double x, double y) const
  {
    const double q[2] = {x, y};
    double r[2];
    for(int k = 0; k < 2; ++k)
      r[k] = (m_period[k] > 0.) ? internal::wrap_angle(q[k]) : q[k];
    const int ci = cell_coordinate(0, r[0]), cj = cell_coordinate(1, r[1]);
    Location best;
    double best_score = -HUGE_VAL;
    std::vector<std::size_t> seen;
    for(int i = ci - 1; i <= ci + 1; ++i)
      for(int j = cj - 1; j <= cj + 1; ++j)
      {
        if((m_period[0] == 0. && (i < 0 || i >= m_n)) || (m_period[1] == 0. && (j < 0 || j >= m_n)))
          continue;
        for(std::size_t f : m_cells[cell(i, j)])
          try_face(f, r, best, best_score);
      }
    if(best_score < -1e-9) // not inside any nearby face: look at all of them
      for(std::size_t f = 0; f < m_corners.size(); ++f)
        try_face(f, r, best, best_score);
    best.inside = best_score >= -1e-9;
    return best;
  }

private:
  int cell_coordinate(int k, double v) const { return int(std::floor((v - m_lo[std::size_t(k)]) / m_size[k])); }
  int clamp(int i) const { return (std::min)((std::max)(i, 0), m_n - 1); }
  std::size_t cell(int i, int j) const
  {
    auto wrap = [&](int a, int k) {
      if(m_period[k] == 0.)
        return clamp(a);
      const int w = a % m_n;
      return (w < 0) ? w + m_n : w;
    };
    return std::size_t(wrap(j, 1)) * std::size_t(m_n) + std::size_t(wrap(i, 0));
  }

  void try_face(std::size_t f, const double r[2], Location& best, double& best_score) const
  {
    const std::array<Chart_coordinates, 3>& c = m_corners[f];
    double q[2];
    for(int k = 0; k < 2; ++k) // the copy of the query nearest to the face, across periodic seams
      q[k] = (m_period[k] > 0.) ? r[k] + m_period[k] * std::round((c[0][std::size_t(k)] - r[k]) / m_period[k]) : r[k];
    const double bx = c[1][0] - c[0][0], by = c[1][1] - c[0][1];
    const double cx = c[2][0] - c[0][0], cy = c[2][1] - c[0][1];
    const double qx = q[0] - c[0][0], qy = q[1] - c[0][1];
    const double det = bx * cy - by * cx;
    if(!(std::abs(det) > 0.))
      return;
    const double s = (qx * cy - qy * cx) / det, t = (bx * qy - by * qx) / det;
    const std::array<double, 3> b = {{1. - s - t, s, t}};
    const double score = (std::min)(b[0], (std::min)(b[1], b[2]));
    if(score > best_score)
    {
      best_score = score;
      best.face = f;
      best.barycentric = b;
    }
  }

  std::array<double, 2> m_lo, m_hi;
  double m_period[2];
  double m_size[2];
  int m_n = 1;
  std::vector<std::array<Chart_coordinates, 3>> m_corners;
  std::vector<std::vector<std::size_t>> m_cells;
};

} // namespace internal

/*!
\ingroup PkgBlendedShapeBlending

The domain of a blended shape as a quotient (eq. 1, 2), discretized over
the chart meshes of `Blended_shape_pieces`: a weighted graph whose nodes
are the chart-mesh vertices that lie on the surface and whose edges join
points that are neighbours on the surface, within a chart or across the
identifications of the quotient (the primitives' own chart seams and the
blends' correspondences `beta`). It answers "which places of the domain
are adjacent" (region growing over the whole model, sec. 5.4) and "how far
apart are two places on the surface" (the topological distance that tells
a self-proximity across a gap from a mere neighbourhood, before a hole is
added, sec. 5.4).

<b>Nodes.</b> Every vertex of every piece (one chart of one component)
whose chart point is on the surface (`Blended_shape::is_on_surface()`).
A node keeps its piece, its vertex, its chart point, the canonical
representative of that point (`Blended_shape::canonical_point()`) and its
position `s` on the surface. Points of the quotient covered by several
charts (chart overlap margins, both sides of a strip, the added part of a
gradual blend) have one node in each covering piece, all at the same place.

<b>Quotient adjacency.</b> Two kinds of edges, weighted by the distance in
space of their end positions:
- the edges of the chart meshes between two nodes (neighbours in one chart);
- gluing edges: a node whose chart point is not its own canonical
  representative is joined to the corners (those that are nodes) of the face
  of the canonical chart's mesh that contains its canonical point, located
  by its chart coordinates. If none of the corners is on the surface, to the
  nearest node around that face.

Why faces and not coincident vertices: identifying nodes whose canonical
points coincide only works where two tessellations happen to share
vertices (the equator ring of the ellipsoid's two charts). The two sides
of a strip are tessellated independently in their own charts, and `beta`
maps one side's vertices to points inside the other side's faces; the
margin rings of a disk chart do not match the other chart's rings either.
Locating the canonical point in the canonical chart works the same way for
every identification of eq. 1 (seam, strip, disk of a gradual blend, hole
end), needs nothing but `canonical_point()`, and gives gluing edges no
longer than a face. Gluing from each non-canonical node to the canonical
chart suffices: every point of an overlap has one canonical representative,
so both sides of the overlap meet in the canonical chart's mesh.

<b>Topological distance.</b> The length of a shortest path (Dijkstra) in
the distance graph, whose edges join every node to every node it reaches
in at most `rings` steps of the quotient adjacency, with their distance in
space as the weight (`rings = 1`: the adjacency itself). A query point is
attached to the corners of the canonical face that contains its canonical
point, like a glued node; two points in the same face are also joined
directly. More rings give the paths more directions to choose from, so the
distance overestimates the geodesic less. Measured on the unit sphere at
resolution 16 (`max_edge_length()` 0.166, test `test_blended_shape_quotient_domain`),
the distance exceeds the great-circle distance by at most 1.7 edge lengths
(13 % of long distances) with 1 ring, 0.8 edge lengths (6 %) with 2 rings
and 0.6 edge lengths (4 %) with 3 rings, the default. From below, the
distance is a sum of chords, each shorter than the geodesic between its
ends by a relative `(L / r)^2 / 24` at most (`L <= rings max_edge_length()`
the chord, `r` the radius of curvature): 0.5 % with 3 rings in that
measurement; and it is never shorter than the straight segment between
the two points.

So: an approximate geodesic distance, within about one edge length
(`max_edge_length()`) plus a few percent, provided the pieces resolve the
shape (edges short against the strips, the discarded regions and the radii
of curvature). Two graphs of the same surface agree to the same accuracy:
the test finds the distance within one ring of Dijkstra on the closed
mesh of make_unified_mesh() across the ellipsoid's seam, across blends and
around a handle.

The result is a metric on the points of the surface: `d(a, a) = 0`,
`d(a, b) = d(b, a)` exactly (the query always runs from the smaller of the
two points), and the triangle inequality holds (every attachment is a face
whose corners are joined to each other), all up to rounding.

The structure is a snapshot: it keeps a copy of the shape and does not
follow later changes of it or of the pieces; build a new one after the
parameters or the blends changed.

\tparam GeomTraits a CGAL kernel whose `FT` is `double`.
*/
template <class GeomTraits>
class Quotient_domain
{
public:
  typedef Blended_shape<GeomTraits> Shape;                ///< the blended shape
  typedef Blended_shape_pieces<GeomTraits> Pieces;        ///< the chart meshes of the shape
  typedef typename Shape::Geom_traits Geom_traits;        ///< the kernel (the shape's)
  typedef typename Shape::Point_3 Point_3;                ///< the point type
  typedef Chart_mesh<GeomTraits> Piece_mesh;              ///< one chart's mesh
  typedef typename Piece_mesh::vertex_descriptor vertex_descriptor; ///< a vertex of a piece
  typedef typename Piece_mesh::face_descriptor face_descriptor;     ///< a face of a piece

  /// The default number of rings of the distance graph.
  static constexpr int default_rings = 3;
  /// The largest number of rings accepted.
  static constexpr int maximum_rings = 8;
  /// Returned by node_of() for a vertex that is not on the surface.
  static constexpr std::size_t no_node = std::numeric_limits<std::size_t>::max();

  /// A node: a chart-mesh vertex on the surface.
  struct Node
  {
    std::size_t piece;       ///< the index of its piece in `Blended_shape_pieces::pieces()`
    vertex_descriptor vertex; ///< the vertex in that piece's mesh
    Shape_point point;       ///< the vertex's chart point, on the piece's component
    Shape_point canonical;   ///< the canonical representative of `point` (`Blended_shape::canonical_point()`)
    Point_3 position;        ///< the point of the surface, `s` at `canonical`
  };

  /// An edge of the quotient adjacency, seen from one of its ends.
  struct Neighbor
  {
    std::size_t node; ///< the other end
    double length;    ///< the distance in space between the two ends' positions
    bool glued;       ///< whether it is a gluing edge (between different charts or across an identification)
  };

  /// \name Creation
  /// @{

  /*!
  Builds the quotient graph of `shape` over the chart meshes `pieces`,
  which must be up to date with `shape` (made from it, or
  `Blended_shape_pieces::update()` called after its last change). `rings`
  (in [1, maximum_rings]) sets the distance graph: see the class description.
  \throws std::invalid_argument if `rings` is out of range or the pieces
          do not have the structure of `shape` (one piece per chart of every
          component, in order, with the same chart kinds).
  */
  Quotient_domain(const Shape& shape, const Pieces& pieces, int rings = default_rings)
    : m_shape(shape), m_pieces(pieces), m_rings(rings)
  {
    if(rings < 1 || rings > maximum_rings)
      throw std::invalid_argument("Quotient_domain: rings must be in [1, " + std::to_string(maximum_rings) + "], got " +
                                  std::to_string(rings));
    check_pieces();
    build_nodes();
    build_adjacency();
    build_distance_graph();
  }
  /// @}

  /// \name The quotient graph
  /// @{

  /// The shape (a copy taken at construction).
  const Shape& shape() const { return m_shape; }
  /// The chart meshes (a copy taken at construction).
  const Pieces& pieces() const { return m_pieces; }
  /// The number of rings of the distance graph.
  int rings() const { return m_rings; }
  /// The number of nodes.
  std::size_t number_of_nodes() const { return m_nodes.size(); }
  /// Node `i`. \throws std::out_of_range if there is no such node
  const Node& node(std::size_t i) const
  {
    check_node(i);
    return m_nodes[i];
  }
  /// The node of vertex `v` of piece `piece`, or `no_node` if that vertex is
  /// not on the surface. \throws std::out_of_range if there is no such piece or vertex
  std::size_t node_of(std::size_t piece, vertex_descriptor v) const
  {
    if(piece >= m_node_of.size() || std::size_t(v) >= m_node_of[piece].size())
      throw std::out_of_range("Quotient_domain::node_of: no vertex " + std::to_string(std::size_t(v)) + " in piece " +
                              std::to_string(piece));
    return m_node_of[piece][std::size_t(v)];
  }
  /// The quotient adjacency of node `i`: its mesh neighbours and its gluing
  /// edges (in both directions), sorted by node, each once. Breadth-first
  /// search over it counts hops on the surface.
  /// \throws std::out_of_range if there is no such node
  const std::vector<Neighbor>& neighbors(std::size_t i) const
  {
    check_node(i);
    return m_adjacency[i];
  }
  /// The index of the piece of `p`'s chart (of its component) in `pieces().pieces()`.
  /// \pre `p` has a valid component and chart
  std::size_t piece_of(const Shape_point& p) const { return m_first_piece[p.component] + p.u.chart; }
  /// The length of the longest edge of the quotient adjacency: the size of
  /// one ring, the additive error scale of the distances.
  double max_edge_length() const { return m_max_edge; }

  /// Up to three nodes and weights (non-negative, summing to 1) that
  /// interpolate a function given at the nodes linearly at a point of the surface.
  struct Node_weights
  {
    std::array<std::size_t, 3> nodes = {{0, 0, 0}}; ///< the nodes
    std::array<double, 3> weights = {{0., 0., 0.}}; ///< their weights
    std::size_t count = 0;                          ///< how many (1 to 3)
  };

  /*!
  The interpolation weights at `p`, a point of the surface: the barycentric
  coordinates of its canonical point in the face of the canonical chart's
  mesh that holds it, over the corners that are nodes (renormalized); weight
  1 on the nearest node if no corner is on the surface.
  \throws std::invalid_argument as topological_distance() does
  */
  Node_weights interpolation_weights(const Shape_point& p) const
  {
    const Attachment a = attach_query(p, "interpolation_weights", "query");
    Node_weights w;
    w.count = a.count;
    w.nodes = a.nodes;
    double sum = 0.;
    for(std::size_t k = 0; k < a.count; ++k)
      sum += (w.weights[k] = (std::max)(a.barycentric[k], 0.));
    for(std::size_t k = 0; k < a.count; ++k) // all corners outside the face's triangle: equal shares
      w.weights[k] = (sum > 0.) ? w.weights[k] / sum : 1. / double(a.count);
    return w;
  }
  /// @}

  /// \name Topological distance
  /// @{

  /*!
  The topological distance between the points `a` and `b` of the surface:
  the length of a shortest path between them on the distance graph (see
  the class description), an approximate geodesic distance over the quotient
  domain. `d(a, b) == d(b, a)` exactly, `d(a, a) == 0`. Infinite if no path
  joins them.
  \throws std::invalid_argument if a point has no such component or chart,
          non-finite coordinates or coordinates outside its chart's domain, or
          is not on the surface (in a discarded part of the domain).
  */
  double topological_distance(const Shape_point& a, const Shape_point& b) const
  {
    Attachment p = attach_query(a, "topological_distance", "first");
    Attachment q = attach_query(b, "topological_distance", "second");
    if(q.key() < p.key())
      std::swap(p, q);
    double best = same_face(p, q) ? (p.x - q.x).norm() : HUGE_VAL;
    std::vector<double> dist;
    dijkstra(p, dist, [&](std::size_t i, double d) {
      if(d >= best)
        return true;
      for(std::size_t k = 0; k < q.count; ++k)
        if(q.nodes[k] == i)
          best = (std::min)(best, d + q.weights[k]);
      return false;
    });
    return best;
  }

private:
  // Where a point of the surface is tied to the graph: the face of the
  // canonical chart's mesh holding its canonical point, and up to three nodes
  // (the face's corners on the surface; or the nearest node) with their
  // distances in space.
  struct Attachment
  {
    std::size_t piece = 0, face = 0;
    Shape_point canonical;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    std::array<std::size_t, 3> nodes = {{0, 0, 0}};
    std::array<double, 3> weights = {{0., 0., 0.}};     // distances in space
    std::array<double, 3> barycentric = {{1., 0., 0.}}; // in the face (1 for a nearest node)
    std::size_t count = 0;
    std::tuple<std::size_t, std::size_t, double, double> key() const
    {
      return std::make_tuple(piece, face, canonical.u.x, canonical.u.y);
    }
  };

public:
  /// The distances from one point of the surface to all nodes and to any
  /// other point: one Dijkstra run for many queries. Made by distances_from();
  /// valid as long as the `Quotient_domain` that made it.
  class Distance_map
  {
  public:
    /// The source point.
    const Shape_point& source() const { return m_source_point; }
    /// The distance from the source to node `i` (infinite if unreachable).
    /// \throws std::out_of_range if there is no such node
    double at_node(std::size_t i) const { return m_dist.at(i); }
    /// The distances from the source to all nodes.
    const std::vector<double>& node_distances() const { return m_dist; }
    /// The distance from the source to `b`: equal to `topological_distance(source(), b)`
    /// up to rounding. \throws std::invalid_argument as topological_distance() does
    double operator()(const Shape_point& b) const
    {
      const Attachment q = m_domain->attach_query(b, "Distance_map", "target");
      double best = same_face(m_source, q) ? (m_source.x - q.x).norm() : HUGE_VAL;
      for(std::size_t k = 0; k < q.count; ++k)
        best = (std::min)(best, m_dist[q.nodes[k]] + q.weights[k]);
      return best;
    }

  private:
    friend class Quotient_domain;
    const Quotient_domain* m_domain = nullptr;
    Shape_point m_source_point;
    typename Quotient_domain::Attachment m_source;
    std::vector<double> m_dist;
  };

  /// The distances from `a` (Dijkstra over the whole distance graph).
  /// \throws std::invalid_argument as topological_distance() does
  Distance_map distances_from(const Shape_point& a) const
  {
    Distance_map m;
    m.m_domain = this;
    m.m_source_point = a;
    m.m_source = attach_query(a, "distances_from", "source");
    dijkstra(m.m_source, m.m_dist, [](std::size_t, double) { return false; });
    return m;
  }
  /// @}

private:
  static bool same_face(const Attachment& a, const Attachment& b) { return a.piece == b.piece && a.face == b.face; }

  static Eigen::Vector3d to_eigen(const Point_3& p) { return internal::to_eigen(p); }

  void check_node(std::size_t i) const
  {
    if(i >= m_nodes.size())
      throw std::out_of_range("Quotient_domain: no node " + std::to_string(i) + " (there are " +
                              std::to_string(m_nodes.size()) + ")");
  }

  void check_pieces() const
  {
    const auto& P = m_pieces.pieces();
    std::size_t k = 0;
    bool ok = true;
    for(std::size_t c = 0; c < m_shape.number_of_components() && ok; ++c)
      for(std::size_t ch = 0; ch < m_shape.component(c).shape().number_of_charts() && ok; ++ch, ++k)
        ok = k < P.size() && P[k].component == c && P[k].mesh.chart_index() == ch &&
             P[k].mesh.domain().kind == m_shape.component(c).shape().chart_domain(ch).kind;
    if(!ok || k != P.size())
      throw std::invalid_argument("Quotient_domain: the pieces do not match the shape (one piece per chart of every "
                                  "component); call Blended_shape_pieces::update(shape) first");
  }

  void build_nodes()
  {
    const auto& P = m_pieces.pieces();
    m_first_piece.assign(m_shape.number_of_components(), 0);
    for(std::size_t k = P.size(); k-- > 0;)
      m_first_piece[P[k].component] = k;
    m_node_of.resize(P.size());
    for(std::size_t k = 0; k < P.size(); ++k)
    {
      const Piece_mesh& m = P[k].mesh;
      m_node_of[k].assign(m.mesh().number_of_vertices(), no_node);
      for(vertex_descriptor v : m.mesh().vertices())
      {
        const Shape_point sp(P[k].component, m.chart_point(v));
        const std::optional<Shape_point> c = m_shape.canonical_point(sp);
        if(!c)
          continue;
        const Point_3 x = m_shape.point(sp);
        m_node_of[k][std::size_t(v)] = m_nodes.size();
        m_nodes.push_back(Node{k, v, sp, *c, x});
        m_x.push_back(to_eigen(x));
      }
      m_locators.emplace_back(m);
    }
  }

  // Ties the surface point with canonical representative `c` and position `x`
  // to the graph (see Attachment).
  Attachment attach(const Shape_point& c, const Eigen::Vector3d& x) const
  {
    Attachment a;
    a.canonical = c;
    a.x = x;
    a.piece = piece_of(c);
    const Piece_mesh& m = m_pieces.pieces()[a.piece].mesh;
    const typename internal::Chart_face_locator<GeomTraits>::Location loc = m_locators[a.piece].locate(c.u.x, c.u.y);
    a.face = loc.face;
    const face_descriptor f(static_cast<typename face_descriptor::size_type>(a.face));
    const std::array<vertex_descriptor, 3> corners = m.face_vertices(f);
    for(std::size_t k = 0; k < 3; ++k)
    {
      const std::size_t n = m_node_of[a.piece][std::size_t(corners[k])];
      if(n != no_node)
      {
        a.nodes[a.count] = n;
        a.weights[a.count] = (m_x[n] - x).norm();
        a.barycentric[a.count] = loc.barycentric[k];
        ++a.count;
      }
    }
    if(a.count == 0)
    { // the point is on the surface, its face's corners are not: the nearest node within two rings
      std::vector<vertex_descriptor> ring(corners.begin(), corners.end());
      for(int step = 0; step < 2 && a.count == 0; ++step)
      {
        std::vector<vertex_descriptor> next;
        for(vertex_descriptor v : ring)
          for(auto h : CGAL::halfedges_around_target(m.mesh().halfedge(v), m.mesh()))
            next.push_back(m.mesh().source(h));
        ring.swap(next);
        for(vertex_descriptor v : ring)
        {
          const std::size_t n = m_node_of[a.piece][std::size_t(v)];
          if(n == no_node)
            continue;
          const double w = (m_x[n] - x).norm();
          if(a.count == 0 || w < a.weights[0])
          {
            a.nodes[0] = n;
            a.weights[0] = w;
            a.barycentric[0] = 1.;
            a.count = 1;
          }
        }
      }
    }
    return a;
  }

  Attachment attach_query(const Shape_point& p, const char* function, const char* which) const
  {
    auto describe = [&]() {
      std::ostringstream s;
      s.precision(17);
      s << "Quotient_domain::" << function << ": the " << which << " point (component " << p.component << ", chart "
        << p.u.chart << ", (" << p.u.x << ", " << p.u.y << "))";
      return s.str();
    };
    if(p.component >= m_shape.number_of_components())
      throw std::invalid_argument(describe() + " has no such component: the shape has " +
                                  std::to_string(m_shape.number_of_components()));
    if(p.u.chart >= m_shape.component(p.component).shape().number_of_charts())
      throw std::invalid_argument(describe() + " has no such chart: the component has " +
                                  std::to_string(m_shape.component(p.component).shape().number_of_charts()));
    if(!std::isfinite(p.u.x) || !std::isfinite(p.u.y))
      throw std::invalid_argument(describe() + " has non-finite chart coordinates");
    if(!m_shape.component(p.component).shape().chart_domain(p.u.chart).contains(p.u.x, p.u.y))
      throw std::invalid_argument(describe() + " is outside the chart's domain");
    const std::optional<Shape_point> c = m_shape.canonical_point(p);
    if(!c)
      throw std::invalid_argument(describe() + " is not on the surface (it is in a discarded part of the domain)");
    return attach(*c, to_eigen(m_shape.point(p)));
  }

  void add_edge(std::size_t i, std::size_t j, bool glued)
  {
    if(i == j)
      return;
    const double w = (m_x[i] - m_x[j]).norm();
    m_adjacency[i].push_back(Neighbor{j, w, glued});
    m_adjacency[j].push_back(Neighbor{i, w, glued});
  }

  void build_adjacency()
  {
    const auto& P = m_pieces.pieces();
    m_adjacency.assign(m_nodes.size(), std::vector<Neighbor>());
    for(std::size_t k = 0; k < P.size(); ++k)
    {
      const auto& mesh = P[k].mesh.mesh();
      for(auto e : mesh.edges())
      {
        const std::size_t i = m_node_of[k][std::size_t(mesh.vertex(e, 0))];
        const std::size_t j = m_node_of[k][std::size_t(mesh.vertex(e, 1))];
        if(i != no_node && j != no_node)
          add_edge(i, j, false);
      }
    }
    // Gluing (eq. 1): each node whose chart point is not its canonical
    // representative, to the canonical chart's face holding that representative.
    for(std::size_t i = 0; i < m_nodes.size(); ++i)
    {
      const Node& n = m_nodes[i];
      if(n.canonical.component == n.point.component && n.canonical.u.chart == n.point.u.chart &&
         n.canonical.u.x == n.point.u.x && n.canonical.u.y == n.point.u.y)
        continue;
      const Attachment a = attach(n.canonical, m_x[i]);
      for(std::size_t k = 0; k < a.count; ++k)
        add_edge(i, a.nodes[k], true);
    }
    m_max_edge = 0.;
    for(std::vector<Neighbor>& l : m_adjacency)
    {
      // Each neighbour once; a mesh edge wins over a gluing edge between the same nodes.
      std::sort(l.begin(), l.end(), [](const Neighbor& a, const Neighbor& b) {
        return a.node < b.node || (a.node == b.node && !a.glued && b.glued);
      });
      l.erase(std::unique(l.begin(), l.end(), [](const Neighbor& a, const Neighbor& b) { return a.node == b.node; }),
              l.end());
      for(const Neighbor& nb : l)
        m_max_edge = (std::max)(m_max_edge, nb.length);
    }
  }

  // The distance graph: every node to every node within `rings` hops of
  // the adjacency, weighted by the distance in space (compressed rows).
  void build_distance_graph()
  {
    const std::size_t n = m_nodes.size();
    m_offsets.assign(n + 1, 0);
    m_targets.clear();
    m_weights.clear();
    std::vector<std::size_t> stamp(n, no_node);
    std::vector<std::size_t> frontier, next;
    for(std::size_t i = 0; i < n; ++i)
    {
      stamp[i] = i;
      frontier.assign(1, i);
      for(int r = 0; r < m_rings && !frontier.empty(); ++r)
      {
        next.clear();
        for(std::size_t u : frontier)
          for(const Neighbor& nb : m_adjacency[u])
            if(stamp[nb.node] != i)
            {
              stamp[nb.node] = i;
              next.push_back(nb.node);
              m_targets.push_back(nb.node);
              m_weights.push_back((m_x[i] - m_x[nb.node]).norm());
            }
        frontier.swap(next);
      }
      m_offsets[i + 1] = m_targets.size();
    }
  }

  // Dijkstra from the attachment `a`; `stop(i, d)` is called when node `i`
  // is settled at distance `d` and ends the search by returning true.
  template <class Stop>
  void dijkstra(const Attachment& a, std::vector<double>& dist, const Stop& stop) const
  {
    dist.assign(m_nodes.size(), HUGE_VAL);
    typedef std::pair<double, std::size_t> Item;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for(std::size_t k = 0; k < a.count; ++k)
      if(a.weights[k] < dist[a.nodes[k]])
      {
        dist[a.nodes[k]] = a.weights[k];
        queue.push(Item(a.weights[k], a.nodes[k]));
      }
    while(!queue.empty())
    {
      const Item top = queue.top();
      queue.pop();
      const std::size_t i = top.second;
      if(top.first > dist[i])
        continue;
      if(stop(i, top.first))
        return;
      for(std::size_t e = m_offsets[i]; e < m_offsets[i + 1]; ++e)
      {
        const double d = top.first + m_weights[e];
        if(d < dist[m_targets[e]])
        {
          dist[m_targets[e]] = d;
          queue.push(Item(d, m_targets[e]));
        }
      }
    }
  }

  Shape m_shape;
  Pieces m_pieces;
  int m_rings;
  std::vector<Node> m_nodes;
  std::vector<Eigen::Vector3d> m_x;
  std::vector<std::vector<std::size_t>> m_node_of;
  std::vector<std::size_t> m_first_piece;
  std::vector<internal::Chart_face_locator<GeomTraits>> m_locators;
  std::vector<std::vector<Neighbor>> m_adjacency;
  double m_max_edge = 0.;
  std::vector<std::size_t> m_offsets, m_targets;
  std::vector<double> m_weights;
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_QUOTIENT_DOMAIN_H
