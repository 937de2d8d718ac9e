// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_BLENDING_BLENDED_SHAPE_MESH_H
#define CGAL_BLENDED_SHAPE_BLENDING_BLENDED_SHAPE_MESH_H

#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>

#include <CGAL/IO/Color.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeBlending

The overlapping per-component meshes of sec. 3.3: every chart of every
component tessellated once (`Chart_mesh`), positioned by the blended map,
with the faces wholly in a discarded part of the domain marked as not
retained. Faces in strips and in the charts' overlap margins stay on both
sides, so pieces overlap in space; a point on any face maps back to a
domain point through `Chart_mesh::chart_point()`. update() recomputes the
positions and the classification after the parameters or the regions moved.
*/
template <class GeomTraits>
class Blended_shape_pieces
{
public:
  typedef Blended_shape<GeomTraits> Shape;            ///< the blended shape
  typedef Chart_mesh<GeomTraits> Piece_mesh;          ///< one chart's mesh
  typedef typename Piece_mesh::face_descriptor face_descriptor; ///< a face of a piece

  /// One piece: a chart of a component.
  struct Piece
  {
    std::size_t component;      ///< the component
    Piece_mesh mesh;            ///< its chart mesh, positioned
    std::vector<bool> retained; ///< per face index: whether the face is kept (not wholly discarded)
  };

  /// Where a point of the shape's own frame goes (e.g. the pose of a fitted model).
  typedef std::function<typename GeomTraits::Point_3(const typename GeomTraits::Point_3&)> Placement;

  /// Tessellates every chart of every component at `resolution` and
  /// positions the pieces: at the shape's points, or, with `placement`, at
  /// their images (as for the pieces of a `Deformable_blended_model`, whose
  /// shape is placed by its pose).
  Blended_shape_pieces(const Shape& shape, int resolution, Placement placement = Placement())
    : m_resolution(resolution), m_placement(std::move(placement))
  {
    update(shape);
  }

  /// Recomputes positions and classification; re-tessellates if the structure changed.
  void update(const Shape& shape)
  {
    bool same = m_pieces.size() > 0;
    std::size_t k = 0;
    for(std::size_t c = 0; c < shape.number_of_components() && same; ++c)
      for(std::size_t ch = 0; ch < shape.component(c).shape().number_of_charts() && same; ++ch, ++k)
        same = k < m_pieces.size() && m_pieces[k].component == c && m_pieces[k].mesh.chart_index() == ch &&
               m_pieces[k].mesh.domain().kind == shape.component(c).shape().chart_domain(ch).kind;
    if(!same || k != m_pieces.size())
    {
      m_pieces.clear();
      for(std::size_t c = 0; c < shape.number_of_components(); ++c)
        for(std::size_t ch = 0; ch < shape.component(c).shape().number_of_charts(); ++ch)
          m_pieces.push_back(Piece{c, Piece_mesh(ch, shape.component(c).shape().chart_domain(ch), m_resolution), {}});
    }
    for(Piece& p : m_pieces)
    {
      const auto& m = p.mesh.mesh();
      std::vector<bool> on(m.number_of_vertices());
      for(auto v : m.vertices())
        on[std::size_t(v)] = shape.is_on_surface(Shape_point(p.component, p.mesh.chart_point(v)));
      p.mesh.set_positions([&](const Chart_point& u) {
        const auto x = shape.point(Shape_point(p.component, u));
        return m_placement ? m_placement(x) : x;
      });
      p.retained.assign(m.number_of_faces(), false);
      for(auto f : m.faces())
      {
        bool any = false;
        for(auto v : p.mesh.face_vertices(f))
          any = any || on[std::size_t(v)];
        p.retained[std::size_t(f)] = any;
      }
    }
  }

  /// The pieces.
  const std::vector<Piece>& pieces() const { return m_pieces; }

  /// All retained faces as one (non-manifold, overlapping) mesh with the
  /// face property `"f:color"` coloring each face by its component, and
  /// `"f:component"`.
  CGAL::Surface_mesh<typename GeomTraits::Point_3> merged_mesh() const
  {
    typedef CGAL::Surface_mesh<typename GeomTraits::Point_3> Mesh;
    Mesh out;
    auto color = out.template add_property_map<typename Mesh::Face_index, CGAL::IO::Color>("f:color").first;
    auto comp = out.template add_property_map<typename Mesh::Face_index, int>("f:component").first;
    for(const Piece& p : m_pieces)
    {
      const auto& m = p.mesh.mesh();
      std::map<std::size_t, typename Mesh::Vertex_index> vmap;
      for(auto f : m.faces())
      {
        if(!p.retained[std::size_t(f)])
          continue;
        std::array<typename Mesh::Vertex_index, 3> vs;
        int k = 0;
        for(auto v : p.mesh.face_vertices(f))
        {
          auto it = vmap.find(std::size_t(v));
          if(it == vmap.end())
            it = vmap.emplace(std::size_t(v), out.add_vertex(m.point(v))).first;
          vs[std::size_t(k++)] = it->second;
        }
        const auto nf = out.add_face(vs[0], vs[1], vs[2]);
        if(nf == Mesh::null_face())
          continue;
        color[nf] = component_color(p.component);
        comp[nf] = int(p.component);
      }
    }
    return out;
  }

  /// A distinct color per component (golden-ratio hues).
  static CGAL::IO::Color component_color(std::size_t c)
  {
    const double h = std::fmod(0.08 + 0.618033988749895 * double(c), 1.) * 6.;
    const int i = int(h);
    const double f = h - i, s = 0.55, v = 0.95;
    const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r, g, b;
    switch(i % 6)
    {
    case 0: r = v; g = t; b = p; break;
    case 1: r = q; g = v; b = p; break;
    case 2: r = p; g = v; b = t; break;
    case 3: r = p; g = q; b = v; break;
    case 4: r = t; g = p; b = v; break;
    default: r = v; g = p; b = q; break;
    }
    return CGAL::IO::Color((unsigned char)(255 * r), (unsigned char)(255 * g), (unsigned char)(255 * b));
  }

private:
  int m_resolution;
  Placement m_placement; // empty: the shape's own frame
  std::vector<Piece> m_pieces;
};

namespace internal {

// A triangulated domain: vertices are domain points, triangles index them.
struct Domain_triangulation
{
  std::vector<Shape_point> vertices;
  std::vector<std::array<std::size_t, 3>> triangles;
};

// The closed sphere of a two-chart superquadric ellipsoid: a subdivided
// octahedron (App. B.1, Fig. 30), each vertex at its canonical chart point.
inline Domain_triangulation sphere_domain(std::size_t component, int n)
{
  Domain_triangulation d;
  std::map<std::array<int, 3>, std::size_t> index;
  auto vertex = [&](int i, int j, int k) {
    const std::array<int, 3> key = {{i, j, k}};
    auto it = index.find(key);
    if(it != index.end())
      return it->second;
    const Eigen::Vector3d p = Eigen::Vector3d(i, j, k).normalized();
    const double eta = std::atan2(p.z(), std::hypot(p.x(), p.y()));
    const double omega = (p.x() == 0. && p.y() == 0.) ? 0. : std::atan2(p.y(), p.x());
    Chart_point u;
    if(eta >= 0.)
    {
      const double rho = 1. - 2. * eta / M_PI;
      u = Chart_point(0, rho * std::cos(omega), rho * std::sin(omega));
    }
    else
    {
      const double rho = 1. + 2. * eta / M_PI;
      u = Chart_point(1, rho * std::cos(omega), -rho * std::sin(omega));
    }
    d.vertices.push_back(Shape_point(component, u));
    index.emplace(key, d.vertices.size() - 1);
    return d.vertices.size() - 1;
  };
  for(int sx : {-1, 1})
    for(int sy : {-1, 1})
      for(int sz : {-1, 1})
      {
        // Octant face with corners n ex, n ey, n ez (scaled by signs); outward when sx sy sz > 0.
        const bool flip = sx * sy * sz < 0;
        auto at = [&](int a, int b) { // a along x, b along y, the rest along z
          return vertex(sx * a, sy * b, sz * (n - a - b));
        };
        auto tri = [&](std::size_t p, std::size_t q, std::size_t r) {
          d.triangles.push_back(flip ? std::array<std::size_t, 3>{{p, r, q}} : std::array<std::size_t, 3>{{p, q, r}});
        };
        for(int a = 0; a < n; ++a)
          for(int b = 0; a + b < n; ++b)
          {
            tri(at(a, b), at(a + 1, b), at(a, b + 1));
            if(a + b + 1 < n)
              tri(at(a + 1, b), at(a + 1, b + 1), at(a, b + 1));
          }
      }
  return d;
}

// One chart mesh as a domain triangulation.
template <class GT>
Domain_triangulation chart_domain_triangulation(std::size_t component, const Chart_mesh<GT>& m)
{
  Domain_triangulation d;
  for(auto v : m.mesh().vertices())
  {
    CGAL_assertion(std::size_t(v) == d.vertices.size());
    d.vertices.push_back(Shape_point(component, m.chart_point(v)));
  }
  for(auto f : m.mesh().faces())
  {
    const auto vs = m.face_vertices(f);
    d.triangles.push_back({{std::size_t(vs[0]), std::size_t(vs[1]), std::size_t(vs[2])}});
  }
  return d;
}

// Cuts a triangulation along the zero level of `value` (linear on edges
// only for locating crossings: each crossing is then found exactly by
// `crossing`), keeping the part where value >= 0. Returns the new vertices on
// the cut. Vertices on a crossed edge are created once, so the result stays
// manifold.
inline std::vector<std::size_t> cut_domain(Domain_triangulation& d, const std::function<double(const Shape_point&)>& value,
                                           const std::function<Shape_point(const Shape_point&, const Shape_point&)>& crossing)
{
  // Vertices within rounding of the level are on the cut (mesh rows often
  // fall exactly on a strip edge): they join the loop instead of spawning
  // coincident crossing vertices.
  std::vector<double> f(d.vertices.size());
  for(std::size_t i = 0; i < d.vertices.size(); ++i)
  {
    f[i] = value(d.vertices[i]);
    if(std::abs(f[i]) < 1e-9)
      f[i] = 0.;
  }
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> cut_vertex;
  std::vector<std::size_t> loop;
  auto on_edge = [&](std::size_t a, std::size_t b) {
    const std::pair<std::size_t, std::size_t> key = (a < b) ? std::make_pair(a, b) : std::make_pair(b, a);
    auto it = cut_vertex.find(key);
    if(it != cut_vertex.end())
      return it->second;
    const std::size_t in = (f[key.first] > 0.) ? key.first : key.second; // from the kept end to the dropped one
    const std::size_t out = (in == key.first) ? key.second : key.first;
    d.vertices.push_back(crossing(d.vertices[in], d.vertices[out]));
    loop.push_back(d.vertices.size() - 1);
    cut_vertex.emplace(key, d.vertices.size() - 1);
    return d.vertices.size() - 1;
  };
  std::vector<bool> on_cut_used(d.vertices.size(), false);
  std::vector<std::array<std::size_t, 3>> kept;
  for(const std::array<std::size_t, 3>& t : d.triangles)
  {
    // Sutherland-Hodgman against f >= 0; at most four corners.
    std::vector<std::size_t> poly;
    int positive = 0;
    for(int k = 0; k < 3; ++k)
    {
      const std::size_t p = t[std::size_t(k)], q = t[std::size_t((k + 1) % 3)];
      if(f[p] >= 0.)
        poly.push_back(p);
      positive += (f[p] > 0.) ? 1 : 0;
      if(f[p] * f[q] < 0.)
        poly.push_back(on_edge(p, q));
    }
    if(positive == 0 || poly.size() < 3)
      continue; // dropped, or only an edge or a corner on the cut
    for(std::size_t k = 1; k + 1 < poly.size(); ++k)
      kept.push_back({{poly[0], poly[k], poly[k + 1]}});
    for(std::size_t v : poly)
      if(v < f.size() && f[v] == 0. && !on_cut_used[v])
      {
        on_cut_used[v] = true;
        loop.push_back(v);
      }
  }
  d.triangles = kept;
  return loop;
}

} // namespace internal

namespace internal {

// The steps of make_unified_mesh(), in order.

// Step 1: the closed domain triangulation of every component that is part
// of the surface (components added by gradual blends are not: the base's disk
// expresses them).
template <class GeomTraits>
std::vector<Domain_triangulation> component_domain_triangulations(const Blended_shape<GeomTraits>& shape,
                                                                  int resolution)
{
  typedef Blended_shape<GeomTraits> Shape;
  std::vector<bool> meshed(shape.number_of_components(), true);
  for(std::size_t b = 0; b < shape.number_of_blends(); ++b)
    if(shape.blend(b).is_gradual())
      meshed[shape.blend(b).added_component()] = false;
  std::vector<Domain_triangulation> domains(shape.number_of_components());
  for(std::size_t c = 0; c < shape.number_of_components(); ++c)
  {
    if(!meshed[c])
      continue;
    const Component_shape& s = shape.component(c).shape();
    if(s.template primitive<typename Shape::Ellipsoid>())
      domains[c] = sphere_domain(c, resolution);
    else if(s.number_of_charts() == 1)
      domains[c] = chart_domain_triangulation(c, Chart_mesh<GeomTraits>(0, s.chart_domain(0), resolution));
    else
      throw std::invalid_argument("make_unified_mesh: component " + std::to_string(c) + " (" + s.type_name() +
                                  ") has no closed domain triangulation");
  }
  return domains;
}

// The cut loop of one side of a blend: its component and the indices of the
// loop's vertices in that component's domain triangulation.
struct Cut_loop
{
  std::size_t component;
  std::vector<std::size_t> vertices;
};

template <class GeomTraits>
bool is_hole_tube(const Blended_shape<GeomTraits>& shape, std::size_t c)
{
  const auto* h = shape.component(c).shape().template primitive<typename Blended_shape<GeomTraits>::Hole>();
  return h && h->domain() == Hole_domain::Tube;
}

// Step 2, one side of blend `B` (0: the base, cut on d = 1; 1: the added
// component, cut on d_2 = 1): cuts its domain triangulation, crossings found
// by bisection in the region's chart, so each cut vertex has strip
// coordinates d = 1 to rounding; the part beyond is dropped.
template <class GeomTraits>
Cut_loop cut_blend_side(const Blended_shape<GeomTraits>& shape, const Blend& B, int side,
                        std::vector<Domain_triangulation>& domains)
{
  // The level of a cut: d - 1 in the strip, +1 / -3 beyond it on the kept / dropped side.
  auto level = [](Region_side rs, double d) {
    return rs == Region_side::Strip ? d - 1. : (rs == Region_side::Retained ? 1. : -3.);
  };
  const std::size_t c = side == 0 ? B.base_component() : B.added_component();
  const Component_shape& s = shape.component(c).shape();
  const bool tube = is_hole_tube(shape, c);
  const std::size_t chart = side == 0 ? B.base_region().chart() : B.added_side().chart(tube);
  auto value = [&](const Shape_point& p) -> double {
    Chart_point v;
    if(!s.to_chart(p.u, chart, v))
      return side == 0 ? 1. : -3.; // not in the region's chart: far outside the curve
    if(side == 0)
    {
      const Region_location loc = B.base_region().locate(Eigen::Vector2d(v.x, v.y));
      return level(loc.side, loc.coordinates.d);
    }
    const Added_side::Location loc = B.added_side().locate(v, tube, B.core_stretch());
    return level(loc.side, loc.d);
  };
  auto crossing = [&](const Shape_point& in, const Shape_point& out) {
    Chart_point a, z;
    if(!s.to_chart(in.u, chart, a) || !s.to_chart(out.u, chart, z))
      throw std::invalid_argument("make_unified_mesh: a cut edge leaves the region's chart; raise the resolution");
    if(tube && std::abs(z.x - a.x) > M_PI) // unwrap the periodic coordinate
      z.x += (z.x < a.x) ? 2. * M_PI : -2. * M_PI;
    double lo = 0., hi = 1.;
    for(int it = 0; it < 60; ++it)
    {
      const double mid = 0.5 * (lo + hi);
      const Shape_point m(c, Chart_point(chart, a.x + mid * (z.x - a.x), a.y + mid * (z.y - a.y)));
      (value(m) >= 0. ? lo : hi) = mid;
    }
    // the strip side of the bracket: the vertex has strip coordinates (d = 1 to rounding)
    Chart_point r(chart, a.x + hi * (z.x - a.x), a.y + hi * (z.y - a.y));
    return Shape_point(c, r);
  };
  return Cut_loop{c, cut_domain(domains[c], value, crossing)};
}

// A vertex of a row of a strip: its strip angle, its global index, and its
// position in the base region's chart (for orientation).
struct Strip_row_vertex
{
  double theta;
  std::size_t index;
  Eigen::Vector2d base_uv;
};

// The row of the cut loop of one side of blend `B`, from the loop's vertices.
template <class GeomTraits>
std::vector<Strip_row_vertex> cut_loop_row(const Blended_shape<GeomTraits>& shape, const Blend& B, std::size_t b,
                                           int side, const Cut_loop& L, const Domain_triangulation& domain,
                                           std::size_t offset)
{
  const Ellipse_blending_region& R = B.base_region();
  const Component_shape& s = shape.component(L.component).shape();
  const bool tube = is_hole_tube(shape, L.component);
  std::vector<Strip_row_vertex> row;
  for(std::size_t li : L.vertices)
  {
    const Shape_point& p = domain.vertices[li];
    Strip_row_vertex rv;
    rv.index = li + offset;
    Chart_point v;
    if(side == 0)
    {
      s.to_chart(p.u, R.chart(), v);
      std::optional<Strip_coordinates> sc = R.strip_coordinates(Eigen::Vector2d(v.x, v.y));
      if(!sc) // a mesh vertex on the strip edge, a rounding error outside: nudge it in
        sc = R.strip_coordinates(Eigen::Vector2d(v.x, v.y) + 1e-7 * (R.center() - Eigen::Vector2d(v.x, v.y)));
      if(!sc)
        throw std::logic_error("make_unified_mesh: a cut vertex is not in its strip");
      rv.theta = sc->theta;
      rv.base_uv = Eigen::Vector2d(v.x, v.y);
    }
    else
    {
      s.to_chart(p.u, B.added_side().chart(tube), v);
      rv.theta = B.added_side().locate(v, tube, B.core_stretch()).theta;
      rv.base_uv = R.strip_point(-1., rv.theta);
    }
    row.push_back(rv);
  }
  if(row.size() < 3)
    throw std::invalid_argument("make_unified_mesh: the cut of blend " + std::to_string(b) +
                                " has fewer than 3 vertices; raise the resolution");
  return row;
}

// Zips two consecutive rows of a strip by theta into triangles, each
// oriented counterclockwise in the base chart (charts are oriented:
// counterclockwise is outward).
inline void zip_strip_rows(const std::vector<Strip_row_vertex>& P, const std::vector<Strip_row_vertex>& Q,
                           std::vector<std::array<std::size_t, 3>>& triangles)
{
  const std::size_t p = P.size(), q = Q.size();
  auto theta = [](const std::vector<Strip_row_vertex>& r, std::size_t i) {
    return r[i % r.size()].theta + 2. * M_PI * double(i / r.size());
  };
  auto emit = [&](const Strip_row_vertex& x, const Strip_row_vertex& y, const Strip_row_vertex& z) {
    const Eigen::Vector2d e1 = y.base_uv - x.base_uv, e2 = z.base_uv - x.base_uv;
    if(e1.x() * e2.y() - e1.y() * e2.x() >= 0.)
      triangles.push_back({{x.index, y.index, z.index}});
    else
      triangles.push_back({{x.index, z.index, y.index}});
  };
  std::size_t i = 0, j = 0;
  while(i < p || j < q)
  {
    const bool advance_p = (j == q) || (i < p && theta(P, i + 1) <= theta(Q, j + 1));
    if(advance_p)
    {
      emit(P[i % p], P[(i + 1) % p], Q[j % q]);
      ++i;
    }
    else
    {
      emit(P[i % p], Q[(j + 1) % q], Q[j % q]);
      ++j;
    }
  }
}

// Step 3, one blend: the strip in its (d, theta) coordinates, rows of
// constant d between the two cut loops (the intermediate ones with as many
// points as the longer loop, appended to `vertices`), zipped by theta.
template <class GeomTraits>
void triangulate_strip(const Blended_shape<GeomTraits>& shape, std::size_t b, const std::array<Cut_loop, 2>& loops,
                       const std::vector<Domain_triangulation>& domains, const std::vector<std::size_t>& offset,
                       int strip_rows, std::vector<Shape_point>& vertices,
                       std::vector<std::array<std::size_t, 3>>& triangles)
{
  const Blend& B = shape.blend(b);
  const Ellipse_blending_region& R = B.base_region();
  std::vector<std::vector<Strip_row_vertex>> rows(std::size_t(strip_rows) + 1);
  for(int side = 0; side < 2; ++side)
  {
    const Cut_loop& L = loops[std::size_t(side)];
    rows[side == 0 ? 0 : std::size_t(strip_rows)] =
      cut_loop_row(shape, B, b, side, L, domains[L.component], offset[L.component]);
  }
  const std::size_t m = std::max(rows.front().size(), rows.back().size());
  for(int k = 1; k < strip_rows; ++k)
  {
    const double d = 1. - 2. * double(k) / strip_rows;
    for(std::size_t j = 0; j < m; ++j)
    {
      const double th = 2. * M_PI * double(j) / double(m);
      const Eigen::Vector2d v = R.strip_point(d, th);
      vertices.push_back(Shape_point(B.base_component(), Chart_point(R.chart(), v.x(), v.y())));
      rows[std::size_t(k)].push_back(Strip_row_vertex{th, vertices.size() - 1, v});
    }
  }
  for(auto& row : rows)
    std::sort(row.begin(), row.end(),
              [](const Strip_row_vertex& x, const Strip_row_vertex& y) { return x.theta < y.theta; });
  for(std::size_t k = 0; k + 1 < rows.size(); ++k)
    zip_strip_rows(rows[k], rows[k + 1], triangles);
}

// Step 4: the mesh of the triangles, with only the vertices they use,
// placed by the blended map.
template <class GeomTraits>
CGAL::Surface_mesh<typename GeomTraits::Point_3>
place_unified_mesh(const Blended_shape<GeomTraits>& shape, const std::vector<Shape_point>& vertices,
                   const std::vector<std::array<std::size_t, 3>>& triangles)
{
  typedef CGAL::Surface_mesh<typename GeomTraits::Point_3> Mesh;
  Mesh out;
  std::vector<typename Mesh::Vertex_index> vmap(vertices.size(), Mesh::null_vertex());
  for(const auto& t : triangles)
    for(std::size_t k : t)
      if(vmap[k] == Mesh::null_vertex())
        vmap[k] = out.add_vertex(shape.point(vertices[k]));
  for(const auto& t : triangles)
    if(out.add_face(vmap[t[0]], vmap[t[1]], vmap[t[2]]) == Mesh::null_face())
      throw std::invalid_argument("make_unified_mesh: the surgery produced a non-manifold mesh; raise the resolution");
  return out;
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeBlending

One closed, oriented, manifold triangle mesh of the whole blended shape,
made by domain surgery (DESIGN.md sec. 6):

1. every component that is part of the surface is triangulated over its
   whole domain: a superquadric ellipsoid as a subdivided octahedron whose
   vertices are canonical chart points of its two charts (the seam is inside
   the triangulation, not a cut), a single-chart primitive (toroid, hole
   tube) as its chart mesh. Components added by gradual blends are not: the
   base's disk expresses them (`Omega_2 = omega_2`, Fig. 7);
2. for every cut-and-glue blend, the base's triangulation is cut exactly on
   the strip edge `d = 1` and the added component's on `d_2 = 1` (crossings
   found by bisection in the region's chart, so each cut vertex has strip
   coordinates `d = 1` to rounding); the parts beyond are dropped;
3. each strip is triangulated in its `(d, theta)` coordinates: rows of
   constant `d` between the two cut loops, zipped by `theta`, so the strip
   shares the cut vertices of both sides;
4. every vertex is placed by the blended map at its domain point.

The Euler characteristic is `2 - 2 genus()` when the components are closed
surfaces. `resolution` is the number of subdivisions of an octant edge
(ellipsoids) or the chart mesh resolution; `strip_rows` the number of rows
across a strip.
\throws std::invalid_argument if a cut does not produce one closed loop
        (the resolution is too coarse for a region), or a component kind has
        no closed domain triangulation.
*/
template <class GeomTraits>
CGAL::Surface_mesh<typename GeomTraits::Point_3> make_unified_mesh(const Blended_shape<GeomTraits>& shape,
                                                                   int resolution = 24, int strip_rows = 4)
{
  if(resolution < 2 || resolution > 1024 || strip_rows < 1 || strip_rows > 256)
    throw std::invalid_argument("make_unified_mesh: resolution must be in [2, 1024] and strip_rows in [1, 256]");
  std::vector<internal::Domain_triangulation> domains = internal::component_domain_triangulations(shape, resolution);
  std::vector<std::array<internal::Cut_loop, 2>> loops(shape.number_of_blends());
  for(std::size_t b = 0; b < shape.number_of_blends(); ++b)
    if(!shape.blend(b).is_gradual())
      for(int side = 0; side < 2; ++side)
        loops[b][std::size_t(side)] = internal::cut_blend_side(shape, shape.blend(b), side, domains);

  // Global vertices: the components' triangulations, then the strip rows.
  std::vector<Shape_point> vertices;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::vector<std::size_t> offset(shape.number_of_components(), 0);
  for(std::size_t c = 0; c < shape.number_of_components(); ++c)
  {
    offset[c] = vertices.size();
    vertices.insert(vertices.end(), domains[c].vertices.begin(), domains[c].vertices.end());
    for(const auto& t : domains[c].triangles)
      triangles.push_back({{t[0] + offset[c], t[1] + offset[c], t[2] + offset[c]}});
  }
  for(std::size_t b = 0; b < shape.number_of_blends(); ++b)
    if(!shape.blend(b).is_gradual())
      internal::triangulate_strip(shape, b, loops[b], domains, offset, strip_rows, vertices, triangles);
  return internal::place_unified_mesh(shape, vertices, triangles);
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_BLENDING_BLENDED_SHAPE_MESH_H
