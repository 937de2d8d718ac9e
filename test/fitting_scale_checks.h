// SPDX-License-Identifier: LGPL-3.0-or-later
// Fits at any scale and place: the normalization of fit_superquadric()
// (internal::Point_normalization) maps points and models exactly; scaling
// the input by 1e-9 or 1e9, or moving it by 1e15, scales and moves the fit
// and keeps its relative figures; 1e-12 and 1e12 work, chamfer distances and
// meshes included; coordinates whose squares overflow are refused first.
#ifndef BLENDED_SHAPE_FITTING_SCALE_CHECKS_H
#define BLENDED_SHAPE_FITTING_SCALE_CHECKS_H
// Part of test_fitting (one program, one compilation of the fitter; CTest
// runs it as `test_fitting scale`).
#include "test_kernels.h"
#include "test_util.h"

#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <CGAL/Blended_shape/Fitting/internal/Point_normalization.h>
#include <CGAL/Blended_shape/Primitives/check_primitive.h>
#include <blended_shape_testing/compare_superquadrics.h>
#include <blended_shape_testing/equivariance.h>
#include <blended_shape_testing/synthetic_scans.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/boost/graph/generators.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

namespace fitting_scale_checks {

namespace BS = CGAL::Blended_shapes;

// Points per synthetic cloud: fewer in sanitizer builds (same code paths).
#ifdef BLENDED_SHAPE_REDUCED_TESTS
const std::size_t cloud_size = 600;
#else
const std::size_t cloud_size = 1500;
#endif

template <class K>
using Model = BS::Deformable_model<BS::Superquadric_ellipsoid<K>>;

template <class Point_3>
std::vector<Point_3> moved(const std::vector<Point_3>& points, const BS::testing::Similarity& T)
{
  std::vector<Point_3> result;
  for(const Point_3& p : points)
    result.push_back(T(p));
  return result;
}

// Every figure of the gap within 1e-6: the relative RMS, the surfaces, the
// semi-axes, the rotation and the translation, the RMS, the initial ellipsoid.
void check_gap(const BS::testing::Equivariance_gap& gap, const std::string& label)
{
  for(std::size_t j = 0; j < 3; ++j)
    BS_CHECK(gap.relative_rms[j] <= 1e-6, label << ": relative RMS " << j << " apart by " << gap.relative_rms[j]);
  BS_CHECK(gap.surface <= 1e-6, label << ": surfaces apart by " << gap.surface << " of the diagonal");
  BS_CHECK(gap.size <= 1e-6, label << ": semi-axes apart by " << gap.size);
  BS_CHECK(gap.rotation <= 1e-9, label << ": axes apart, 1 - |cos| = " << gap.rotation);
  BS_CHECK(gap.translation <= 1e-6, label << ": translations apart by " << gap.translation << " of the diagonal");
  BS_CHECK(gap.rms <= 1e-6, label << ": RMS apart by " << gap.rms);
  BS_CHECK(gap.initial_axes <= 1e-6, label << ": initial ellipsoids apart by " << gap.initial_axes);
  std::cout << "  " << label << ": relative RMS " << gap.moved_relative_rms[0] << ' ' << gap.moved_relative_rms[1]
            << ' ' << gap.moved_relative_rms[2] << " (apart by at most "
            << (std::max)({gap.relative_rms[0], gap.relative_rms[1], gap.relative_rms[2]}) << ")\n";
}

// Point_normalization: a power-of-two scale, the points in [-1, 1]^3 with
// a side of at least 1/2, the round trip within rounding, and a model taken
// back is the same surface, its sizes scaled exactly.
template <class K>
void test_point_normalization(std::mt19937_64& rng)
{
  typedef typename K::Point_3 Point_3;
  const Model<K> truth = BS::testing::random_superellipsoid<K>(rng);
  const std::vector<Point_3> unit = BS::testing::synthetic_scan(truth, 300, true, 0., rng);
  for(const BS::testing::Similarity& T : {BS::testing::random_similarity(rng, 1e-12, 0.),
                                          BS::testing::random_similarity(rng, 3e5, 1e15)})
  {
    const std::vector<Point_3> pts = moved(unit, T);
    const BS::internal::Point_normalization<K> N(pts, CGAL::Identity_property_map<Point_3>());
    std::ostringstream label;
    label << "normalization at scale " << T.scale << ", offset " << T.t.norm();
    int exponent;
    BS_CHECK(std::frexp(N.scale(), &exponent) == 0.5, label.str() << ": scale " << N.scale() << " not a power of two");
    const double epsilon = std::numeric_limits<double>::epsilon();
    const double tolerance = 4. * epsilon * (N.center().norm() + N.scale());
    Eigen::Vector3d low = Eigen::Vector3d::Constant(HUGE_VAL), high = -low;
    double worst_round_trip = 0.;
    for(const Point_3& p : N.normalized_points(pts, CGAL::Identity_property_map<Point_3>()))
    {
      const Eigen::Vector3d x(p.x(), p.y(), p.z());
      low = low.cwiseMin(x);
      high = high.cwiseMax(x);
    }
    for(const Point_3& p : pts)
        worst_round_trip = (std::max)(worst_round_trip, std::sqrt(CGAL::squared_distance(N.from_normalized(N.to_normalized(p)), p)));
    BS_CHECK(low.minCoeff() >= -1. && high.maxCoeff() <= 1. && (high - low).maxCoeff() >= 0.5,
             label.str() << ": normalized box " << low.transpose() << " to " << high.transpose());
    BS_CHECK(worst_round_trip <= tolerance, label.str() << ": round trip off by " << worst_round_trip);

    const Model<K> back = N.model_from_normalized(truth);
    BS_CHECK(back.shape().parameters().template head<3>() == N.scale() * truth.shape().parameters().template head<3>() &&
               back.shape().parameters().template tail<2>() == truth.shape().parameters().template tail<2>(),
             label.str() << ": shape parameters " << back.shape().parameters().transpose());
    double worst_point = 0.;
    for(int i = 0; i < 50; ++i)
    {
      const BS::Chart_point u = BS::random_chart_point(truth.shape(), std::size_t(i % 2), rng);
      worst_point = (std::max)(worst_point, std::sqrt(CGAL::squared_distance(back.point(u), N.from_normalized(truth.point(u)))));
    }
    BS_CHECK(worst_point <= 16. * epsilon * (N.center().norm() + 10. * N.scale()), label.str() << ": a model point taken back is off by " << worst_point);
  }
}

// Scaling the input by 1e-9, 1 and 1e9 (with a rotation and a translation of
// about 10 times the scale) scales the fit and keeps its relative figures.
template <class K>
void test_scale_equivariance(std::mt19937_64& rng)
{
  const Model<K> truth = BS::testing::random_superellipsoid<K>(rng);
  const auto pts = BS::testing::synthetic_scan(truth, cloud_size, false, 0.002, rng);
  const auto fit = BS::fit_superquadric(pts);
  std::cout << "  unit: relative RMS " << fit.metrics.relative_rms[0] << ' ' << fit.metrics.relative_rms[1] << ' '
            << fit.metrics.relative_rms[2] << "\n";
  for(double scale : {1e-9, 1., 1e9})
  {
    const BS::testing::Similarity T = BS::testing::random_similarity(rng, scale, 10. * scale);
    std::ostringstream label;
    label << "scale " << scale;
    check_gap(BS::testing::equivariance_gap(fit, moved(pts, T), T), label.str());
  }
}

// Moving a cloud of size about 1e7 by about 1e15 (exactly: its coordinates
// are multiples of 1/8, the spacing of doubles near 1e15) moves the fit and
// keeps its relative figures.
template <class K>
void test_offset_equivariance(std::mt19937_64& rng)
{
  typedef typename K::Point_3 Point_3;
  const Model<K> truth = BS::testing::random_superellipsoid<K>(rng);
  std::vector<Point_3> pts;
  for(const Point_3& p : BS::testing::synthetic_scan(truth, cloud_size, true, 0.002, rng))
  {
    auto on_grid = [](double x) { return std::round(std::ldexp(x, 20 + 3)) / 8.; }; // times 2^20, to 1/8
    pts.emplace_back(on_grid(p.x()), on_grid(p.y()), on_grid(p.z()));
  }
  const auto fit = BS::fit_superquadric(pts);
  for(const Eigen::Vector3d& offset : {Eigen::Vector3d(1e15, -1e15, 0.5e15), Eigen::Vector3d(-7e14, 0., 1e15)})
  {
    BS::testing::Similarity T;
    T.t = offset;
    const std::vector<Point_3> far = moved(pts, T);
    bool exact = true;
    for(std::size_t i = 0; i < pts.size(); ++i)
      exact = exact && T.inverse(far[i]) == pts[i];
    std::ostringstream label;
    label << "offset " << offset.transpose();
    BS_CHECK(exact, label.str() << ": the moved cloud is not exact");
    check_gap(BS::testing::equivariance_gap(fit, far, T), label.str());
  }
}

// The unit sphere at 1e-12 (the case of the issue) and 1e12: the fit, its
// chamfer distance to a moved reference mesh and its meshes scale.
template <class K>
void test_extreme_scales(std::mt19937_64& rng)
{
  typedef typename K::Point_3 Point_3;
  typedef CGAL::Surface_mesh<Point_3> Mesh;
  const Model<K> sphere;
  const auto pts = BS::testing::synthetic_scan(sphere, cloud_size / 2, false, 0.002, rng);
  Mesh reference;
  CGAL::make_icosahedron<Mesh, Point_3>(reference, Point_3(0., 0., 0.), 1.);
  // A noisy sphere's rotation is barely defined: it comes to rest slowly, so only 30 iterations.
  const auto fit = BS::fit_superquadric(pts, BS::parameters::reference_mesh(&reference).number_of_iterations(30));
  for(double scale : {1e-12, 1e12})
  {
    BS::testing::Similarity T; // no rotation: the axes of a sphere are barely defined
    T.scale = scale;
    T.t = scale * Eigen::Vector3d(0.3, -0.2, 0.1);
    Mesh moved_reference = reference;
    for(auto v : moved_reference.vertices())
      moved_reference.point(v) = T(moved_reference.point(v));
    const auto far =
      BS::fit_superquadric(moved(pts, T), BS::parameters::reference_mesh(&moved_reference).number_of_iterations(30));
    std::ostringstream label;
    label << "unit sphere at scale " << scale;
    BS_CHECK(far.model.parameters().allFinite() && far.metrics.converged == fit.metrics.converged,
             label.str() << ": " << far.model.parameters().transpose());
    for(std::size_t j = 0; j < 3; ++j)
      BS_CHECK(std::abs(far.metrics.relative_rms[j] / fit.metrics.relative_rms[j] - 1.) <= 1e-6,
               label.str() << ": relative RMS " << far.metrics.relative_rms[j] << " vs " << fit.metrics.relative_rms[j]);
    BS_CHECK(std::abs(*far.metrics.chamfer_distance / (scale * *fit.metrics.chamfer_distance) - 1.) <= 1e-6,
             label.str() << ": chamfer distance " << *far.metrics.chamfer_distance << " vs "
                         << scale * *fit.metrics.chamfer_distance);
    const auto c = BS::testing::compare_superquadrics(far.model, T.moved_model(fit.model));
    BS_CHECK(c.size_error <= 1e-6, label.str() << ": semi-axes " << far.model.shape().parameters().transpose());
    double worst_vertex = 0.;
    for(std::size_t m = 0; m < far.meshes.size(); ++m)
      for(auto v : far.meshes[m].mesh().vertices())
        worst_vertex = (std::max)(worst_vertex, std::sqrt(CGAL::squared_distance(
                                                  far.meshes[m].mesh().point(v), T(fit.meshes[m].mesh().point(v)))));
    BS_CHECK(worst_vertex <= 1e-6 * scale, label.str() << ": mesh vertices off by " << worst_vertex / scale << " of the size");
  }
}

// Coordinates beyond 1e150, or an extent under 1e-150, are refused before
// any fitting with Scale_out_of_range and a message that says so; up to
// there the fit works.
template <class K>
void test_scale_out_of_range(std::mt19937_64& rng)
{
  typedef typename K::Point_3 Point_3;
  const Model<K> sphere;
  const auto pts = BS::testing::synthetic_scan(sphere, 200, false, 0.002, rng);
  auto error_of = [&](const std::vector<Point_3>& cloud) {
    try
    {
      const auto r = BS::fit_superquadric(cloud);
      return "no error; the fit gives " + std::to_string(r.model.parameters()[7]);
    }
    catch(const BS::Input_error& e)
    {
      return std::string(e.code() == BS::Input_error::Scale_out_of_range ? "" : "wrong code: ") + e.what();
    }
  };
  auto scaled = [&](double scale) { return moved(pts, BS::testing::random_similarity(rng, scale, 0.)); };
  const std::string huge = error_of(scaled(1e300));
  BS_CHECK(huge.rfind("check_points: point ", 0) == 0 && huge.find("beyond 1e+150") != std::string::npos &&
             huge.find("nan") == std::string::npos,
           "1e300: " << huge);
  std::vector<Point_3> one_far = pts;
  one_far[7] = Point_3(0., -2e150, 0.);
  const std::string far = error_of(one_far);
  BS_CHECK(far.rfind("check_points: point 7 ", 0) == 0, "one point at 2e150: " << far);
  const std::string tiny = error_of(scaled(1e-160));
  BS_CHECK(tiny.rfind("check_points: the points span only ", 0) == 0 && tiny.find("1e-150") != std::string::npos,
           "1e-160: " << tiny);
  for(double scale : {1e140, 1e-140})
  {
    const auto r = BS::fit_superquadric(scaled(scale), CGAL::parameters::number_of_iterations(30));
    BS_CHECK(r.model.parameters().allFinite() && std::abs(r.model.shape().parameters()[0] / scale - 1.) < 0.01 &&
               r.metrics.relative_rms[0] < 0.01,
             "scale " << scale << ": " << r.model.parameters().transpose());
  }
}

template <class Test>
void timed(const char* name, const Test& test)
{
  const auto start = std::chrono::steady_clock::now();
  test();
  std::cout << " " << name << ": " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
            << " s\n";
}

template <class K>
void run(const char* kernel)
{
  std::mt19937_64 rng(20261122);
  const int before = blended_shape_test::failures();
  std::cout << kernel << ":\n";
  timed("point normalization", [&] { test_point_normalization<K>(rng); });
  timed("scale equivariance", [&] { test_scale_equivariance<K>(rng); });
  timed("offset equivariance", [&] { test_offset_equivariance<K>(rng); });
  timed("extreme scales", [&] { test_extreme_scales<K>(rng); });
  timed("scale out of range", [&] { test_scale_out_of_range<K>(rng); });
  std::cout << kernel << ": " << blended_shape_test::failures() - before << " failed checks" << std::endl;
}

inline void run_all()
{
  std::cout << "Fits at any scale and place; relative RMS of the moved copies, and seconds per test:\n";
  blended_shape_test::for_each_kernel([](auto kernel, const char* name) { run<decltype(kernel)>(name); });
}

} // namespace fitting_scale_checks

#endif
