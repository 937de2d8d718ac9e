// A tiny user program built against the installed package: the pole of the
// upper chart of an ellipsoid with semi-axes (1, 2, 3) is the point (0, 0, 3).
#include <CGAL/Blended_shape/Primitives.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <iostream>

int main()
{
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  const CGAL::Blended_shapes::Superquadric_ellipsoid<Kernel> ellipsoid(1., 2., 3.);
  const Kernel::Point_3 pole = ellipsoid.point(CGAL::Blended_shapes::Chart_point(0, 0., 0.));
  std::cout << "pole of the upper chart: " << pole << '\n';
  const bool ok = std::abs(pole.x()) < 1e-12 && std::abs(pole.y()) < 1e-12 &&
                  std::abs(pole.z() - 3.) < 1e-12;
  return ok ? 0 : 1;
}
