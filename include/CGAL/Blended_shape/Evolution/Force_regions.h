// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_EVOLUTION_FORCE_REGIONS_H
#define CGAL_BLENDED_SHAPE_EVOLUTION_FORCE_REGIONS_H

#include <CGAL/Blended_shape/Blending/Quotient_domain.h>

#include <CGAL/Shape_detection/Region_growing/Region_growing.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <deque>
#include <iterator>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeEvolution
/// One data force as the force analysis sees it (eq. 12): the closest point
/// `u` of a data point `p` on the model, how far `p` lies out of the surface
/// along the outward normal, and the point's weight in the fit. The normal
/// force is `F = weight * normal_distance` (`f . n` with `f = w n n^T (p - x)`, eq. 8).
struct Normal_force
{
  Shape_point point;           ///< the closest point `u`, a point of the surface
  double normal_distance = 0.; ///< `n(u) . (p - x(u))`
  double weight = 1.;          ///< `w`: 1, or the robust weight (0 for a stray point)
};

/// \ingroup PkgBlendedShapeEvolution
/// The class of a place of the domain in the force analysis (sec. 5.4, Fig. 16 a).
enum class Force_class : unsigned char
{
  Outward,      ///< `F > eps_F`: pulled outward
  Inward,       ///< `F < -eps_F`: pulled inward
  Equilibrated, ///< `|F| <= eps_F`
  Untouched     ///< no force applied
};

/// \ingroup PkgBlendedShapeEvolution
/// What becomes of the equilibrated parts of the domain in Force_regions.
enum class Equilibrated_regions
{
  /// The outward and inward regions grow into them (Fig. 16 c, the paper):
  /// every region is pulled outward or inward.
  Absorbed,
  /// They stay regions of their own (sign 0). For a model at rest on most
  /// of the data (a robust fit of a body with a part that it takes for
  /// strays): there the part's footprint is the only region pulled, and
  /// absorbing the rest would give it the whole model and no boundary.
  Kept
};

/*!
\ingroup PkgBlendedShapeEvolution

The analysis of the data forces on a model at rest that tells where to
split it (sec. 5.4, eq. 12, 13, Fig. 16): the domain is cut into regions
pulled outward and regions pulled inward, each labelled with its flux, and
the boundary curves between them are ranked by the difference of the fluxes
on their two sides; the first is where the paper splits the model.

<b>Forces on the nodes.</b> The domain is the quotient graph of the model's
chart meshes (`Quotient_domain`): regions grow across chart seams and across
blends, never in one chart alone. Each data force is spread to the corners
of the canonical face that holds its point, with its barycentric
coordinates times its weight `b w`. A node's value is the weighted mean of
the normal distances spread to it,
`F(v) = sum b w d / sum b w`
(a length: how far out of the surface the data lie around `v`). A node
that no force reaches but whose point has its canonical representative in
another chart (the charts' overlap margins, the added side of a strip)
takes the value interpolated there, so that the seams are invisible.

<b>The threshold `eps_F`</b> comes from the noise, measured on the data: each
point's normal distance minus the field `F` interpolated at its place
without that point (leave one out) is the part of the residual that the
smooth misfit does not explain; `sigma = 1.4826 median |.|` over the points
of weight above 1/2 is its standard deviation, robustly. A node's value is
a mean of `n_eff = (sum b w)^2 / sum (b w)^2` such residuals, so
`eps_F(v) = threshold_factor * sigma / sqrt(n_eff(v))`: `threshold_factor`
standard errors (default 3). Nodes with `F > eps_F` are pulled outward,
`F < -eps_F` inward, the others are equilibrated (Fig. 16 a).

<b>Regions</b> (Fig. 16 b, c): the outward, inward and equilibrated nodes grow
into the untouched ones, then the outward and inward nodes grow into the
equilibrated ones (unless `Equilibrated_regions::Kept`). Each growth is simultaneous (breadth first from all
sources at once, one ring per round, ties to the smaller node index), so a
class does not eat another's share because it was seeded first. The
connected sets of nodes of one class are the regions, found by CGAL's
`Shape_detection::Region_growing` with the quotient adjacency as its
neighbour query; the growths themselves are not a region growing from a
seed (a region grown to completion before the next starts would take every
untouched node it reaches), which is why they are written here.

<b>Flux</b> (eq. 13): `f_i = integral of F over region i = sum over its nodes
of A(v) F(v)`, `A(v)` a third of the area of the faces around `v` that are
canonical (their centroid's canonical representative is in their own
chart: each place of the surface is counted once). `F` being a length,
`f_i` is the volume between the data and the model over the region,
positive where the data lie outside: it does not depend on how densely the
scanner sampled the surface, which varies a lot over one view.

A snapshot: it refers to the `Quotient_domain` it was made from, which
must outlive it.

\tparam GeomTraits a CGAL kernel whose `FT` is `double`.
*/
template <class GeomTraits>
class Force_regions
{
public:
  typedef Quotient_domain<GeomTraits> Domain; ///< the domain the regions are made of

  /// The threshold factor used when none is given: three standard errors.
  static constexpr double default_threshold_factor = 3.;

  /// A region `Omega^i` of the domain.
  struct Region
  {
    /// +1 for outward, -1 for inward, 0 for equilibrated (with
    /// `Equilibrated_regions::Kept`, or the single region of a model on
    /// which no force passes the threshold).
    int sign = 0;
    std::vector<std::size_t> nodes; ///< its nodes, in increasing order
    double flux = 0.;               ///< `f_i` (eq. 13)
    double area = 0.;               ///< its area
    /// The area of its nodes that forces reach (not `Force_class::Untouched`):
    /// the part of it that the data cover.
    double covered_area = 0.;
  };

  /// A boundary curve between two regions: a connected set of edges of the
  /// quotient adjacency whose ends lie in the two regions.
  struct Boundary
  {
    std::array<std::size_t, 2> regions = {{0, 0}}; ///< the two regions, the one of larger sign first
    std::vector<std::array<std::size_t, 2>> edges;  ///< its edges: (node of `regions[0]`, node of `regions[1]`)
    double flux_difference = 0.;                    ///< `|f_i - f_j|`
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero(); ///< the mean of its edges' midpoints, in the shape's frame
    std::size_t piece = 0; ///< the piece (chart of a component) that holds most of its nodes' canonical points
  };

  /*!
  Analyses `forces` on `domain`, with `eps_F` at `threshold_factor`
  standard errors (see the class description) and the equilibrated parts
  of the domain absorbed or kept (`equilibrated`).
  \throws std::invalid_argument if `forces` is empty, a force has
          non-finite values or a negative weight, or its point is not a point
          of the surface of the domain's shape (the message names the force),
          or if `threshold_factor` is negative or not finite.
  */
  Force_regions(const Domain& domain, const std::vector<Normal_force>& forces,
                double threshold_factor = default_threshold_factor,
                Equilibrated_regions equilibrated = Equilibrated_regions::Absorbed)
    : m_domain(domain), m_threshold_factor(threshold_factor)
  {
    if(!(threshold_factor >= 0.) || !std::isfinite(threshold_factor))
      throw std::invalid_argument("Force_regions: threshold_factor must be finite and non-negative, got " +
                                  std::to_string(threshold_factor));
    if(forces.empty())
      throw std::invalid_argument("Force_regions: no forces (fit the model to some points first)");
    spread(forces);
    fill_glued_nodes();
    estimate_noise(forces);
    classify();
    grow_into(Force_class::Untouched, [](Force_class c) { return c != Force_class::Untouched; });
    if(equilibrated == Equilibrated_regions::Absorbed)
      grow_into(Force_class::Equilibrated,
                [](Force_class c) { return c == Force_class::Outward || c == Force_class::Inward; });
    segment();
    compute_node_areas();
    compute_fluxes();
    find_boundaries();
  }

  /// The domain.
  const Domain& domain() const { return m_domain; }
  /// The threshold factor.
  double threshold_factor() const { return m_threshold_factor; }
  /// `sigma`: the standard deviation of the data's noise along the normal, measured.
  double noise() const { return m_noise; }

  /// \name Nodes (see Quotient_domain::node())
  /// @{

  /// `F(v)`, 0 at nodes no force reaches.
  double node_force(std::size_t v) const { return m_force.at(v); }
  /// `eps_F(v)` (infinite at nodes no force reaches).
  double node_threshold(std::size_t v) const { return m_threshold.at(v); }
  /// The class of node `v` from its own force (Fig. 16 a), before the regions grow.
  Force_class node_class(std::size_t v) const { return m_class.at(v); }
  /// The region of node `v` (Fig. 16 c).
  std::size_t node_region(std::size_t v) const { return m_region_of.at(v); }
  /// `A(v)`: the area node `v` stands for.
  double node_area(std::size_t v) const { return m_area.at(v); }
  /// @}

  /// The regions, in the order of their smallest node.
  const std::vector<Region>& regions() const { return m_regions; }
  /// The boundary curves, largest flux difference first.
  const std::vector<Boundary>& boundaries() const { return m_boundaries; }
  /// The boundary along which to split (the largest flux difference), or
  /// null if there is none (a single region: nothing to split).
  const Boundary* best_boundary() const { return m_boundaries.empty() ? nullptr : &m_boundaries.front(); }

private:
  typedef typename Domain::Node_weights Node_weights;

  // Fig. 16 a: the weighted means of the normal distances at the nodes.
  void spread(const std::vector<Normal_force>& forces)
  {
    const std::size_t n = m_domain.number_of_nodes();
    m_weight.assign(n, 0.);
    m_weighted_sum.assign(n, 0.);
    m_squared_weight.assign(n, 0.);
    m_force_weights.reserve(forces.size());
    for(std::size_t k = 0; k < forces.size(); ++k)
    {
      const Normal_force& f = forces[k];
      if(!std::isfinite(f.normal_distance) || !std::isfinite(f.weight) || f.weight < 0.)
        throw std::invalid_argument("Force_regions: force " + std::to_string(k) +
                                    " has a non-finite normal distance or a negative or non-finite weight");
      try
      {
        m_force_weights.push_back(m_domain.interpolation_weights(f.point));
      }
      catch(const std::invalid_argument& e)
      {
        throw std::invalid_argument("Force_regions: force " + std::to_string(k) + ": " + e.what());
      }
      const Node_weights& b = m_force_weights.back();
      for(std::size_t c = 0; c < b.count; ++c)
      {
        const double bw = b.weights[c] * f.weight;
        m_weight[b.nodes[c]] += bw;
        m_weighted_sum[b.nodes[c]] += bw * f.normal_distance;
        m_squared_weight[b.nodes[c]] += bw * bw;
      }
    }
    m_force.assign(n, 0.);
    for(std::size_t v = 0; v < n; ++v)
      if(m_weight[v] > 0.)
        m_force[v] = m_weighted_sum[v] / m_weight[v];
  }

  static bool same_point(const Shape_point& a, const Shape_point& b)
  {
    return a.component == b.component && a.u.chart == b.u.chart && a.u.x == b.u.x && a.u.y == b.u.y;
  }

  // Nodes away from their canonical chart take the values interpolated at
  // their canonical point (from the canonical nodes, which keep theirs).
  void fill_glued_nodes()
  {
    const std::vector<double> weight = m_weight, squared = m_squared_weight, force = m_force;
    for(std::size_t v = 0; v < m_domain.number_of_nodes(); ++v)
    {
      const typename Domain::Node& node = m_domain.node(v);
      if(weight[v] > 0. || same_point(node.point, node.canonical))
        continue;
      const Node_weights b = m_domain.interpolation_weights(node.canonical);
      double w = 0., s = 0., q = 0.;
      for(std::size_t c = 0; c < b.count; ++c)
      {
        w += b.weights[c] * weight[b.nodes[c]];
        s += b.weights[c] * weight[b.nodes[c]] * force[b.nodes[c]];
        q += b.weights[c] * squared[b.nodes[c]];
      }
      if(w > 0.)
      {
        m_weight[v] = w;
        m_squared_weight[v] = q;
        m_force[v] = s / w;
      }
    }
  }

  // sigma from the leave-one-out residuals of the points of weight above 1/2.
  void estimate_noise(const std::vector<Normal_force>& forces)
  {
    std::vector<double> residuals;
    residuals.reserve(forces.size());
    for(std::size_t k = 0; k < forces.size(); ++k)
    {
      const Normal_force& f = forces[k];
      if(!(f.weight > 0.5))
        continue;
      const Node_weights& b = m_force_weights[k];
      double field = 0., total = 0.;
      for(std::size_t c = 0; c < b.count; ++c)
      {
        const std::size_t v = b.nodes[c];
        const double bw = b.weights[c] * f.weight;
        const double others = m_weight[v] - bw;
        if(!(others > 1e-12 * m_weight[v]))
          continue; // only this point reaches the node
        field += b.weights[c] * (m_weighted_sum[v] - bw * f.normal_distance) / others;
        total += b.weights[c];
      }
      if(total > 0.)
        residuals.push_back(std::abs(f.normal_distance - field / total));
    }
    m_noise = 0.;
    if(!residuals.empty())
    {
      const auto middle = residuals.begin() + std::ptrdiff_t(residuals.size() / 2);
      std::nth_element(residuals.begin(), middle, residuals.end());
      m_noise = 1.4826 * *middle;
    }
  }

  void classify()
  {
    const std::size_t n = m_domain.number_of_nodes();
    m_class.assign(n, Force_class::Untouched);
    m_threshold.assign(n, HUGE_VAL);
    for(std::size_t v = 0; v < n; ++v)
    {
      if(!(m_weight[v] > 0.))
        continue;
      const double effective_count = m_weight[v] * m_weight[v] / m_squared_weight[v];
      m_threshold[v] = m_threshold_factor * m_noise / std::sqrt(effective_count);
      m_class[v] = (m_force[v] > m_threshold[v])    ? Force_class::Outward
                   : (m_force[v] < -m_threshold[v]) ? Force_class::Inward
                                                    : Force_class::Equilibrated;
    }
    m_label = m_class;
  }

  // Fig. 16 b, c: the nodes labelled `target` take the label of the nearest
  // source node (in rings of the adjacency; ties to the earlier source).
  template <class IsSource>
  void grow_into(Force_class target, const IsSource& is_source)
  {
    std::deque<std::size_t> queue;
    for(std::size_t v = 0; v < m_label.size(); ++v)
      if(is_source(m_label[v]))
        queue.push_back(v);
    while(!queue.empty())
    {
      const std::size_t v = queue.front();
      queue.pop_front();
      for(const typename Domain::Neighbor& nb : m_domain.neighbors(v))
        if(m_label[nb.node] == target)
        {
          m_label[nb.node] = m_label[v];
          queue.push_back(nb.node);
        }
    }
  }

  // The neighbour query and region type of CGAL's region growing: the
  // quotient adjacency, and "the same label as the node it is reached from".
  struct Neighbor_query
  {
    const Domain* domain;
    void operator()(std::size_t v, std::vector<std::size_t>& neighbors) const
    {
      for(const typename Domain::Neighbor& nb : domain->neighbors(v))
        neighbors.push_back(nb.node);
    }
  };
  struct Same_label
  {
    const std::vector<Force_class>* label;
    bool is_part_of_region(std::size_t query, std::size_t neighbor, const std::vector<std::size_t>&) const
    {
      return (*label)[query] == (*label)[neighbor];
    }
    bool is_valid_region(const std::vector<std::size_t>&) const { return true; }
    void update(const std::vector<std::size_t>&) {}
  };

  void segment()
  {
    std::vector<std::size_t> items(m_domain.number_of_nodes());
    std::iota(items.begin(), items.end(), std::size_t(0));
    Neighbor_query query{&m_domain};
    Same_label same{&m_label};
    CGAL::Shape_detection::Region_growing<std::vector<std::size_t>, Neighbor_query, Same_label> growing(items, query,
                                                                                                        same);
    std::vector<std::vector<std::size_t>> found;
    growing.detect(std::back_inserter(found));
    m_region_of.assign(items.size(), 0);
    m_regions.clear();
    for(std::vector<std::size_t>& nodes : found)
    {
      std::sort(nodes.begin(), nodes.end());
      Region r;
      const Force_class c = m_label[nodes.front()];
      r.sign = (c == Force_class::Outward) ? 1 : (c == Force_class::Inward) ? -1 : 0;
      for(std::size_t v : nodes)
        m_region_of[v] = m_regions.size();
      r.nodes = std::move(nodes);
      m_regions.push_back(std::move(r));
    }
  }

  // A(v): a third of each canonical face around v, shared among the face's
  // corners on the surface.
  void compute_node_areas()
  {
    m_area.assign(m_domain.number_of_nodes(), 0.);
    const auto& pieces = m_domain.pieces().pieces();
    const auto& shape = m_domain.shape();
    for(std::size_t k = 0; k < pieces.size(); ++k)
    {
      const auto& chart_mesh = pieces[k].mesh;
      const auto& mesh = chart_mesh.mesh();
      const auto& primitive = shape.component(pieces[k].component).shape();
      for(auto f : mesh.faces())
      {
        const auto corners = chart_mesh.face_vertices(f);
        std::array<std::size_t, 3> nodes;
        std::size_t on_surface = 0;
        for(std::size_t c = 0; c < 3; ++c)
          on_surface += (nodes[c] = m_domain.node_of(k, corners[c])) != Domain::no_node;
        if(on_surface == 0)
          continue;
        const Chart_point centre =
          primitive.canonical_chart_point(chart_mesh.chart_point(f, {{1. / 3., 1. / 3., 1. / 3.}}));
        const std::optional<Shape_point> canonical = shape.canonical_point(Shape_point(pieces[k].component, centre));
        if(!canonical || m_domain.piece_of(*canonical) != k)
          continue; // off the surface, or counted in another chart
        const Eigen::Vector3d p0 = internal::to_eigen(mesh.point(corners[0]));
        const Eigen::Vector3d p1 = internal::to_eigen(mesh.point(corners[1]));
        const Eigen::Vector3d p2 = internal::to_eigen(mesh.point(corners[2]));
        const double share = 0.5 * (p1 - p0).cross(p2 - p0).norm() / double(on_surface);
        for(std::size_t c = 0; c < 3; ++c)
          if(nodes[c] != Domain::no_node)
            m_area[nodes[c]] += share;
      }
    }
  }

  void compute_fluxes()
  {
    for(Region& r : m_regions)
      for(std::size_t v : r.nodes)
      {
        r.flux += m_area[v] * m_force[v];
        r.area += m_area[v];
        if(m_class[v] != Force_class::Untouched)
          r.covered_area += m_area[v];
      }
  }

  // The edges between regions, by pair of regions, cut into connected curves.
  void find_boundaries()
  {
    std::map<std::pair<std::size_t, std::size_t>, std::vector<std::array<std::size_t, 2>>> crossing;
    for(std::size_t v = 0; v < m_domain.number_of_nodes(); ++v)
      for(const typename Domain::Neighbor& nb : m_domain.neighbors(v))
      {
        const std::size_t a = m_region_of[v], b = m_region_of[nb.node];
        if(v < nb.node && a != b)
        {
          const bool outward_first = m_regions[a].sign >= m_regions[b].sign;
          crossing[outward_first ? std::make_pair(a, b) : std::make_pair(b, a)].push_back(
            outward_first ? std::array<std::size_t, 2>{{v, nb.node}} : std::array<std::size_t, 2>{{nb.node, v}});
        }
      }
    m_boundaries.clear();
    for(const auto& pair_edges : crossing)
      for(std::vector<std::array<std::size_t, 2>>& curve : connected_curves(pair_edges.second))
        m_boundaries.push_back(make_boundary(pair_edges.first, std::move(curve)));
    std::stable_sort(m_boundaries.begin(), m_boundaries.end(), [](const Boundary& a, const Boundary& b) {
      return a.flux_difference > b.flux_difference;
    });
  }

  // Edges sharing a node are in one curve (union-find over the edges).
  static std::vector<std::vector<std::array<std::size_t, 2>>>
  connected_curves(const std::vector<std::array<std::size_t, 2>>& edges)
  {
    std::vector<std::size_t> parent(edges.size());
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    auto root = [&](std::size_t e) {
      while(parent[e] != e)
        e = parent[e] = parent[parent[e]];
      return e;
    };
    std::map<std::size_t, std::size_t> edge_at_node;
    for(std::size_t e = 0; e < edges.size(); ++e)
      for(std::size_t v : edges[e])
      {
        const auto it = edge_at_node.emplace(v, e).first;
        const std::size_t a = root(it->second), b = root(e);
        parent[(std::max)(a, b)] = (std::min)(a, b);
      }
    std::map<std::size_t, std::vector<std::array<std::size_t, 2>>> curves; // by smallest edge
    for(std::size_t e = 0; e < edges.size(); ++e)
      curves[root(e)].push_back(edges[e]);
    std::vector<std::vector<std::array<std::size_t, 2>>> result;
    for(auto& c : curves)
      result.push_back(std::move(c.second));
    return result;
  }

  Boundary make_boundary(const std::pair<std::size_t, std::size_t>& regions,
                         std::vector<std::array<std::size_t, 2>>&& edges) const
  {
    Boundary b;
    b.regions = {{regions.first, regions.second}};
    b.flux_difference = std::abs(m_regions[regions.first].flux - m_regions[regions.second].flux);
    std::map<std::size_t, std::size_t> nodes_in_piece;
    for(const std::array<std::size_t, 2>& e : edges)
      for(std::size_t v : e)
      {
        const typename Domain::Node& node = m_domain.node(v);
        b.centroid += 0.5 * internal::to_eigen(node.position);
        ++nodes_in_piece[m_domain.piece_of(node.canonical)];
      }
    b.centroid /= double(edges.size());
    b.piece = std::max_element(nodes_in_piece.begin(), nodes_in_piece.end(), [](const auto& x, const auto& y) {
                return x.second < y.second;
              })->first;
    b.edges = std::move(edges);
    return b;
  }

  const Domain& m_domain;
  double m_threshold_factor;
  double m_noise = 0.;
  std::vector<Node_weights> m_force_weights;             // per force
  std::vector<double> m_weight, m_weighted_sum, m_squared_weight; // per node: sum b w, sum b w d, sum (b w)^2
  std::vector<double> m_force, m_threshold, m_area;      // per node: F, eps_F, A
  std::vector<Force_class> m_class, m_label;             // per node: Fig. 16 a, and c
  std::vector<std::size_t> m_region_of;                  // per node
  std::vector<Region> m_regions;
  std::vector<Boundary> m_boundaries;
};

/// \ingroup PkgBlendedShapeEvolution
/// The normal forces of a fitter's data forces (Deformable_model_fitter::forces())
/// on a Deformable_blended_model: points of the blended shape's domain, ready
/// for Force_regions. With `weighted`, each with the fit's weight of its
/// point; otherwise all with weight 1, so that points a robust fit takes for
/// strays (a part that the model cannot reach yet) pull too.
template <class Fitter>
std::vector<Normal_force> normal_forces(Fitter& fitter, bool weighted = true)
{
  std::vector<Normal_force> result;
  const auto forces = fitter.forces();
  result.reserve(forces.size());
  for(const auto& f : forces)
    result.push_back(
      Normal_force{fitter.model().shape_point(f.chart_point), f.normal_distance, weighted ? f.weight : 1.});
  return result;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_EVOLUTION_FORCE_REGIONS_H
