// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_SCANNING_CAD_PRIMITIVE_SOLIDS_H
#define CGAL_BLENDED_SHAPE_SCANNING_CAD_PRIMITIVE_SOLIDS_H

// The primitive solids of the CAD objects (CAD_objects.h) and the checks of
// their sizes, without the Boolean operations that join them: CGAL's
// corefinement is a large part of the compilation of a program that includes
// it, and a program that only needs a box or a cylinder does without it.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeScanning
/// The mesh type of the test objects: exact predicates make the Boolean
/// operations robust, and the points are plain doubles.
typedef Exact_predicates_inexact_constructions_kernel CAD_kernel;
/// \ingroup PkgBlendedShapeScanning
/// The mesh type of the test objects.
typedef Surface_mesh<CAD_kernel::Point_3> CAD_mesh;

/// \name Primitive solids
/// Closed triangle meshes with outward-facing triangles, inputs of the Booleans.
/// @{

/// \ingroup PkgBlendedShapeScanning
/// The axis-aligned box `[lo, hi]` (12 triangles).
/// \pre `lo` is below `hi` on every axis.
inline CAD_mesh make_box_mesh(const CAD_mesh::Point& lo, const CAD_mesh::Point& hi)
{
  CGAL_precondition(lo.x() < hi.x() && lo.y() < hi.y() && lo.z() < hi.z());
  CAD_mesh m;
  std::vector<CAD_mesh::Vertex_index> v;
  for(int i = 0; i < 8; ++i) // bit 0: x, bit 1: y, bit 2: z
    v.push_back(m.add_vertex(CAD_mesh::Point((i & 1) ? hi.x() : lo.x(),
                                             (i & 2) ? hi.y() : lo.y(),
                                             (i & 4) ? hi.z() : lo.z())));
  // Two triangles per side, counterclockwise seen from outside.
  const int tri[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                          {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  for(const auto& t : tri)
    m.add_face(v[t[0]], v[t[1]], v[t[2]]);
  return m;
}

/// \ingroup PkgBlendedShapeScanning
/// A cylinder with axis parallel to z: a prism over a regular `segments`-gon
/// inscribed in the circle of radius `radius` around `base`, from `base.z()`
/// to `base.z() + height`. The caps are fans around a centre vertex (no slivers).
/// Vertex `i` is at the angle `(i + turn) * 2 pi / segments`: the objects
/// below choose `turn` so that no vertex lines up with an edge of another
/// solid, which would leave almost coincident points after the Booleans.
/// \pre `radius > 0`, `height > 0`, `segments >= 3`.
inline CAD_mesh make_cylinder_mesh(const CAD_mesh::Point& base, double radius, double height,
                                   std::size_t segments, double turn = 0.)
{
  CGAL_precondition(radius > 0. && height > 0. && segments >= 3);
  CAD_mesh m;
  const double z0 = base.z(), z1 = base.z() + height;
  const auto bottom_center = m.add_vertex(CAD_mesh::Point(base.x(), base.y(), z0));
  const auto top_center = m.add_vertex(CAD_mesh::Point(base.x(), base.y(), z1));
  std::vector<CAD_mesh::Vertex_index> bottom, top;
  for(std::size_t i = 0; i < segments; ++i)
  {
    const double a = 2. * M_PI * (double(i) + turn) / double(segments);
    const double x = base.x() + radius * std::cos(a), y = base.y() + radius * std::sin(a);
    bottom.push_back(m.add_vertex(CAD_mesh::Point(x, y, z0)));
    top.push_back(m.add_vertex(CAD_mesh::Point(x, y, z1)));
  }
  for(std::size_t i = 0; i < segments; ++i)
  {
    const std::size_t j = (i + 1) % segments;
    m.add_face(bottom_center, bottom[j], bottom[i]);
    m.add_face(top_center, top[i], top[j]);
    m.add_face(bottom[i], bottom[j], top[j]);
    m.add_face(bottom[i], top[j], top[i]);
  }
  return m;
}

/// \ingroup PkgBlendedShapeScanning
/// A torus around `axis` through `center`: the tube of radius `tube_radius`
/// around the circle of radius `ring_radius`, with `ring_segments` x `tube_segments` quads.
/// \pre `0 < tube_radius < ring_radius`, `axis` not null, at least 3 segments each way.
inline CAD_mesh make_torus_mesh(const CAD_mesh::Point& center, const CAD_kernel::Vector_3& axis,
                                double ring_radius, double tube_radius,
                                std::size_t ring_segments, std::size_t tube_segments)
{
  typedef CAD_kernel::Vector_3 Vector;
  CGAL_precondition(tube_radius > 0. && tube_radius < ring_radius);
  CGAL_precondition(ring_segments >= 3 && tube_segments >= 3);
  const Vector a = axis / std::sqrt(axis.squared_length());
  // (u, v, a) right-handed, so that the (ring, tube) parameter order faces outward.
  const Vector helper = std::abs(a.x()) < 0.9 ? Vector(1, 0, 0) : Vector(0, 1, 0);
  Vector u = CGAL::cross_product(helper, a);
  u = u / std::sqrt(u.squared_length());
  const Vector v = CGAL::cross_product(a, u);

  CAD_mesh m;
  std::vector<CAD_mesh::Vertex_index> vid(ring_segments * tube_segments);
  for(std::size_t i = 0; i < ring_segments; ++i)
  {
    const double theta = 2. * M_PI * double(i) / double(ring_segments);
    const Vector radial = std::cos(theta) * u + std::sin(theta) * v;
    for(std::size_t j = 0; j < tube_segments; ++j)
    {
      const double phi = 2. * M_PI * double(j) / double(tube_segments);
      vid[i * tube_segments + j] = m.add_vertex(
        center + (ring_radius + tube_radius * std::cos(phi)) * radial + tube_radius * std::sin(phi) * a);
    }
  }
  for(std::size_t i = 0; i < ring_segments; ++i)
    for(std::size_t j = 0; j < tube_segments; ++j)
    {
      const std::size_t i1 = (i + 1) % ring_segments, j1 = (j + 1) % tube_segments;
      const auto p00 = vid[i * tube_segments + j], p10 = vid[i1 * tube_segments + j];
      const auto p11 = vid[i1 * tube_segments + j1], p01 = vid[i * tube_segments + j1];
      m.add_face(p00, p10, p11);
      m.add_face(p00, p11, p01);
    }
  return m;
}
/// @}

namespace internal {

// Turns of the cylinders (see make_cylinder_mesh()): never a multiple of 1/8
// of a segment, so no vertex sits on an axis or a box diagonal, and half a
// segment apart between nested cylinders (cup and cavity).
constexpr double outer_turn = 0.3;
constexpr double inner_turn = 0.8;

inline void require(bool ok, const std::string& who, const std::string& message)
{
  if(!ok)
    throw std::invalid_argument(who + ": " + message);
}

inline std::string to_string_g(double x)
{
  std::ostringstream s;
  s << x;
  return s.str();
}

// Finite, positive lengths within a factor 1000 of each other: beyond that the
// Booleans would produce slivers that no scan resolves.
inline void check_lengths(const std::string& who,
                          std::initializer_list<std::pair<const char*, double>> lengths)
{
  double largest = 0.;
  for(const auto& l : lengths)
  {
    require(std::isfinite(l.second) && l.second > 0., who,
            std::string(l.first) + " is " + to_string_g(l.second) + "; it must be a positive finite number");
    largest = (std::max)(largest, l.second);
  }
  for(const auto& l : lengths)
    require(l.second >= 1e-3 * largest, who,
            std::string(l.first) + " (" + to_string_g(l.second) + ") is less than 1/1000 of the largest size (" +
              to_string_g(largest) + "); use sizes of comparable magnitude");
}

inline void check_segments(const std::string& who, std::size_t segments)
{
  require(segments >= 8 && segments <= 1024, who,
          "segments is " + std::to_string(segments) +
            "; use between 8 and 1024 segments per circle (32 to 48 are usually enough)");
}

// The checks every CAD object starts with: its lengths, then its segments per circle.
inline void check_sizes(const std::string& who, std::size_t segments,
                        std::initializer_list<std::pair<const char*, double>> lengths)
{
  check_lengths(who, lengths);
  check_segments(who, segments);
}

} // namespace internal

/// \ingroup PkgBlendedShapeScanning
/// A box with a cylinder standing on its top (Fig. 19).
struct Box_cylinder_parameters
{
  double box_length = 2.;      ///< along x
  double box_width = 2.;       ///< along y
  double box_height = 1.;      ///< along z
  double cylinder_radius = 0.6; ///< radius of the cylinder
  double cylinder_height = 1.;  ///< height of the cylinder above the box top
  std::size_t segments = 48;   ///< per circle
};

namespace internal {

// The two solids whose union is make_box_cylinder(p), after its checks of
// `p`: the box, standing on z = 0, and the cylinder on its top centre, which
// starts a quarter of the box's height inside the box (touching faces would
// be coplanar in the union).
inline std::pair<CAD_mesh, CAD_mesh> box_cylinder_solids(const Box_cylinder_parameters& p, const std::string& who)
{
  check_sizes(who, p.segments, {{"box length", p.box_length}, {"box width", p.box_width},
                                {"box height", p.box_height}, {"cylinder radius", p.cylinder_radius},
                                {"cylinder height", p.cylinder_height}});
  const double fit = 0.45 * (std::min)(p.box_length, p.box_width);
  require(p.cylinder_radius <= fit, who,
          "cylinder radius " + to_string_g(p.cylinder_radius) +
            " does not fit on the box top (at most 0.45 x the smaller box side = " + to_string_g(fit) +
            "); use a thinner cylinder or a larger box");
  const double sink = 0.25 * p.box_height;
  return {make_box_mesh(CAD_mesh::Point(-0.5 * p.box_length, -0.5 * p.box_width, 0.),
                        CAD_mesh::Point(0.5 * p.box_length, 0.5 * p.box_width, p.box_height)),
          make_cylinder_mesh(CAD_mesh::Point(0., 0., p.box_height - sink), p.cylinder_radius,
                             p.cylinder_height + sink, p.segments, outer_turn)};
}

// The two solids of box_cylinder_solids() in one mesh, overlapping, not
// united: for a ray scan it stands in for make_box_cylinder() without
// compiling the corefinement, since every ray meets the same surface first
// and the bounding box (so the default camera) is the same (test_scanning
// checks both).
inline CAD_mesh box_cylinder_overlapping_solids(const Box_cylinder_parameters& p, const std::string& who)
{
  auto [box, cylinder] = box_cylinder_solids(p, who);
  box += cylinder;
  return box;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_SCANNING_CAD_PRIMITIVE_SOLIDS_H
