// SPDX-License-Identifier: LGPL-3.0-or-later
// Stray points (issue 12): fit_superquadric() by default fits random
// superellipsoids among 0, 20 and 40 % strays spread over 2 and 10 times
// their bounding box (the EMS protocol) and reports the strays.
#ifndef BLENDED_SHAPE_STRAY_POINT_CHECKS_H
#define BLENDED_SHAPE_STRAY_POINT_CHECKS_H
// Part of test_fitting (one program, one compilation of the fitter; CTest
// runs it as `test_fitting strays`).
#include "test_kernels.h"
#include "test_util.h"

#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <CGAL/Blended_shape/Fitting/internal/stray_surface_points.h>
#include <CGAL/Blended_shape/Scanning/CAD_primitive_solids.h>
#include <CGAL/Blended_shape/Scanning/Range_scan_simulator.h>
#include <blended_shape_testing/compare_superquadrics.h>
#include <blended_shape_testing/scanner_views.h>
#include <blended_shape_testing/synthetic_scans.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <iostream>
#include <random>
#include <sstream>

namespace stray_point_checks {

namespace BS = CGAL::Blended_shapes;

#ifdef BLENDED_SHAPE_REDUCED_TESTS
constexpr std::size_t cloud_size = 1500; // sanitizer builds: fewer points
#else
constexpr std::size_t cloud_size = 3000;
#endif

// A random superellipsoid seen from one view (`inliers` points, noise 0.2 %
// of the diagonal) among `strays` points spread over `box_factor` times its box.
template <class K>
void test_fit_among_strays(std::size_t inliers, std::size_t strays, double box_factor, std::mt19937_64& rng)
{
  typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Model;
  const double stray_fraction = double(strays) / double(inliers + strays);
  const Model truth = BS::testing::random_superellipsoid<K>(rng);
  auto pts = BS::testing::synthetic_scan(truth, inliers, false, 0.002, rng);
  const double diagonal = BS::testing::bounding_box_diagonal(pts);
  BS::testing::add_stray_points(pts, strays, box_factor, rng);

  const auto r = BS::fit_superquadric(pts);
  std::ostringstream label;
  label << 100. * stray_fraction << " % strays over " << box_factor << "x the box, truth "
        << truth.shape().parameters().transpose() << ", fit " << r.model.shape().parameters().transpose();
  const auto identity = [](const typename K::Point_3& p) { return p; };
  const double apart = (std::max)(BS::testing::surface_distance(r.model, identity, truth),
                                  BS::testing::surface_distance(truth, identity, r.model));
  // The strays are appended: indices from `inliers` on.
  std::size_t strays_found = 0, inliers_flagged = 0;
  for(std::size_t i : r.stray_points)
    (i >= inliers ? strays_found : inliers_flagged) += 1;
  BS_CHECK(r.metrics.number_of_stray_points == r.stray_points.size(), label.str() << ": count and indices differ");
  BS_CHECK(apart <= 0.01 * diagonal, label.str() << ": surfaces " << apart / diagonal << " of the diagonal apart");
  // Strays that fell within the stray distance (about 0.03 of the diagonal
  // with 40 % strays) of the surface are points of the surface as far as
  // any fit can tell: a few % of those spread over twice the box, so 90 %
  // must be found. An inlier with Gaussian noise is never 7 sigma away.
  BS_CHECK(double(strays_found) >= 0.9 * double(strays),
           label.str() << ": " << strays_found << " of " << strays << " strays found");
  BS_CHECK(inliers_flagged <= inliers / 200, label.str() << ": " << inliers_flagged << " inliers judged stray");
}

// No strays, but uneven density: the cylinder of the box/cylinder scanned
// from the default camera (the points above the box's top, every 4th: 1325
// points), its cap seen face-on (dense), its side at a slant (sparse). The
// scan is of the box and the cylinder as two solids, not of their union
// (make_box_cylinder(), whose Boolean operation was a seventh of this
// program's compilation): the surfaces a ray meets first are the same, and so
// is the camera (the bounding box is the same), as test_scanning checks. One
// superquadric holds it; the robust default must fit it whole. With the
// full fits' noise ceiling in the rough fits of the search
// (candidate_noise_ceiling 0.02), none of them reached that basin: the fit
// ended at semi-axes 0.44, 1.97, 0.22 with 606 points judged stray.
template <class K>
void test_uneven_density_cylinder()
{
  const auto object = BS::internal::box_cylinder_overlapping_solids(BS::Box_cylinder_parameters(), "box/cylinder");
  std::vector<typename K::Point_3> pts;
  std::size_t above = 0;
  for(const auto& sample : BS::simulate_range_scan(object, BS::default_camera_for(object)))
    if(sample.point.z() > 1.02 && above++ % 4 == 0)
      pts.emplace_back(sample.point.x(), sample.point.y(), sample.point.z());
  const auto r = BS::fit_superquadric(pts);
  const auto q = r.model.shape().parameters();
  std::ostringstream label;
  label << "cylinder of the box/cylinder scan (" << pts.size() << " points, no strays): fit " << q.transpose()
        << ", " << r.metrics.number_of_stray_points << " points judged stray";
  // the radius 0.6 (a1, a2), a circular cross-section (e2 = 1), flat ends (e1 small)
  BS_CHECK(std::abs(q[0] - 0.6) <= 0.02 && std::abs(q[1] - 0.6) <= 0.02 && q[3] < 0.3 && std::abs(q[4] - 1.) < 0.1,
           label.str());
  BS_CHECK(r.metrics.number_of_stray_points <= pts.size() / 100, label.str());
  BS_CHECK(r.metrics.converged, label.str() << ": not converged");
}

// No strays, but a range scan's uneven density, on a random superellipsoid
// (fit_single_superquadric --scanner-views, its first view: 7000): before
// the mend of missed surfaces (mend_missed_surfaces(false)) the robust
// default rested on the dense part alone, taking the rest for strays, on
// this view and on 13 more of 100; least squares fitted it. The mended fit
// must fit the whole view, and judge at most 1 % of its points stray.
template <class K>
void test_scanner_view_mended()
{
  const auto view = BS::testing::scanner_view<K>(7000u);
  const auto r = BS::fit_superquadric(view.points);
  std::ostringstream label;
  label << "scanner view 7000 (" << view.points.size() << " points, no strays): fit "
        << r.model.shape().parameters().transpose() << ", " << r.metrics.number_of_stray_points
        << " points judged stray";
  BS_CHECK(BS::testing::fits_view(view.points, r.model), label.str());
  BS_CHECK(r.metrics.number_of_stray_points <= view.points.size() / 100, label.str());
}

template <class K>
void run(const char* kernel)
{
  std::mt19937_64 rng(20261212);
  const int before = blended_shape_test::failures();
  for(double box_factor : {2., 10.})
    for(double stray_fraction : {0., 0.2, 0.4})
    {
      const std::size_t strays = std::size_t(std::lround(stray_fraction * double(cloud_size)));
      test_fit_among_strays<K>(cloud_size - strays, strays, box_factor, rng);
    }
  // Two clouds of the peer protocol (fit_single_superquadric --outliers 0.4
  // --outlier-box 2, its fits 1 and 2: 3600 points and 2400 strays over
  // twice the box) on which the fit ended among the strays (8.9 and 3.0 %
  // of the diagonal) before the initialization left the isolated points out.
  // (Not in sanitizer builds: 6000 points each, the code paths of the
  // clouds above at a larger size.)
#ifndef BLENDED_SHAPE_REDUCED_TESTS
  for(unsigned fit : {1u, 2u})
  {
    std::mt19937_64 protocol_rng(5000u + fit);
    test_fit_among_strays<K>(3600, 2400, 2., protocol_rng);
  }
#endif
  test_uneven_density_cylinder<K>();
  test_scanner_view_mended<K>();
  std::cout << "stray points with " << kernel << (blended_shape_test::failures() == before ? ": SUCCESS" : ": FAILED")
            << std::endl;
}

// count_stray_surface_points(), the test of the mend, on points whose
// answer is known: every point judged stray and none isolated,
// - spread uniformly through a cube: their neighbourhoods are not flat (the
//   smallest eigenvalue of a point's and its 16 nearest's covariance is
//   about a fifth of its trace), so at most 1 % count, which never starts
//   the mend; with the flatness bound at 1 (every neighbourhood flat
//   enough) they all count, so the flatness test is what tells them apart;
// - on a plane (a grid): every one counts;
// - on the plane but only one in ten judged stray (strays among inliers):
//   none counts.
inline void test_stray_surface_points()
{
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> u(0., 1.);
  std::vector<Eigen::Vector3d> cube(3000), plane;
  for(Eigen::Vector3d& p : cube)
    p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  for(int i = 0; i < 50; ++i)
    for(int j = 0; j < 50; ++j)
      plane.emplace_back(0.02 * i, 0.02 * j, 0.01 * i);
  const std::vector<bool> cube_stray(cube.size(), true), cube_isolated(cube.size(), false);
  const std::size_t in_cube = BS::internal::count_stray_surface_points(cube, cube_stray, cube_isolated);
  BS_CHECK(in_cube <= cube.size() / 100, in_cube << " of " << cube.size() << " points spread through a cube counted as a surface");
  const std::size_t any_flatness = BS::internal::count_stray_surface_points(cube, cube_stray, cube_isolated, 16, 0.75, 1.);
  BS_CHECK(any_flatness == cube.size(), any_flatness << " of the cube's points counted without the flatness test");
  const std::vector<bool> plane_stray(plane.size(), true), plane_isolated(plane.size(), false);
  const std::size_t on_plane = BS::internal::count_stray_surface_points(plane, plane_stray, plane_isolated);
  BS_CHECK(on_plane == plane.size(), on_plane << " of " << plane.size() << " stray points of a plane counted as a surface");
  std::vector<bool> few(plane.size(), false);
  for(std::size_t i = 0; i < plane.size(); i += 10)
    few[i] = true;
  const std::size_t among_inliers = BS::internal::count_stray_surface_points(plane, few, plane_isolated);
  BS_CHECK(among_inliers == 0, among_inliers << " strays among the inliers of a plane counted as a surface");
}

inline void run_all()
{
  test_stray_surface_points();
  blended_shape_test::for_each_kernel([](auto kernel, const char* name) { run<decltype(kernel)>(name); });
}

} // namespace stray_point_checks

#endif
