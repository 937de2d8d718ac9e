// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef BLENDED_SHAPE_TESTING_SCANNER_VIEWS_H
#define BLENDED_SHAPE_TESTING_SCANNER_VIEWS_H

#include <blended_shape_testing/synthetic_scans.h>

#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Fitting/Deformable_blended_model.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model_fitter.h>
#include <CGAL/Blended_shape/Scanning/Range_scan_simulator.h>

#include <CGAL/Surface_mesh.h>
#include <Eigen/Core>

#include <cmath>
#include <random>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace testing {

// A tessellation of `m` in place (the unified mesh of its shape, moved by its pose).
template <class K>
CGAL::Surface_mesh<typename K::Point_3> placed_mesh(const Deformable_model<Superquadric_ellipsoid<K>>& m)
{
  const auto blended = make_blended_model(m);
  CGAL::Surface_mesh<typename K::Point_3> mesh = make_unified_mesh(blended.shape(), 48);
  for(const auto v : mesh.vertices())
    mesh.point(v) = blended.placed(mesh.point(v));
  return mesh;
}

// A random superellipsoid (random_superellipsoid(), drawn with `seed`) and
// the range scan (simulate_range_scan(), 200x200 pixels, no noise) of its
// tessellation from a random direction: unlike synthetic_scan(), whose
// samples are spread evenly by area, dense where the surface faces the
// scanner and sparse where it is seen at a slant.
template <class K>
struct Scanner_view
{
  Deformable_model<Superquadric_ellipsoid<K>> truth;
  std::vector<typename K::Point_3> points;
};

template <class K>
Scanner_view<K> scanner_view(unsigned int seed)
{
  std::mt19937_64 rng(seed);
  Scanner_view<K> view{random_superellipsoid<K>(rng), {}};
  const auto mesh = placed_mesh(view.truth);
  Camera<K> camera = default_camera_for(mesh);
  std::normal_distribution<double> g(0., 1.);
  const Eigen::Vector3d d = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
  camera.eye = camera.target + std::sqrt(CGAL::squared_distance(camera.eye, camera.target)) *
                                 typename K::Vector_3(d[0], d[1], d[2]);
  camera.up = std::abs(d[2]) < 0.9 ? typename K::Vector_3(0., 0., 1.) : typename K::Vector_3(1., 0., 0.);
  for(const auto& sample : simulate_range_scan(mesh, camera))
    view.points.push_back(sample.point);
  return view;
}

// Whether `model` fits the points `pts` of a view of one superquadric: the
// RMS of their distances to it at most 0.5 % of their bounding-box
// diagonal, and at most 2 % of them farther than 1 % of it.
template <class K>
bool fits_view(const std::vector<typename K::Point_3>& pts, const Deformable_model<Superquadric_ellipsoid<K>>& model)
{
  const double diagonal = bounding_box_diagonal(pts);
  Deformable_model_fitter<Deformable_model<Superquadric_ellipsoid<K>>> probe(pts, model); // every point's distance
  double sum = 0.;
  std::size_t far = 0;
  for(const auto& f : probe.forces())
  {
    sum += CGAL::square(f.normal_distance);
    far += std::abs(f.normal_distance) > 0.01 * diagonal ? 1 : 0;
  }
  return std::sqrt(sum / double(pts.size())) <= 0.005 * diagonal && double(far) <= 0.02 * double(pts.size());
}

} // namespace testing
} // namespace Blended_shapes
} // namespace CGAL

#endif // BLENDED_SHAPE_TESTING_SCANNER_VIEWS_H
