// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef BLENDED_SHAPE_TESTING_SYNTHETIC_SCANS_H
#define BLENDED_SHAPE_TESTING_SYNTHETIC_SCANS_H

#include <CGAL/Blended_shape/Fitting/Deformable_model.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Fitting/sample_model.h>

#include <CGAL/Bbox_3.h>
#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace testing {

// Seeded synthetic data shared by the tests and the benchmarks.

// A random superellipsoid: a_i in [0.5, 2.5] pairwise at least 10 % apart
// (so that its axes are defined), exponents in [0.3, 1.7], random pose.
template <class K>
Deformable_model<Superquadric_ellipsoid<K>> random_superellipsoid(std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> size(0.5, 2.5), expo(0.3, 1.7), shift(-5., 5.);
  std::normal_distribution<double> g(0., 1.);
  std::array<double, 3> a;
  do { a = {{size(rng), size(rng), size(rng)}}; }
  while(std::abs(a[0] / a[1] - 1.) < 0.1 || std::abs(a[1] / a[2] - 1.) < 0.1 || std::abs(a[0] / a[2] - 1.) < 0.1);
  const Superquadric_ellipsoid<K> s(a[0], a[1], a[2], expo(rng), expo(rng));
  return Deformable_model<Superquadric_ellipsoid<K>>(s, Eigen::Vector3d(shift(rng), shift(rng), shift(rng)),
                                                     Eigen::Vector4d(g(rng), g(rng), g(rng), g(rng)));
}

template <class Point_3>
double bounding_box_diagonal(const std::vector<Point_3>& pts)
{
  CGAL::Bbox_3 b;
  for(const auto& p : pts) b += p.bbox();
  return std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                   CGAL::square(b.zmax() - b.zmin()));
}

// `n` surface samples of `model`: all around, or (single view) those facing
// an eye 10 model sizes away in a random direction; then isotropic Gaussian
// noise of `noise` times the bounding-box diagonal of the samples, whose
// standard deviation is returned in `sigma_out`.
template <class Model>
std::vector<typename Model::Point_3> synthetic_scan(const Model& model, std::size_t n, bool single_view,
                                                    double noise, std::mt19937_64& rng, double* sigma_out = nullptr)
{
  typedef typename Model::Point_3 Point_3;
  Point_3 eye;
  if(single_view)
  {
    std::normal_distribution<double> g(0., 1.);
    Eigen::Vector3d d(g(rng), g(rng), g(rng));
    d = model.translation() + 10. * model.shape().parameters().template head<3>().maxCoeff() * d.normalized();
    eye = Point_3(d[0], d[1], d[2]);
  }
  const auto samples = sample_model_surface(model, n, unsigned(rng()), 24, single_view ? &eye : nullptr);
  std::vector<Point_3> pts;
  pts.reserve(samples.size());
  for(const auto& s : samples) pts.push_back(s.point);
  const double sigma = noise * bounding_box_diagonal(pts);
  if(sigma > 0.)
  {
    std::normal_distribution<double> g(0., sigma);
    for(auto& p : pts)
      p = Point_3(p.x() + g(rng), p.y() + g(rng), p.z() + g(rng));
  }
  if(sigma_out) *sigma_out = sigma;
  return pts;
}

// Appends `count` stray points spread uniformly over the bounding box of
// `pts` scaled by `box_factor` about its centre (the outliers of the EMS
// protocol: 2 or 10 times the object's box).
template <class Point_3>
void add_stray_points(std::vector<Point_3>& pts, std::size_t count, double box_factor, std::mt19937_64& rng)
{
  CGAL::Bbox_3 b;
  for(const auto& p : pts) b += p.bbox();
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  const double c[3] = {0.5 * (b.xmin() + b.xmax()), 0.5 * (b.ymin() + b.ymax()), 0.5 * (b.zmin() + b.zmax())};
  const double size[3] = {box_factor * (b.xmax() - b.xmin()), box_factor * (b.ymax() - b.ymin()),
                          box_factor * (b.zmax() - b.zmin())};
  for(std::size_t i = 0; i < count; ++i)
  {
    const double x = c[0] + size[0] * unit(rng), y = c[1] + size[1] * unit(rng), z = c[2] + size[2] * unit(rng);
    pts.emplace_back(x, y, z);
  }
}

// Whether `p` (in space) is inside the placed superellipsoid `m` (a
// Deformable_model of a Superquadric_ellipsoid): its inside-outside
// function below 1. For scenes of several superquadrics, whose union's
// surface is the samples of each outside the others.
template <class Model>
bool is_inside(const Model& m, const Eigen::Vector3d& p)
{
  const Eigen::Quaterniond q(m.quaternion()[0], m.quaternion()[1], m.quaternion()[2], m.quaternion()[3]);
  const Eigen::Vector3d x = q.conjugate() * (p - m.translation());
  const auto a = m.shape().parameters();
  const double xy = std::pow(std::pow(std::abs(x[0] / a[0]), 2. / a[4]) + std::pow(std::abs(x[1] / a[1]), 2. / a[4]),
                             a[4] / a[3]);
  return xy + std::pow(std::abs(x[2] / a[2]), 2. / a[3]) < 1.;
}

// Noisy samples of the surface of the union of two placed superellipsoids
// (a body and a part sticking out of it): `n` samples of each surface (by
// sample_model_surface(), seed 5), those outside the other one kept, with
// normal noise of standard deviation `noise` on each coordinate.
template <class Point_3, class Model, class RandomEngine>
std::vector<Point_3> scan_of_union(const Model& body, const Model& part, std::size_t n, double noise, RandomEngine& rng)
{
  std::vector<Point_3> points;
  std::normal_distribution<double> g(0., noise);
  for(const Model* m : {&body, &part})
    for(const auto& s : sample_model_surface(*m, n, 5))
    {
      const Eigen::Vector3d p(CGAL::to_double(s.point.x()), CGAL::to_double(s.point.y()), CGAL::to_double(s.point.z()));
      if(!is_inside(m == &body ? part : body, p))
        points.emplace_back(p.x() + g(rng), p.y() + g(rng), p.z() + g(rng));
    }
  return points;
}

// The body with a part of the evolution tests and benchmarks: an ellipsoid
// (1, 0.8, 0.6) with a round part (0.3, 0.3, 0.5, exponents 0.4, 1) on top
// (centre at z = 0.9), scanned by scan_of_union() with noise 0.006 (0.2 %
// of the diagonal), `n` samples per surface, random engine seeded `seed`.
template <class K>
std::vector<typename K::Point_3> body_with_part_scan(std::size_t n, unsigned seed)
{
  typedef Deformable_model<Superquadric_ellipsoid<K>> Model;
  const Model body(Superquadric_ellipsoid<K>(1., 0.8, 0.6, 1., 1.));
  const Model part(Superquadric_ellipsoid<K>(0.3, 0.3, 0.5, 0.4, 1.), Eigen::Vector3d(0., 0., 0.9),
                   Eigen::Vector4d(1., 0., 0., 0.));
  std::mt19937_64 rng(seed);
  return scan_of_union<typename K::Point_3>(body, part, n, 0.006, rng);
}

} // namespace testing
} // namespace Blended_shapes
} // namespace CGAL

#endif // BLENDED_SHAPE_TESTING_SYNTHETIC_SCANS_H
