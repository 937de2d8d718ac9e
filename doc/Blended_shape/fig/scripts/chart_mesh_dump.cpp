// SPDX-License-Identifier: LGPL-3.0-or-later
// Figure helper (not part of the package build): prints the chart meshes of a
// superquadric ellipsoid, for make_figures.py.
//
//   chart_mesh_dump RESOLUTION A1 A2 A3 E1 E2
//
// Output, one record per line:
//   V chart x y X Y Z canonical_chart   a vertex: chart coordinates, position,
//                                       and the chart of its canonical chart point
//   F chart i j k                       a face (vertex indices within its chart,
//                                       counterclockwise in the chart plane)
#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>

#include <CGAL/Simple_cartesian.h>

#include <cstdlib>
#include <iostream>

int main(int argc, char** argv)
{
  namespace BS = CGAL::Blended_shapes;
  typedef CGAL::Simple_cartesian<double> K;
  if(argc != 7)
  {
    std::cerr << "usage: chart_mesh_dump RESOLUTION A1 A2 A3 E1 E2\n";
    return 2;
  }
  const int resolution = std::atoi(argv[1]);
  const BS::Superquadric_ellipsoid<K> shape(std::atof(argv[2]), std::atof(argv[3]), std::atof(argv[4]),
                                            std::atof(argv[5]), std::atof(argv[6]));
  const auto meshes = BS::make_chart_meshes(shape, resolution);
  std::cout.precision(10);
  for(const auto& cm : meshes)
  {
    for(auto v : cm.mesh().vertices())
    {
      const BS::Chart_point u = cm.chart_point(v);
      const K::Point_3 p = cm.mesh().point(v);
      std::cout << "V " << cm.chart_index() << ' ' << u.x << ' ' << u.y << ' ' << p.x() << ' ' << p.y() << ' '
                << p.z() << ' ' << shape.canonical_chart_point(u).chart << '\n';
    }
    for(auto f : cm.mesh().faces())
    {
      const auto v = cm.face_vertices(f);
      std::cout << "F " << cm.chart_index() << ' ' << std::size_t(v[0]) << ' ' << std::size_t(v[1]) << ' '
                << std::size_t(v[2]) << '\n';
    }
  }
  return 0;
}
