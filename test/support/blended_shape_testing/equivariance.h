// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef BLENDED_SHAPE_TESTING_EQUIVARIANCE_H
#define BLENDED_SHAPE_TESTING_EQUIVARIANCE_H

#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <blended_shape_testing/compare_superquadrics.h>
#include <CGAL/Blended_shape/internal/quaternion.h>
#include <blended_shape_testing/synthetic_scans.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace testing {

// The similarity x -> scale R x + t.
struct Similarity
{
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double scale = 1.;

  template <class Point_3>
  Point_3 operator()(const Point_3& p) const
  {
    const Eigen::Vector3d y = scale * (R * Eigen::Vector3d(p.x(), p.y(), p.z())) + t;
    return Point_3(y[0], y[1], y[2]);
  }
  template <class Point_3>
  Point_3 inverse(const Point_3& p) const
  {
    const Eigen::Vector3d y = R.transpose() * (Eigen::Vector3d(p.x(), p.y(), p.z()) - t) / scale;
    return Point_3(y[0], y[1], y[2]);
  }
  // A superquadric model moved by this similarity.
  template <class Model>
  Model moved_model(const Model& model) const
  {
    auto q = model.shape().parameters();
    q.template head<3>() *= scale;
    typename Model::Shape_type shape = model.shape();
    shape.set_parameters(q);
    return Model(shape, scale * (R * model.translation()) + t, internal::quaternion_from_matrix(R * model.rotation()));
  }
};

// A random rotation, a translation of `shift` times a standard normal
// vector, and `scale`.
template <class RandomEngine>
Similarity random_similarity(RandomEngine& rng, double scale, double shift)
{
  std::normal_distribution<double> g(0., 1.);
  Similarity T;
  T.R = internal::rotation_matrix(Eigen::Vector4d(g(rng), g(rng), g(rng), g(rng)));
  T.t = Eigen::Vector3d(shift * g(rng), shift * g(rng), shift * g(rng));
  T.scale = scale;
  return T;
}

// How far a fit_superquadric() result of a cloud and that of its copy moved
// by a similarity are apart. For tests and benchmarks.
struct Equivariance_gap
{
  std::array<double, 3> relative_rms = {{0., 0., 0.}}; // |RMS_j(copy) - RMS_j| / RMS_j (eq. 14)
  std::array<double, 3> moved_relative_rms = {{0., 0., 0.}}; // RMS_j(copy)
  double surface = 0.; // the fitted surfaces apart (both ways), over the copy's bounding-box diagonal
  double size = 0.;    // the largest |a_i(copy) / (scale a_i) - 1| of the semi-axes (see compare_superquadrics())
  double rotation = 0.; // 1 - the smallest |cos| between matched axes of the copy's fit and the moved fit
  double translation = 0.; // |c(copy) - T(c)|, over the copy's bounding-box diagonal
  double rms = 0.;     // |rms(copy) / (scale rms) - 1|
  double initial_axes = 0.; // the largest |axis(copy) / (scale axis) - 1| of the initial ellipsoids
};

// The gap between `fit`, the result of fit_superquadric() for some points,
// and the fit of `moved`, their image by `T`.
template <class Point_3, class Result>
Equivariance_gap equivariance_gap(const Result& fit, const std::vector<Point_3>& moved, const Similarity& T)
{
  const auto& a = fit;
  const auto b = fit_superquadric(moved);
  auto relative_gap = [](double x, double reference) { return std::abs(x / reference - 1.); };
  Equivariance_gap gap;
  const double diagonal = bounding_box_diagonal(moved);
  for(std::size_t j = 0; j < 3; ++j)
  {
    gap.relative_rms[j] = relative_gap(b.metrics.relative_rms[j], a.metrics.relative_rms[j]);
    gap.moved_relative_rms[j] = b.metrics.relative_rms[j];
    gap.initial_axes = (std::max)(gap.initial_axes, relative_gap(b.initial_ellipsoid.axes[j], T.scale * a.initial_ellipsoid.axes[j]));
  }
  const auto inverse = [&](const Point_3& p) { return T.inverse(p); };
  gap.surface = (std::max)(surface_distance(a.model, T, b.model), T.scale * surface_distance(b.model, inverse, a.model)) /
                diagonal;
  const auto moved_fit = T.moved_model(a.model);
  const Superquadric_comparison c = compare_superquadrics(b.model, moved_fit);
  gap.size = c.size_error;
  gap.rotation = 1. - c.axis_alignment;
  gap.translation = (b.model.translation() - moved_fit.translation()).norm() / diagonal;
  gap.rms = relative_gap(b.metrics.rms, T.scale * a.metrics.rms);
  return gap;
}

// The gap between the fits of `points` and of their copy moved by a random
// similarity (rotation, translation of about 10, scale 3.7).
template <class Point_3, class RandomEngine>
Equivariance_gap equivariance_gap(const std::vector<Point_3>& points, RandomEngine& rng)
{
  const Similarity T = random_similarity(rng, 3.7, 10.);
  std::vector<Point_3> moved;
  for(const Point_3& p : points)
    moved.push_back(T(p));
  return equivariance_gap(fit_superquadric(points), moved, T);
}

} // namespace testing
} // namespace Blended_shapes
} // namespace CGAL

#endif // BLENDED_SHAPE_TESTING_EQUIVARIANCE_H
