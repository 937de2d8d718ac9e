// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_IO_READ_TRIANGLE_MESH_H
#define CGAL_BLENDED_SHAPE_IO_READ_TRIANGLE_MESH_H

#include <CGAL/Blended_shape/IO/Input_error.h>
#include <CGAL/Blended_shape/IO/check_points.h>
#include <CGAL/Blended_shape/IO/read_points.h> // file checks, soup reading, welding

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// Removes the points no polygon uses, keeping the others in file order
// (PMP::remove_isolated_points_in_polygon_soup() reorders them).
template <class Point_3>
void remove_unreferenced_points(std::vector<Point_3>& points,
                                std::vector<std::vector<std::size_t> >& polygons)
{
  const std::size_t unused = std::size_t(-1);
  std::vector<std::size_t> new_index(points.size(), unused);
  for(const std::vector<std::size_t>& polygon : polygons)
    for(std::size_t v : polygon)
      new_index[v] = 0;
  std::size_t n = 0;
  for(std::size_t i = 0; i < points.size(); ++i)
    if(new_index[i] != unused)
    {
      new_index[i] = n;
      points[n++] = points[i];
    }
  points.resize(n);
  for(std::vector<std::size_t>& polygon : polygons)
    for(std::size_t& v : polygon)
      v = new_index[v];
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeIO

Reads a surface mesh from an `.off`, `.obj`, `.ply` or `.stl` file (letter
case of the extension does not matter) and makes it a valid triangle mesh:

1. the file is read as a polygon soup (`CGAL::IO::read_polygon_soup()`);
2. vertices with exactly equal coordinates are merged (an STL file repeats
   every vertex for each triangle), vertices used by no face are removed;
3. faces that then repeat a vertex, and repeated faces, are removed;
4. faces are oriented consistently (`CGAL::Polygon_mesh_processing::orient_polygon_soup()`,
   which duplicates the vertices where the surface is not manifold);
5. the soup becomes a mesh and polygonal faces are triangulated.

The orientation is consistent but not necessarily outward.

`mesh` is assigned only once everything succeeded; on error it is unchanged.

\tparam Mesh a model of `MutableFaceGraph` with an internal point property
        map, e.g. `CGAL::Surface_mesh<Point_3>`.

\throws Input_error with code
 - `File_not_found`, `Unreadable_file`, `Unsupported_format` (the message lists the extensions);
 - `Malformed_content`: the reader failed, a face uses a missing vertex, or
   the faces cannot form a valid polygon mesh; a PLY file is checked whole
   first, as read_points() does (its header, every element there, no list
   longer than the rest of the file);
 - `No_points`: the mesh has no faces (also after removing degenerate ones);
 - `Non_finite_point`: a vertex used by a face has a NaN or infinite coordinate.
*/
template <class Mesh>
void read_triangle_mesh(const std::string& filename, Mesh& mesh)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  typedef typename boost::property_map<Mesh, CGAL::vertex_point_t>::type Vertex_point_map;
  typedef typename boost::property_traits<Vertex_point_map>::value_type Point_3;
  typedef std::vector<std::size_t> Polygon;

  const std::string function = "read_triangle_mesh";
  const std::uintmax_t size = internal::check_readable_file(filename, function);
  const std::string format = internal::lower_case_extension(filename);
  if(format != "off" && format != "obj" && format != "ply" && format != "stl")
    throw Input_error(Input_error::Unsupported_format,
                      function + ": cannot read " + internal::quoted(filename) + ": " +
                      (format.empty() ? std::string("it has no extension")
                                      : "the extension '." + format + "' is not supported") +
                      "; supported extensions are .off, .obj, .ply, .stl; convert the mesh to "
                      "one of these formats");

  const std::string where = function + ": " + internal::quoted(filename);
  const std::string no_surface = "; there is no surface to fit, so check that the file holds "
                                 "a surface mesh and not only points";
  if(size == 0)
    throw Input_error(Input_error::No_points, where + " is empty: the mesh has no faces" + no_surface);

  std::vector<Point_3> points;
  std::vector<Polygon> polygons;
  internal::read_soup_or_throw(filename, format, points, polygons, function);
  if(polygons.empty())
    throw Input_error(Input_error::No_points, where + ": the mesh has no faces" + no_surface);

  // Only the vertices of faces matter; they must be finite before welding
  // (NaN does not compare) and before any geometry.
  for(const Polygon& polygon : polygons)
    for(std::size_t v : polygon)
      if(!internal::is_finite_point(points[v]))
        throw Input_error(Input_error::Non_finite_point,
                          where + ": vertex " + std::to_string(v) + " (counting from 0) has a "
                          "non-finite coordinate (" + internal::point_to_string(points[v]) +
                          "); repair or remove that vertex and its faces in a mesh editor");
  internal::remove_unreferenced_points(points, polygons);

  const std::vector<std::size_t> welded = internal::weld_exact_duplicates(points);
  std::vector<Polygon> kept;
  kept.reserve(polygons.size());
  for(Polygon& polygon : polygons)
  {
    for(std::size_t& v : polygon)
      v = welded[v];
    Polygon sorted = polygon;
    std::sort(sorted.begin(), sorted.end());
    const bool degenerate = sorted.size() < 3 ||
                            std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    if(!degenerate)
      kept.push_back(std::move(polygon));
  }
  if(kept.empty())
    throw Input_error(Input_error::No_points,
                      where + ": the mesh has no faces left after removing " +
                      internal::plural(polygons.size(), "degenerate face") +
                      " (each had fewer than three distinct vertices)" + no_surface);
  PMP::merge_duplicate_polygons_in_polygon_soup(points, kept);
  internal::remove_unreferenced_points(points, kept);

  PMP::orient_polygon_soup(points, kept);
  if(!PMP::is_polygon_soup_a_polygon_mesh(kept))
    throw Input_error(Input_error::Malformed_content,
                      where + ": the faces do not form a valid polygon mesh even after "
                      "orientation; repair the mesh (e.g. CGAL::Polygon_mesh_processing::"
                      "repair_polygon_soup) or export it again");

  Mesh result;
  PMP::polygon_soup_to_polygon_mesh(points, kept, result);
  if(!PMP::triangulate_faces(result))
    throw Input_error(Input_error::Malformed_content,
                      where + ": some polygonal faces cannot be triangulated (they are "
                      "degenerate); triangulate or repair the mesh in a mesh editor");
  if(!CGAL::is_valid_polygon_mesh(result))
    throw Input_error(Input_error::Malformed_content,
                      where + ": the faces do not form a valid polygon mesh; repair the mesh "
                      "in a mesh editor or export it again");
  mesh = std::move(result);
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_READ_TRIANGLE_MESH_H
