// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_CHART_MESH_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_CHART_MESH_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>

#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeCharts

The tessellation of one chart domain: a `CGAL::Surface_mesh` whose vertices
carry their chart coordinates (property `"v:chart_point"`) and whose points are
positions in space, set from any map of chart points (set_positions()).

The connectivity is made once; only the positions change while a model
deforms. Each face knows its chart, so a point on a face (barycentric
coordinates) maps back to a chart point (chart_point(face, ...)), which is how
closest points found on the mesh are turned into exact domain points.

- Disk charts follow a subdivided octahedron (paper Fig. 30): ring `j` of
  `4 j` vertices at radius `j / resolution` up to radius 1, then margin rings
  up to the domain radius; the triangles are near-equilateral everywhere,
  also at the centre (the pole), where a latitude-longitude grid would have
  slivers. Euler characteristic 1.
- Torus charts are a `4 resolution` x `max(3, 2 resolution)` periodic grid, closed
  (Euler characteristic 0); chart coordinates of a face are unwrapped across
  the seams when interpolated.
- Tube charts are a grid of `4 resolution` columns, periodic in `x`, and rows
  `1 / resolution` apart in `y` (rounded up to a whole number of rows on
  each side of 0), with rows exactly at `y = y_min`, `y = y_max` and, if
  `y_min < 0 < y_max`, `y = 0`. When `y_min` and `y_max` are multiples of
  `1 / resolution` (e.g. the hole's `[-1, 1]`) the rows are `1 / resolution`
  apart and each triangle has the mean chart area `pi / (4 resolution^2)` of
  a disk triangle; the rows `y = +-j / resolution` of the hole's tube are then
  the rings of its two disk charts at the same resolution. The mesh
  is an annulus: two boundary loops (`y = y_min` and `y = y_max`), Euler
  characteristic 0; chart coordinates of a face are unwrapped across the seam
  in `x` only.

All triangles are counterclockwise in the chart coordinates `(x, y)`.
*/
template <class GeomTraits>
class Chart_mesh
{
public:
  typedef GeomTraits Geom_traits;                 ///< the kernel
  typedef typename Geom_traits::Point_3 Point_3;  ///< the point type of the mesh
  typedef CGAL::Surface_mesh<Point_3> Mesh;      ///< the tessellation
  typedef typename Mesh::Vertex_index vertex_descriptor; ///< a vertex of the mesh
  typedef typename Mesh::Face_index face_descriptor;     ///< a face of the mesh
  typedef std::array<double, 2> Chart_coordinates;       ///< the chart coordinates (x, y) of a vertex
  /// The vertex property map of the chart coordinates (property `"v:chart_point"`).
  typedef typename Mesh::template Property_map<vertex_descriptor, Chart_coordinates> Chart_coordinate_map;

  /// Tessellates the domain `domain` of chart `chart_index` with `resolution`
  /// rings (disk) or `4 resolution` columns (torus, tube). The vertex positions are
  /// the chart points themselves, `(x, y, 0)`, until set_positions() is called.
  /// \throws std::invalid_argument if `resolution` is not in [1, 4096], the
  ///         radius of a disk domain is not positive, or the `y` range of a
  ///         tube domain is not finite and non-empty (`y_min < y_max`).
  Chart_mesh(std::size_t chart_index, const Chart_domain& domain, int resolution)
    : m_chart(chart_index), m_domain(domain)
  {
    if(resolution < 1 || resolution > 4096)
    {
      std::ostringstream msg;
      msg << "Chart_mesh: resolution " << resolution << " is not in [1, 4096]";
      throw std::invalid_argument(msg.str());
    }
    m_uv = m_mesh.template add_property_map<vertex_descriptor, Chart_coordinates>(
             "v:chart_point", Chart_coordinates{{0., 0.}}).first;
    switch(domain.kind)
    {
    case Chart_kind::Disk: build_disk(resolution); break;
    case Chart_kind::Torus: build_torus(resolution); break;
    case Chart_kind::Tube: build_tube(resolution); break;
    default: throw std::invalid_argument("Chart_mesh: unknown chart kind");
    }
  }

  // The chart-coordinate map is a handle into the mesh's own property
  // storage: copies and moves must fetch it again from the new mesh.
  /// Copy constructor: the copy has its own mesh and chart-coordinate map.
  Chart_mesh(const Chart_mesh& other)
    : m_chart(other.m_chart), m_domain(other.m_domain), m_mesh(other.m_mesh)
  { attach_chart_coordinates(); }
  /// Move constructor.
  Chart_mesh(Chart_mesh&& other) noexcept
    : m_chart(other.m_chart), m_domain(other.m_domain), m_mesh(std::move(other.m_mesh))
  { attach_chart_coordinates(); }
  /// Assignment (copy or move).
  Chart_mesh& operator=(Chart_mesh other) noexcept
  {
    m_chart = other.m_chart;
    m_domain = other.m_domain;
    m_mesh = std::move(other.m_mesh);
    attach_chart_coordinates();
    return *this;
  }

  /// The mesh, with the current positions.
  const Mesh& mesh() const { return m_mesh; }
  /// The index of the chart this mesh tessellates.
  std::size_t chart_index() const { return m_chart; }
  /// The chart domain.
  const Chart_domain& domain() const { return m_domain; }
  /// The chart coordinates of the vertices.
  Chart_coordinate_map chart_coordinate_map() const { return m_uv; }

  /// The chart point of vertex `v`.
  Chart_point chart_point(vertex_descriptor v) const
  {
    const Chart_coordinates& c = m_uv[v];
    return Chart_point(m_chart, c[0], c[1]);
  }

  /// The three vertices of `f` in the order barycentric coordinates refer to:
  /// source, target and next target of `halfedge(f)` (the order of
  /// `CGAL::Polygon_mesh_processing::Face_location`).
  std::array<vertex_descriptor, 3> face_vertices(face_descriptor f) const
  {
    const auto h = m_mesh.halfedge(f);
    return {{m_mesh.source(h), m_mesh.target(h), m_mesh.target(m_mesh.next(h))}};
  }

  /// The chart point at barycentric coordinates `b` of face `f`, interpolated
  /// from the corners' chart coordinates unwrapped across the periodic seams
  /// (face_chart_coordinates()): on a face across a seam, a periodic
  /// coordinate may come out slightly outside `[0, 2 pi)`, which is the same
  /// point of the domain (use the primitive's canonical_chart_point() to reduce it).
  Chart_point chart_point(face_descriptor f, const std::array<double, 3>& b) const
  {
    const std::array<vertex_descriptor, 3> v = face_vertices(f);
    std::array<Chart_coordinates, 3> c = {{m_uv[v[0]], m_uv[v[1]], m_uv[v[2]]}};
    unwrap(c);
    return Chart_point(m_chart,
                       b[0] * c[0][0] + b[1] * c[1][0] + b[2] * c[2][0],
                       b[0] * c[0][1] + b[1] * c[1][1] + b[2] * c[2][1]);
  }

  /// Chart coordinates of the corners of `f`, unwrapped across periodic
  /// seams (both coordinates of a torus, `x` of a tube) so that the triangle
  /// is a genuine planar triangle.
  std::array<Chart_coordinates, 3> face_chart_coordinates(face_descriptor f) const
  {
    const std::array<vertex_descriptor, 3> v = face_vertices(f);
    std::array<Chart_coordinates, 3> c = {{m_uv[v[0]], m_uv[v[1]], m_uv[v[2]]}};
    unwrap(c);
    return c;
  }

  /// Sets every vertex position to `map(chart_point(v))`.
  template <class PointMapFunction>
  void set_positions(const PointMapFunction& map)
  {
    for(vertex_descriptor v : m_mesh.vertices())
      m_mesh.point(v) = map(chart_point(v));
  }

private:
  void attach_chart_coordinates()
  {
    m_uv = m_mesh.template property_map<vertex_descriptor, Chart_coordinates>("v:chart_point").first;
  }

  // Brings corners 1 and 2 within half a period of corner 0, in each
  // periodic coordinate only (a tube's y is a real boundary, not a seam).
  void unwrap(std::array<Chart_coordinates, 3>& c) const
  {
    const double periods[2] = {m_domain.x_period(), m_domain.y_period()};
    for(int i = 1; i < 3; ++i)
      for(int k = 0; k < 2; ++k)
      {
        const double period = periods[k];
        if(period == 0.)
          continue;
        const double d = c[i][k] - c[0][k];
        if(d > 0.5 * period) c[i][k] -= period;
        else if(d < -0.5 * period) c[i][k] += period;
      }
  }

  vertex_descriptor add_vertex(double x, double y)
  {
    const vertex_descriptor v = m_mesh.add_vertex(Point_3(x, y, 0.));
    m_uv[v] = Chart_coordinates{{x, y}};
    return v;
  }

  void add_face(vertex_descriptor a, vertex_descriptor b, vertex_descriptor c)
  {
    if(m_mesh.add_face(a, b, c) == Mesh::null_face())
      throw std::logic_error("Chart_mesh: internal tessellation error (non-manifold face)");
  }

  // Subdivided octahedron seen from its pole: ring j has 4j vertices at
  // equal angles; between rings j-1 and j each of the 4 sectors holds j
  // "outward" and j-1 "inward" triangles (4 (2j - 1) per ring, 4 n^2 up to ring n).
  void build_disk(int n)
  {
    const double R = m_domain.radius;
    if(!(R > 0.))
      throw std::invalid_argument("Chart_mesh: disk radius must be positive");
    std::vector<double> radii(1, 0.);
    const double inner = (std::min)(R, 1.);
    for(int j = 1; j <= n; ++j)
      radii.push_back(inner * double(j) / n);
    if(R > 1.)
    {
      const int margin_rings = (std::max)(1, int(std::ceil((R - 1.) * n)));
      for(int j = 1; j <= margin_rings; ++j)
        radii.push_back(1. + (R - 1.) * double(j) / margin_rings);
    }
    std::vector<std::vector<vertex_descriptor>> rings;
    rings.push_back({add_vertex(0., 0.)});
    for(std::size_t j = 1; j < radii.size(); ++j)
    {
      std::vector<vertex_descriptor> ring;
      const std::size_t count = 4 * j;
      for(std::size_t k = 0; k < count; ++k)
      {
        const double a = 2. * M_PI * double(k) / double(count);
        ring.push_back(add_vertex(radii[j] * std::cos(a), radii[j] * std::sin(a)));
      }
      rings.push_back(std::move(ring));
    }
    for(std::size_t j = 1; j < rings.size(); ++j)
    {
      const std::vector<vertex_descriptor>& in = rings[j - 1];
      const std::vector<vertex_descriptor>& out = rings[j];
      auto outer = [&](std::size_t s, std::size_t i) { return out[(s * j + i) % out.size()]; };
      auto inner_v = [&](std::size_t s, std::size_t i) {
        return (j == 1) ? in[0] : in[(s * (j - 1) + i) % in.size()];
      };
      for(std::size_t s = 0; s < 4; ++s)
      {
        for(std::size_t i = 0; i < j; ++i)
          add_face(outer(s, i), outer(s, i + 1), inner_v(s, i));
        for(std::size_t i = 0; i + 1 < j; ++i)
          add_face(inner_v(s, i), outer(s, i + 1), inner_v(s, i + 1));
      }
    }
  }

  void build_torus(int n)
  {
    // at least 3 rows, or the two vertical edges of a column would coincide
    const std::size_t nx = 4 * std::size_t(n), ny = (std::max)(std::size_t(3), 2 * std::size_t(n));
    const double period = m_domain.period();
    std::vector<vertex_descriptor> grid(nx * ny);
    for(std::size_t j = 0; j < ny; ++j)
      for(std::size_t i = 0; i < nx; ++i)
        grid[j * nx + i] = add_vertex(period * double(i) / nx, period * double(j) / ny);
    auto at = [&](std::size_t i, std::size_t j) { return grid[(j % ny) * nx + (i % nx)]; };
    for(std::size_t j = 0; j < ny; ++j)
      for(std::size_t i = 0; i < nx; ++i)
      {
        add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
  }

  // The rows of a tube: uniform steps of at most 1/n on each side of 0, with
  // y_min, 0 (when strictly inside) and y_max exactly; periodic in x like
  // the torus, with 4n columns; two triangles per cell, counterclockwise.
  void build_tube(int n)
  {
    const double y0 = m_domain.y_min, y1 = m_domain.y_max;
    if(!(std::isfinite(y0) && std::isfinite(y1) && y0 < y1))
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "Chart_mesh: tube domain y range [" << y0 << ", " << y1 << "] is not finite and non-empty";
      throw std::invalid_argument(msg.str());
    }
    // rows over [a, b]: ceil((b - a) n) uniform steps (the small tolerance
    // keeps ranges that are whole multiples of 1/n from gaining a row)
    std::vector<double> rows;
    auto add_rows = [&](double a, double b, bool first) {
      const int steps = (std::max)(1, int(std::ceil((b - a) * n * (1. - 1e-12))));
      for(int k = first ? 0 : 1; k <= steps; ++k)
        rows.push_back(k == steps ? b : a + (b - a) * double(k) / steps);
    };
    if(y0 < 0. && 0. < y1)
    {
      add_rows(y0, 0., true);
      add_rows(0., y1, false);
    }
    else
      add_rows(y0, y1, true);
    const std::size_t nx = 4 * std::size_t(n), ny = rows.size();
    const double period = m_domain.x_period();
    std::vector<vertex_descriptor> grid(nx * ny);
    for(std::size_t j = 0; j < ny; ++j)
      for(std::size_t i = 0; i < nx; ++i)
        grid[j * nx + i] = add_vertex(period * double(i) / nx, rows[j]);
    auto at = [&](std::size_t i, std::size_t j) { return grid[j * nx + (i % nx)]; };
    for(std::size_t j = 0; j + 1 < ny; ++j)
      for(std::size_t i = 0; i < nx; ++i)
      {
        add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
  }

  std::size_t m_chart;
  Chart_domain m_domain;
  Mesh m_mesh;
  Chart_coordinate_map m_uv;
};

/// \ingroup PkgBlendedShapeCharts
/// One Chart_mesh per chart of `primitive`, positioned by the primitive.
template <class Primitive>
std::vector<Chart_mesh<typename Primitive::Geom_traits>>
make_chart_meshes(const Primitive& primitive, int resolution)
{
  std::vector<Chart_mesh<typename Primitive::Geom_traits>> meshes;
  for(std::size_t c = 0; c < primitive.number_of_charts(); ++c)
  {
    meshes.emplace_back(c, primitive.chart_domain(c), resolution);
    meshes.back().set_positions([&](const Chart_point& p) { return primitive.point(p); });
  }
  return meshes;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_CHART_MESH_H
