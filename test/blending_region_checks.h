// SPDX-License-Identifier: LGPL-3.0-or-later
// The 2D math of blending regions (App. A.1-A.4): the blending function, the
// Bezier loop and its strip, strip coordinates and their inverse, sides,
// de Casteljau subdivision, the ellipse-shaped parameterization, and every
// analytic derivative against central finite differences.
#ifndef BLENDED_SHAPE_BLENDING_REGION_CHECKS_H
#define BLENDED_SHAPE_BLENDING_REGION_CHECKS_H
// Part of test_blended_shape (one program, one compilation of the blended
// shape for each kernel; CTest runs it as `test_blended_shape_blending_region`).
#include "test_util.h"

#include <CGAL/Blended_shape/Blending/Blending_function.h>
#include <CGAL/Blended_shape/Blending/Blending_region.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

namespace blending_region_checks {

namespace BS = CGAL::Blended_shapes;
typedef Eigen::Vector2d V2;
typedef BS::Ellipse_blending_region Ellipse;

std::mt19937_64 rng(20240611);
double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

template <class F>
bool throws_invalid(F f)
{
  try
  {
    f();
  }
  catch(const std::invalid_argument&)
  {
    return true;
  }
  return false;
}

// Largest error of an analytic gradient against a finite-difference one,
// component by component, relative to max(|fd_j|, 1e-3 |fd|_inf, 1e-5):
// small components are compared at the scale of the whole gradient, and a
// gradient that nearly vanishes (alpha at d ~ w) in absolute terms, since
// the rounding noise of a difference quotient with step 1e-6 is ~1e-10.
template <class A, class B>
double gradient_error(const A& analytic, const B& fd)
{
  const double scale = (std::max)(fd.cwiseAbs().maxCoeff(), 1e-2);
  double worst = 0.;
  for(Eigen::Index j = 0; j < fd.size(); ++j)
  {
    const double e = std::abs(analytic[j] - fd[j]) / (std::max)(std::abs(fd[j]), 1e-3 * scale);
    if(!(e <= worst))
      worst = std::isfinite(e) ? (std::max)(e, worst) : HUGE_VAL;
  }
  return worst;
}

double angle_difference(double a, double b)
{
  double t = std::fmod(a - b, 2. * M_PI);
  if(t > M_PI)
    t -= 2. * M_PI;
  if(t < -M_PI)
    t += 2. * M_PI;
  return t;
}

// ---------------------------------------------------------------------------
// Blending function (eq. 4, 15)

// A deliberately wrong d alpha0 / dw (sign flipped) that the check must catch.
double wrong_alpha0_derivative_w(double d, double w) { return -BS::Blending_function::alpha0_derivative_w(d, w); }

void test_blending_function()
{
  typedef BS::Blending_function F;
  // Outside the transition, and the symmetry alpha0(-d) = 1 - alpha0(d).
  for(double w : {0.05, 0.3, 0.77, 1.})
  {
    BS_CHECK(F::alpha0(-w - 1e-9, w) == 0. && F::alpha0(-1., w) == 0. && F::alpha0(-5., w) == 0., "w = " << w);
    BS_CHECK(F::alpha0(w + 1e-9, w) == 1. && F::alpha0(1., w) == 1. && F::alpha0(5., w) == 1., "w = " << w);
    BS_CHECK(std::abs(F::alpha0(0., w) - 0.5) < 1e-15, "alpha0(0) = 1/2");
    BS_CHECK(F::alpha0_derivative_d(-2., w) == 0. && F::alpha0_derivative_d(2., w) == 0., "flat outside");
    for(int k = 0; k <= 100; ++k)
    {
      const double d = -1.2 + 2.4 * k / 100.;
      BS_CHECK(std::abs(F::alpha0(-d, w) - (1. - F::alpha0(d, w))) < 1e-15, "symmetry at d = " << d);
      BS_CHECK(F::alpha0(d, w) >= 0. && F::alpha0(d, w) <= 1., "range at d = " << d);
      BS_CHECK(F::alpha0(d + 1e-3, w) >= F::alpha0(d, w), "monotone at d = " << d);
    }
    // C1 at d = +-w: value and slope agree from both sides, and the
    // difference quotients across the joint tend to the (zero) slope.
    for(double s : {-1., 1.})
    {
      const double joint = s * w;
      const double inside = joint - s * 1e-7, outside = joint + s * 1e-7;
      // 1 - alpha0(w - delta) = 3 delta^2 / (4 w^2) + O(delta^3)
      BS_CHECK(std::abs(F::alpha0(inside, w) - F::alpha0(outside, w)) < 1e-14 / (w * w), "value jump at " << joint);
      BS_CHECK(std::abs(F::alpha0_derivative_d(inside, w)) < 1e-6 / w / w, "slope at " << joint);
      for(double delta : {1e-3, 1e-4, 1e-5})
      {
        const double q = (F::alpha0(joint + delta, w) - F::alpha0(joint - delta, w)) / (2. * delta);
        BS_CHECK(std::abs(q) <= 3. * delta / (w * w), "difference quotient " << q << " at " << joint);
        const double qd =
          (F::alpha0_derivative_d(joint + delta, w) - F::alpha0_derivative_d(joint - delta, w)) / 2.;
        BS_CHECK(std::abs(qd) < 2. * delta / (w * w * w), "slope jump at " << joint);
      }
    }
  }

  // alpha = alpha0 (1 - h) + h: range [h, 1], h = 0 gives alpha0, h = 1 gives 1.
  for(int k = 0; k < 200; ++k)
  {
    const double w = uniform(0.05, 1.), h = uniform(0., 1.), d = uniform(-1.5, 1.5);
    const F f(w, h);
    BS_CHECK(f(d) >= h - 1e-15 && f(d) <= 1. + 1e-15, "alpha range");
    BS_CHECK(std::abs(F(w, 0.)(d) - F::alpha0(d, w)) < 1e-15, "h = 0");
    BS_CHECK(F(w, 1.)(d) == 1., "h = 1");
    BS_CHECK(F(w, (std::min)(1., h + 0.1))(d) >= f(d) - 1e-15, "alpha increases with h");
  }

  // Every analytic derivative against central differences.
  double worst = 0., worst_wrong = HUGE_VAL;
  for(int k = 0; k < 2000; ++k)
  {
    const double w = uniform(0.1, 0.99), h = uniform(0.002, 0.998), d = uniform(-1., 1.);
    if(std::abs(std::abs(d) - w) < 1e-3)
      continue; // alpha0 is only C1 there
    const double eps = 1e-6;
    const F f(w, h);
    const F::Derivatives D = f.derivatives(d);
    BS_CHECK(D.alpha == f(d) && D.alpha0 == F::alpha0(d, w), "derivatives() values");
    Eigen::Vector3d an(D.d_d, D.d_w, D.d_h), fd;
    fd[0] = (f(d + eps) - f(d - eps)) / (2. * eps);
    fd[1] = (F(w + eps, h)(d) - F(w - eps, h)(d)) / (2. * eps);
    fd[2] = (F(w, h + 1e-3)(d) - F(w, h - 1e-3)(d)) / 2e-3; // affine in h: any step is exact
    // with the wrong d/dw
    Eigen::Vector3d wrong = an;
    wrong[1] = (1. - h) * wrong_alpha0_derivative_w(d, w);
    const double e = gradient_error(an, fd);
    worst = (std::max)(worst, e);
    if(std::abs(fd[1]) > 1e-2)
      worst_wrong = (std::min)(worst_wrong, gradient_error(wrong, fd));
    const double e0 = std::abs(F::alpha0_derivative_d(d, w) -
                               (F::alpha0(d + eps, w) - F::alpha0(d - eps, w)) / (2. * eps));
    BS_CHECK(e0 < 1e-8, "d alpha0 / dd at d = " << d << ", w = " << w);
  }
  BS_CHECK(worst < 1e-6, "alpha derivatives vs finite differences: " << worst);
  BS_CHECK(worst_wrong > 1e-2, "a wrong d alpha / dw went unnoticed: " << worst_wrong);
  std::cout << "  alpha derivatives: max relative error " << worst << " (wrong d/dw: >= " << worst_wrong << ")\n";

  // Validation.
  for(double w : {0., -0.2, 1.0000001, 2., std::nan(""), HUGE_VAL})
    BS_CHECK(throws_invalid([&] { F f(w, 0.); }), "w = " << w << " accepted");
  for(double h : {-1e-9, 1.5, std::nan(""), -HUGE_VAL})
    BS_CHECK(throws_invalid([&] { F f(0.5, h); }), "h = " << h << " accepted");
  F f(0.5, 0.5);
  BS_CHECK(throws_invalid([&] { f.set_w(0.); }) && f.w() == 0.5, "set_w validates and keeps the old value");
  BS_CHECK(throws_invalid([&] { f.set_h(2.); }) && f.h() == 0.5, "set_h validates and keeps the old value");
  BS_CHECK(!throws_invalid([&] { F g(1., 1.); F g2(1e-6, 0.); }), "bounds w = 1, h = 1 accepted");

  // The lower bound of w evaluates, on the curve (d = 0) too; below it
  // (at the smallest positive double, the bound before) alpha0 is 0 / 0.
  BS_CHECK(throws_invalid([&] { F g(0.5 * F::minimum_w, 0.); }) &&
             throws_invalid([&] { F g(std::numeric_limits<double>::min(), 0.); }),
           "w below minimum_w accepted");
  BS_CHECK(std::isnan(F::alpha0(0., std::numeric_limits<double>::min())),
           "alpha0 at the smallest positive w evaluates: minimum_w could be lower, say why it is not");
  const double wmin = F::minimum_w;
  for(double d : {0., 0.5 * wmin, -0.5 * wmin, wmin, -wmin, 0.5, -1.})
    for(double h : {0., 0.5})
    {
      const F::Derivatives D = F(wmin, h).derivatives(d);
      BS_CHECK(std::isfinite(D.alpha) && D.alpha >= h && D.alpha <= 1. && std::isfinite(D.d_d) &&
                 std::isfinite(D.d_w) && std::isfinite(D.d_h),
               "alpha or its derivatives at w = minimum_w, d = " << d << ": " << D.alpha << " " << D.d_d << " "
                                                                 << D.d_w << " " << D.d_h);
    }
  BS_CHECK(F::alpha0(0., wmin) == 0.5, "alpha0(0) at w = minimum_w: " << F::alpha0(0., wmin));
}

// ---------------------------------------------------------------------------
// Regions used by the tests

struct Region_case
{
  BS::Blending_region region;
  const char* what;
};

Ellipse random_ellipse(std::size_t n, BS::Blending_region_kind kind, BS::Retained_side side, double* r_out = nullptr)
{
  const double e1 = uniform(0.25, 0.7), e2 = uniform(0.25, 0.7);
  const double rmin = (std::min)(e1, e2) * (std::min)(e1, e2) / (std::max)(e1, e2);
  const double r = rmin * uniform(0.1, 0.3);
  if(r_out)
    *r_out = r;
  const double h = (kind == BS::Blending_region_kind::Disk) ? uniform(0.1, 0.9) : 0.;
  return Ellipse(Ellipse::make_parameters(uniform(-0.4, 0.4), uniform(-0.4, 0.4), e1, e2, uniform(-M_PI, M_PI),
                                          uniform(0.3, 0.9), h),
                 r, n, kind, side);
}

// A general loop: the tangent-polygon of a circle (as for an ellipse
// region, but any N >= 3), control points moved at random, random mu.
BS::Blending_region random_loop(std::size_t n)
{
  for(;;)
  {
    const V2 c(uniform(-0.2, 0.2), uniform(-0.2, 0.2));
    const double rho = uniform(0.4, 0.6), phase = uniform(0., 3.);
    std::vector<V2> cp;
    std::vector<double> mu;
    for(std::size_t i = 0; i < n; ++i)
    {
      const double m = phase + 2. * M_PI * (double(i) + 0.5) / double(n);
      cp.push_back(c + rho / std::cos(M_PI / double(n)) * V2(std::cos(m), std::sin(m)) +
                   V2(uniform(-0.05, 0.05), uniform(-0.05, 0.05)));
      mu.push_back(uniform(0.35, 0.65));
    }
    try
    {
      return BS::Blending_region(cp, mu, 0.04, BS::Blending_region_kind::Disk, BS::Retained_side::Outside,
                                 BS::Blending_function(0.7, 0.3));
    }
    catch(const std::invalid_argument&)
    {
    } // a fold: draw again
  }
}

// A rounded square: corner arcs alternating with straight pieces, where
// consecutive normals are equal (the first case of eq. 23).
BS::Blending_region rounded_square(BS::Retained_side side)
{
  std::vector<V2> cp = {V2(1, 0),  V2(1, 1),   V2(0, 1),  V2(-1, 1),
                        V2(-1, 0), V2(-1, -1), V2(0, -1), V2(1, -1)};
  std::vector<double> mu(8, 0.5);
  return BS::Blending_region(cp, mu, 0.1, BS::Blending_region_kind::Annulus, side);
}

std::vector<Region_case> regions_for_coordinates()
{
  std::vector<Region_case> cases;
  const std::size_t ns[] = {4, 5, 6, 8, 12, 16};
  for(std::size_t k = 0; k < 6; ++k)
  {
    const BS::Blending_region_kind kind = (k % 2) ? BS::Blending_region_kind::Disk : BS::Blending_region_kind::Annulus;
    const BS::Retained_side side = (kind == BS::Blending_region_kind::Annulus && k % 4 == 0)
                                     ? BS::Retained_side::Inside
                                     : BS::Retained_side::Outside;
    cases.push_back(Region_case{random_ellipse(ns[k], kind, side).region(), "random ellipse"});
  }
  cases.push_back(Region_case{random_loop(5), "random loop N = 5"});
  cases.push_back(Region_case{random_loop(3), "random loop N = 3"});
  cases.push_back(Region_case{rounded_square(BS::Retained_side::Outside), "rounded square"});
  cases.push_back(Region_case{rounded_square(BS::Retained_side::Inside), "rounded square, inside kept"});
  // Clockwise control points: orientation -1.
  {
    std::vector<V2> cp;
    const BS::Blending_region& r = cases[0].region;
    for(std::size_t i = r.number_of_segments(); i-- > 0;)
      cp.push_back(r.control_point(i));
    std::vector<double> mu(cp.size());
    for(std::size_t i = 0; i < cp.size(); ++i)
      mu[i] = 1. - r.mu((2 * r.number_of_segments() - i) % r.number_of_segments());
    cases.push_back(Region_case{BS::Blending_region(cp, mu, r.half_width()), "clockwise ellipse"});
  }
  return cases;
}

// ---------------------------------------------------------------------------
// Bezier loop, normals, subdivision

void test_bezier(const std::vector<Region_case>& cases)
{
  double worst_split = 0.;
  for(const Region_case& rc : cases)
  {
    const BS::Blending_region& R = rc.region;
    const std::size_t n = R.number_of_segments();
    const double r = R.half_width();
    for(std::size_t i = 0; i < n; ++i)
    {
      const std::size_t j = (i + 1) % n, p = (i + n - 1) % n;
      // eq. 20, and the end points of eq. 21.
      const V2 ki = R.control_point(p) * (1. - R.mu(i)) + R.control_point(i) * R.mu(i);
      BS_CHECK((ki - R.vertex(i)).norm() < 1e-15, rc.what << ": eq. 20 at " << i);
      BS_CHECK((R.curve_point(i, 0.) - R.vertex(i)).norm() < 1e-15, rc.what << ": start of segment " << i);
      BS_CHECK((R.curve_point(i, 1.) - R.vertex(j)).norm() < 1e-15, rc.what << ": end of segment " << i);
      // Tangent to the control polygon at both ends, hence G1 across vertices.
      const V2 t0 = R.curve_tangent(i, 0.), t1 = R.curve_tangent(i, 1.);
      const V2 l0 = R.control_point(i) - R.vertex(i), l1 = R.vertex(j) - R.control_point(i);
      BS_CHECK(std::abs(t0.x() * l0.y() - t0.y() * l0.x()) < 1e-13 && t0.dot(l0) > 0., rc.what << ": tangent at start");
      BS_CHECK(std::abs(t1.x() * l1.y() - t1.y() * l1.x()) < 1e-13 && t1.dot(l1) > 0., rc.what << ": tangent at end");
      const V2 tp = R.curve_tangent(p, 1.).normalized();
      BS_CHECK((tp - t0.normalized()).norm() < 1e-12, rc.what << ": G1 at vertex " << i);
      // Normals: length r, orthogonal to the curve, and the middle normal
      // makes the offset polygon parallel (eq. 23).
      const V2 ni = R.normal(i), nj = R.normal(j), nc = R.middle_normal(i);
      BS_CHECK(std::abs(ni.norm() - r) < 1e-14 && std::abs(ni.dot(t0)) < 1e-13 * t0.norm(), rc.what << ": n_i");
      BS_CHECK(std::abs(nc.dot(ni.normalized()) - r) < 1e-13 && std::abs(nc.dot(nj.normalized()) - r) < 1e-13,
               rc.what << ": offset legs at distance r");
      const V2 ni_hat = ni / r, nj_hat = nj / r;
      const double sin_turn = std::abs(ni_hat.x() * nj_hat.y() - ni_hat.y() * nj_hat.x());
      if(sin_turn > 1e-3)
      {
        // The paper's formula, with the sign of the retained side.
        const V2 pi = (R.control_point(i) - R.vertex(i)).normalized(), pj = (R.control_point(i) - R.vertex(j)).normalized();
        V2 paper = r * (pi + pj) / sin_turn;
        if(paper.dot(ni + nj) < 0.)
          paper = -paper;
        BS_CHECK((paper - nc).norm() < 1e-12, rc.what << ": eq. 23 at segment " << i);
      }
      else if((ni - nj).norm() < 1e-14)
        BS_CHECK((nc - ni).norm() < 1e-14, rc.what << ": eq. 23, equal normals");
      // Normals point to the retained side.
      const V2 probe = R.curve_point(i, 0.5) + 1.5 * R.strip_jacobian(i, 0., 0.5).col(0);
      const BS::Region_location loc = R.locate(probe);
      BS_CHECK(loc.side == BS::Region_side::Retained, rc.what << ": normal toward the retained side");
    }

    // de Casteljau split leaves the curve unchanged.
    for(int trial = 0; trial < 3; ++trial)
    {
      const std::size_t i = std::size_t(uniform(0., double(n) - 1e-9));
      const double gs = uniform(0.05, 0.95);
      BS::Blending_region S = R;
      S.split_segment_at(i, gs);
      BS_CHECK(S.number_of_segments() == n + 1, "split adds one segment");
      for(int k = 0; k <= 200; ++k)
      {
        const double g = k / 200.;
        const V2 a = R.curve_point(i, g);
        const V2 b = (g <= gs) ? S.curve_point(i, g / gs) : S.curve_point(i + 1, (g - gs) / (1. - gs));
        worst_split = (std::max)(worst_split, (a - b).norm());
        // theta on the curve is unchanged too
        const double ta = R.make_coordinates(i, 0., g).theta;
        const double tb = (g <= gs) ? S.make_coordinates(i, 0., g / gs).theta
                                    : S.make_coordinates(i + 1, 0., (g - gs) / (1. - gs)).theta;
        BS_CHECK(std::abs(angle_difference(ta, tb)) < 1e-13, "theta after split");
      }
      for(std::size_t k = 1; k < n; ++k) // the other segments
      {
        const std::size_t a = (i + k) % n, b = (a > i) ? a + 1 : a;
        for(double g : {0., 0.3, 0.7, 1.})
          worst_split = (std::max)(worst_split, (R.curve_point(a, g) - S.curve_point(b, g)).norm());
      }
    }
  }
  BS_CHECK(worst_split <= 1e-14, "de Casteljau split moved the curve by " << worst_split);
  std::cout << "  de Casteljau split: max curve change " << worst_split << "\n";

  // Subdivision where a chart predicate flips: an ellipse crossing the unit
  // circle (e.g. the rim of a disk chart) and a vertical line.
  {
    const Ellipse e(Ellipse::make_parameters(0.7, 0.1, 0.6, 0.35, 0.4), 0.05, 8);
    const BS::Blending_region R0 = e.region();
    BS::Blending_region R = R0;
    auto chart_of = [](const V2& u) { return u.norm() < 1. ? 0 : 1; };
    const std::size_t splits = R.subdivide_where(chart_of, 1e-12);
    BS_CHECK(splits == 2, "expected 2 crossings of the unit circle, got " << splits);
    double worst_crossing = 0.;
    std::size_t on_circle = 0;
    for(std::size_t i = 0; i < R.number_of_segments(); ++i)
    {
      // Every piece lies in one chart (up to the tolerance at its ends).
      const int c = chart_of(R.curve_point(i, 0.5));
      for(int k = 1; k < 64; ++k)
        BS_CHECK(chart_of(R.curve_point(i, k / 64.)) == c, "piece " << i << " crosses the chart boundary");
      const double off = std::abs(R.vertex(i).norm() - 1.);
      if(off < 1e-6)
      {
        ++on_circle;
        worst_crossing = (std::max)(worst_crossing, off);
      }
    }
    BS_CHECK(on_circle == 2, on_circle << " vertices on the chart boundary");
    BS_CHECK(worst_crossing < 1e-11, "split points on the circle: " << worst_crossing);
    // Same curve, same theta along it.
    double worst = 0.;
    for(int k = 0; k < 1000; ++k)
    {
      const double t = 2. * M_PI * k / 1000.;
      worst = (std::max)(worst, (R0.strip_point_at_theta(0., t) - R.strip_point_at_theta(0., t)).norm());
    }
    BS_CHECK(worst < 1e-14, "subdivide_where moved the curve by " << worst);
    // The strip off the curve changes only a little (see split_segment_at()).
    double worst_d = 0.;
    for(int k = 0; k < 500; ++k)
    {
      const std::size_t i = std::size_t(uniform(0., 8. - 1e-9));
      const V2 u = R0.strip_point(i, uniform(-0.9, 0.9), uniform(0., 1.));
      const auto a = R0.strip_coordinates(u), b = R.strip_coordinates(u);
      BS_CHECK(a && b, "strip point lost by the subdivision");
      if(a && b)
        worst_d = (std::max)(worst_d, std::abs(a->d - b->d));
    }
    BS_CHECK(worst_d < 0.05, "subdivision changed d by " << worst_d);
    BS::Blending_region L = R0;
    const std::size_t line_splits = L.subdivide_where([](const V2& u) { return u.x() > 0.75; });
    BS_CHECK(line_splits == 2, "expected 2 crossings of x = 0.75, got " << line_splits);
    std::cout << "  subdivide_where: split points within " << worst_crossing
              << " of the chart boundary; d changed by at most " << worst_d << "\n";
  }
}

// ---------------------------------------------------------------------------
// Strip coordinates

// Brute force: Newton from a grid of starts in every segment, no hull test.
std::vector<std::pair<std::size_t, double>> brute_force_segments(const BS::Blending_region& R, const V2& u)
{
  std::vector<std::pair<std::size_t, double>> found;
  for(std::size_t i = 0; i < R.number_of_segments(); ++i)
  {
    bool done = false;
    for(int a = 0; a <= 2 && !done; ++a)
      for(int b = 0; b <= 4 && !done; ++b)
      {
        double d = -1. + a, g = b * 0.25;
        for(int it = 0; it < 30; ++it)
        {
          const V2 F = R.strip_point(i, d, g) - u;
          if(F.norm() < 1e-14)
            break;
          const Eigen::Matrix2d A = R.strip_jacobian(i, d, g);
          const double det = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
          d -= (A(1, 1) * F.x() - A(0, 1) * F.y()) / det;
          g -= (-A(1, 0) * F.x() + A(0, 0) * F.y()) / det;
          if(!std::isfinite(d) || std::abs(d) > 5. || std::abs(g) > 5.)
            break;
        }
        if(std::isfinite(d) && (R.strip_point(i, d, g) - u).norm() < 1e-12 && std::abs(d) <= 1. && g >= -1e-12 &&
           g <= 1. + 1e-12)
        {
          found.emplace_back(i, d);
          done = true;
        }
      }
  }
  return found;
}

void test_strip_coordinates(const std::vector<Region_case>& cases)
{
  double worst_inverse = 0., worst_residual = 0.;
  std::size_t total = 0, brute_checked = 0, in_strip = 0;
  for(const Region_case& rc : cases)
  {
    const BS::Blending_region& R = rc.region;
    const std::size_t n = R.number_of_segments();
    for(int k = 0; k < 2000; ++k)
    {
      const std::size_t i = std::size_t(uniform(0., double(n) - 1e-9));
      const double d = uniform(-1., 1.), g = uniform(0., 1.);
      const V2 u = R.strip_point(i, d, g);
      const std::optional<BS::Strip_coordinates> c = R.strip_coordinates(u);
      ++total;
      BS_CHECK(c.has_value(), rc.what << ": strip point (" << d << ", " << g << ") of segment " << i << " not found");
      if(!c)
        continue;
      worst_residual = (std::max)(worst_residual, (R.strip_point(c->segment, c->d, c->gamma) - u).norm());
      const double theta = R.make_coordinates(i, d, g).theta;
      if(c->segment == i)
        worst_inverse = (std::max)({worst_inverse, std::abs(c->d - d), std::abs(c->gamma - g)});
      else // a neighbour at a junction
      {
        const bool junction = (c->segment == (i + 1) % n && g > 1. - 1e-9) || (i == (c->segment + 1) % n && g < 1e-9);
        BS_CHECK(junction, rc.what << ": segment " << c->segment << " instead of " << i << " at gamma " << g);
        worst_inverse = (std::max)(worst_inverse, std::abs(c->d - d));
      }
      BS_CHECK(std::abs(angle_difference(c->theta, theta)) < 1e-9, rc.what << ": theta");
      BS_CHECK(c->theta >= 0. && c->theta < 2. * M_PI, "theta in [0, 2 pi)");
      if(k % 10 == 0)
        BS_CHECK(R.locate(u).side == BS::Region_side::Strip, "locate() in the strip");

      // Beyond the strip: |d| > 1 is not in the strip (locate() says Strip
      // exactly when strip_coordinates() finds the point), and the side is right.
      const double s = (k % 2) ? 1. : -1.;
      const V2 v = R.strip_point(i, s * uniform(1.001, 1.6), g);
      const BS::Region_location lv = R.locate(v);
      BS_CHECK(lv.side == (s > 0. ? BS::Region_side::Retained : BS::Region_side::Discarded),
               rc.what << ": side of a point beyond the strip");
    }

    // Segment lookup vs brute force, at random points around the region.
    V2 lo = R.vertex(0), hi = R.vertex(0);
    for(std::size_t i = 0; i < n; ++i)
      for(double g : {0., 0.25, 0.5, 0.75, 1.})
        for(double d : {-1.2, 1.2})
        {
          lo = lo.cwiseMin(R.strip_point(i, d, g));
          hi = hi.cwiseMax(R.strip_point(i, d, g));
        }
    for(int k = 0; k < 600; ++k)
    {
      const V2 u(uniform(lo.x(), hi.x()), uniform(lo.y(), hi.y()));
      const auto c = R.strip_coordinates(u);
      const auto brute = brute_force_segments(R, u);
      if(c && std::abs(std::abs(c->d) - 1.) < 1e-9)
        continue; // on the strip's edge: either answer is right
      ++brute_checked;
      BS_CHECK(c.has_value() == !brute.empty(), rc.what << ": lookup " << c.has_value() << " vs brute force "
                                                        << brute.size() << " at " << u.transpose());
      if(c && !brute.empty())
      {
        ++in_strip;
        bool listed = false;
        for(const auto& b : brute)
          if(b.first == c->segment)
          {
            listed = true;
            BS_CHECK(std::abs(b.second - c->d) < 1e-10, rc.what << ": d differs from brute force");
          }
        BS_CHECK(listed, rc.what << ": segment " << c->segment << " not among the brute-force ones");
        BS_CHECK(brute.size() == 1 || brute.size() == 2, "a point held by " << brute.size() << " segments");
      }
    }
  }
  BS_CHECK(worst_inverse < 1e-10, "inverse of eq. 24 off by " << worst_inverse);
  BS_CHECK(worst_residual < 1e-12, "C(d(u), gamma(u)) - u = " << worst_residual);
  std::cout << "  strip coordinates: " << total << " points, max |(d, gamma) error| " << worst_inverse
            << ", max |C(d, gamma) - u| " << worst_residual << "; lookup vs brute force at " << brute_checked
            << " points (" << in_strip << " in strips)\n";

  // The equal-normals case (rounded square): the straight pieces.
  {
    const BS::Blending_region R = rounded_square(BS::Retained_side::Outside);
    for(std::size_t i : {0, 2, 4, 6})
      BS_CHECK((R.middle_normal(i) - R.normal(i)).norm() == 0., "straight piece: n_{i(i+1)} = n_i exactly");
    const auto c = R.strip_coordinates(V2(0., 1.05));
    BS_CHECK(c && std::abs(c->d - 0.5) < 1e-14, "d on a straight piece");
  }

  // Far from the strip: the side agrees with the true ellipse, and alpha.
  {
    double r;
    const Ellipse e = random_ellipse(8, BS::Blending_region_kind::Disk, BS::Retained_side::Outside, &r);
    const Ellipse::Parameter_vector q = e.parameters();
    const Eigen::Matrix2d Rt = Eigen::Rotation2Dd(q[Ellipse::E_THETA]).toRotationMatrix().transpose();
    std::size_t far = 0;
    for(int k = 0; k < 4000; ++k)
    {
      const V2 u(uniform(-1.5, 1.5), uniform(-1.5, 1.5));
      const V2 l = Rt * (u - V2(q[Ellipse::E_U], q[Ellipse::E_V]));
      const double f = std::sqrt(l.x() * l.x() / (q[Ellipse::E_1] * q[Ellipse::E_1]) +
                                 l.y() * l.y() / (q[Ellipse::E_2] * q[Ellipse::E_2]));
      if(std::abs(f - 1.) * (std::min)(q[Ellipse::E_1], q[Ellipse::E_2]) < 2. * r)
        continue; // near the curve
      ++far;
      const bool inside = f < 1.;
      BS_CHECK(e.region().is_inside_curve(u) == inside, "winding number at " << u.transpose());
      const BS::Region_location loc = e.locate(u);
      BS_CHECK(loc.side == (inside ? BS::Region_side::Discarded : BS::Region_side::Retained), "disk sides");
      BS_CHECK(e.alpha(u) == (inside ? q[Ellipse::H] : 1.), "alpha = h inside a disk region, 1 outside");
    }
    BS_CHECK(far > 1000, "too few far points");
    const V2 center(q[Ellipse::E_U], q[Ellipse::E_V]);
    BS_CHECK(e.region().winding_number(center) == 1, "counterclockwise ellipse");
    BS_CHECK(e.region().locate(BS::Chart_point(0, center.x(), center.y())).side == BS::Region_side::Discarded,
             "Chart_point overload");
    // An annulus keeping the inside: sides swap, alpha = 0 on the discarded side.
    const Ellipse a(Ellipse::make_parameters(q[0], q[1], q[2], q[3], q[4], q[5], 0.), r, 8,
                    BS::Blending_region_kind::Annulus, BS::Retained_side::Inside);
    BS_CHECK(a.locate(center).side == BS::Region_side::Retained && a.alpha(center) == 1., "annulus, inside kept");
    const V2 outside = center + V2(3., 0.);
    BS_CHECK(a.locate(outside).side == BS::Region_side::Discarded && a.alpha(outside) == 0., "annulus discarded side");
  }
}

// ---------------------------------------------------------------------------
// Derivatives with respect to the region parameters (eq. 30)

struct Fd_result
{
  double d = 0., theta = 0., alpha = 0., wrong = HUGE_VAL;
  std::size_t points = 0;
};

// Values of (d, theta, alpha) at u, or nothing if u left the strip.
template <class Region>
std::optional<Eigen::Vector3d> strip_values(const Region& R, const V2& u)
{
  const auto c = R.strip_coordinates(u);
  if(!c)
    return std::nullopt;
  return Eigen::Vector3d(c->d, c->theta, R.alpha(u));
}

void check_ellipse_derivatives(const Ellipse& E, std::size_t points, Fd_result& res)
{
  const BS::Blending_region& R = E.region();
  const std::size_t n = R.number_of_segments();
  const bool annulus = E.kind() == BS::Blending_region_kind::Annulus;
  const Ellipse::Parameter_vector q0 = E.parameters();
  std::size_t done = 0;
  while(done < points)
  {
    // Away from segment junctions (theta is only C0 there) and from d = +-w
    // (alpha0 is only C1 there).
    const std::size_t i = std::size_t(uniform(0., double(n) - 1e-9));
    const double d = uniform(-0.95, 0.95), g = uniform(0.03, 0.97);
    if(std::abs(std::abs(d) - q0[Ellipse::W]) < 2e-3)
      continue;
    const V2 u = R.strip_point(i, d, g);
    const auto cg = E.strip_coordinates_and_gradient(u);
    const auto ag = E.alpha_and_gradient(u);
    BS_CHECK(cg && ag.location.side == BS::Region_side::Strip, "strip point");
    if(!cg)
      continue;
    BS_CHECK(std::abs(ag.alpha - E.alpha(u)) < 1e-15 && std::abs(cg->coordinates.d - d) < 1e-10, "values");
    Eigen::Matrix<double, 7, 1> fd_d, fd_t, fd_a;
    bool ok = true;
    for(int j = 0; j < 7 && ok; ++j)
    {
      if(j == Ellipse::H && annulus)
      {
        fd_d[j] = fd_t[j] = fd_a[j] = 0.; // h is fixed to 0 on an annulus
        continue;
      }
      const double step = 1e-6 * (std::max)(1., std::abs(q0[j]));
      Ellipse Ep = E, Em = E;
      Ellipse::Parameter_vector qp = q0, qm = q0;
      qp[j] += step;
      qm[j] -= step;
      Ep.set_parameters(qp);
      Em.set_parameters(qm);
      const auto vp = strip_values(Ep, u), vm = strip_values(Em, u);
      if(!vp || !vm)
      {
        ok = false;
        break;
      }
      fd_d[j] = ((*vp)[0] - (*vm)[0]) / (2. * step);
      fd_t[j] = angle_difference((*vp)[1], (*vm)[1]) / (2. * step);
      fd_a[j] = ((*vp)[2] - (*vm)[2]) / (2. * step);
    }
    BS_CHECK(ok, "a strip point left the strip under a tiny parameter change");
    if(!ok)
      continue;
    res.d = (std::max)(res.d, gradient_error(cg->d_gradient, fd_d));
    res.theta = (std::max)(res.theta, gradient_error(cg->theta_gradient, fd_t));
    res.alpha = (std::max)(res.alpha, gradient_error(ag.gradient, fd_a));
    // A deliberately wrong derivative: d d / d e_1 and d d / d e_2 swapped.
    Ellipse::Parameter_vector wrong = cg->d_gradient;
    std::swap(wrong[Ellipse::E_1], wrong[Ellipse::E_2]);
    if(std::abs(fd_d[Ellipse::E_1] - fd_d[Ellipse::E_2]) > 1e-2 * fd_d.cwiseAbs().maxCoeff())
      res.wrong = (std::min)(res.wrong, gradient_error(wrong, fd_d));
    ++done;
    ++res.points;
  }
}

void test_derivatives()
{
  Fd_result ellipse;
  const std::size_t ns[] = {4, 6, 8, 8, 12};
  for(std::size_t k = 0; k < 5; ++k)
  {
    const BS::Blending_region_kind kind = (k % 2) ? BS::Blending_region_kind::Annulus : BS::Blending_region_kind::Disk;
    const BS::Retained_side side =
      (k == 1) ? BS::Retained_side::Inside : BS::Retained_side::Outside;
    check_ellipse_derivatives(random_ellipse(ns[k], kind, side), 105, ellipse);
  }
  BS_CHECK(ellipse.points >= 500, "only " << ellipse.points << " points checked");
  BS_CHECK(ellipse.d < 1e-6, "d d / d q_b vs finite differences: " << ellipse.d);
  BS_CHECK(ellipse.theta < 1e-6, "d theta / d q_b vs finite differences: " << ellipse.theta);
  BS_CHECK(ellipse.alpha < 1e-6, "d alpha / d q_b vs finite differences: " << ellipse.alpha);
  BS_CHECK(ellipse.wrong > 1e-3, "swapped d d / d e1, d e2 went unnoticed: " << ellipse.wrong);
  std::cout << "  ellipse region (7 parameters), " << ellipse.points << " points: max relative error d "
            << ellipse.d << ", theta " << ellipse.theta << ", alpha " << ellipse.alpha
            << " (a wrong derivative shows " << ellipse.wrong << ")\n";

  // The general loop: 3N + 2 parameters (control points, mu, w, h).
  double worst_d = 0., worst_t = 0., worst_a = 0.;
  std::size_t pts = 0;
  for(std::size_t n : {3, 5, 7})
  {
    const BS::Blending_region R = random_loop(n);
    const Eigen::VectorXd q0 = R.parameters();
    const Eigen::Index P = q0.size();
    BS_CHECK(std::size_t(P) == 3 * n + 2, "3N + 2 parameters");
    for(int k = 0; k < 40; ++k)
    {
      const std::size_t i = std::size_t(uniform(0., double(n) - 1e-9));
      const double d = uniform(-0.95, 0.95), g = uniform(0.03, 0.97);
      if(std::abs(std::abs(d) - R.w()) < 2e-3)
        continue;
      const V2 u = R.strip_point(i, d, g);
      const auto cg = R.strip_coordinates_and_gradient(u);
      const auto ag = R.alpha_and_gradient(u);
      if(!cg)
      {
        BS_CHECK(false, "strip point not found");
        continue;
      }
      Eigen::VectorXd fd_d(P), fd_t(P), fd_a(P);
      for(Eigen::Index j = 0; j < P; ++j)
      {
        const double step = 1e-6 * (std::max)(1., std::abs(q0[j]));
        BS::Blending_region Rp = R, Rm = R;
        Eigen::VectorXd qp = q0, qm = q0;
        qp[j] += step;
        qm[j] -= step;
        Rp.set_parameters(qp);
        Rm.set_parameters(qm);
        const auto vp = strip_values(Rp, u), vm = strip_values(Rm, u);
        BS_CHECK(vp && vm, "left the strip");
        if(!vp || !vm)
          return;
        fd_d[j] = ((*vp)[0] - (*vm)[0]) / (2. * step);
        fd_t[j] = angle_difference((*vp)[1], (*vm)[1]) / (2. * step);
        fd_a[j] = ((*vp)[2] - (*vm)[2]) / (2. * step);
      }
      worst_d = (std::max)(worst_d, gradient_error(cg->d_gradient, fd_d));
      worst_t = (std::max)(worst_t, gradient_error(cg->theta_gradient, fd_t));
      worst_a = (std::max)(worst_a, gradient_error(ag.gradient, fd_a));
      ++pts;
    }
  }
  BS_CHECK(worst_d < 1e-6 && worst_t < 1e-6 && worst_a < 1e-6,
           "general loop derivatives: d " << worst_d << ", theta " << worst_t << ", alpha " << worst_a);
  std::cout << "  general loop (3N + 2 parameters), " << pts << " points: max relative error d " << worst_d
            << ", theta " << worst_t << ", alpha " << worst_a << "\n";

  // Outside the strip: only w (never) and h (disk interior) act on alpha.
  const Ellipse E = random_ellipse(8, BS::Blending_region_kind::Disk, BS::Retained_side::Outside);
  const V2 c(E.parameters()[Ellipse::E_U], E.parameters()[Ellipse::E_V]);
  const auto inside = E.alpha_and_gradient(c);
  Ellipse::Parameter_vector expect = Ellipse::Parameter_vector::Zero();
  expect[Ellipse::H] = 1.;
  BS_CHECK(inside.location.side == BS::Region_side::Discarded && inside.gradient == expect,
           "disk interior: alpha = h, gradient e_h");
  const auto outside = E.alpha_and_gradient(c + V2(5., 5.));
  BS_CHECK(outside.alpha == 1. && outside.gradient.isZero(), "retained side: alpha = 1, zero gradient");
}

// ---------------------------------------------------------------------------
// The ellipse loop approximates the ellipse

double distance_to_ellipse(const V2& local, double e1, double e2)
{
  double best_t = 0., best = HUGE_VAL;
  for(int k = 0; k < 720; ++k)
  {
    const double t = 2. * M_PI * k / 720.;
    const double dx = e1 * std::cos(t) - local.x(), dy = e2 * std::sin(t) - local.y();
    const double dist = dx * dx + dy * dy;
    if(dist < best)
    {
      best = dist;
      best_t = t;
    }
  }
  double t = best_t;
  for(int it = 0; it < 30; ++it) // Newton on (E(t) - p) . E'(t) = 0
  {
    const V2 E(e1 * std::cos(t), e2 * std::sin(t)), E1(-e1 * std::sin(t), e2 * std::cos(t));
    const V2 E2(-e1 * std::cos(t), -e2 * std::sin(t));
    const double f = (E - local).dot(E1), fp = E1.squaredNorm() + (E - local).dot(E2);
    if(!(fp > 0.))
      break;
    t -= f / fp;
  }
  return (std::min)(std::sqrt(best), (V2(e1 * std::cos(t), e2 * std::sin(t)) - local).norm());
}

void test_ellipse_approximation()
{
  double worst8 = 0., worst4 = 0.;
  for(int k = 0; k < 12; ++k)
  {
    const double e1 = uniform(0.2, 0.8), e2 = e1 * uniform(0.5, 2.), et = uniform(-3., 3.);
    const V2 center(uniform(-0.3, 0.3), uniform(-0.3, 0.3));
    for(std::size_t n : {4, 8})
    {
      const Ellipse E(Ellipse::make_parameters(center.x(), center.y(), e1, e2, et), 0.01 * (std::min)(e1, e2), n);
      const BS::Blending_region& R = E.region();
      const Eigen::Matrix2d Rt = Eigen::Rotation2Dd(et).toRotationMatrix().transpose();
      double worst = 0.;
      for(std::size_t i = 0; i < n; ++i)
      {
        BS_CHECK((R.vertex(i) - E.ellipse_point(R.theta(i))).norm() < 1e-14, "k_i on the ellipse at theta_i");
        for(int s = 0; s <= 100; ++s)
          worst = (std::max)(worst, distance_to_ellipse(Rt * (R.curve_point(i, s / 100.) - center), e1, e2));
      }
      const double rel = worst / (std::min)(e1, e2);
      (n == 8 ? worst8 : worst4) = (std::max)(n == 8 ? worst8 : worst4, rel);
    }
  }
  BS_CHECK(worst8 < 0.01, "N = 8 loop is " << worst8 << " of the small axis away from the ellipse");
  std::cout << "  ellipse loop: max distance / min(e1, e2) = " << worst8 << " (N = 8), " << worst4 << " (N = 4)\n";

  // The circle: the midpoint error of a quadratic arc of angle pi/4 is
  // (cos(pi/8) + 1/cos(pi/8))/2 - 1 of the radius.
  const Ellipse C(Ellipse::make_parameters(0., 0., 1., 1., 0.), 0.1, 8);
  const double expected = 0.5 * (std::cos(M_PI / 8.) + 1. / std::cos(M_PI / 8.)) - 1.;
  BS_CHECK(std::abs(C.region().curve_point(0, 0.5).norm() - 1. - expected) < 1e-14, "circle arc midpoint");
}

// ---------------------------------------------------------------------------
// Bad inputs

void test_bad_inputs()
{
  const Ellipse::Parameter_vector q = Ellipse::make_parameters(0., 0., 0.5, 0.3, 0.2, 0.5, 0.5);
  BS_CHECK(!throws_invalid([&] { Ellipse e(q, 0.03, 4); }), "a valid ellipse region");
  BS_CHECK(throws_invalid([&] { Ellipse e(q, 0.03, 3); }), "N = 3 ellipse accepted");
  BS_CHECK(throws_invalid([&] { Ellipse e(q, 0., 8); }), "r = 0 accepted");
  BS_CHECK(throws_invalid([&] { Ellipse e(q, -0.1, 8); }), "r < 0 accepted");
  BS_CHECK(throws_invalid([&] { Ellipse e(q, std::nan(""), 8); }), "r = NaN accepted");
  BS_CHECK(throws_invalid([&] { Ellipse e(q, 0.25, 8); }), "r larger than the radius of curvature accepted");
  for(int j = 0; j < 7; ++j)
  {
    Ellipse::Parameter_vector b = q;
    b[j] = std::nan("");
    BS_CHECK(throws_invalid([&] { Ellipse e(b, 0.03, 8); }), "NaN in parameter " << Ellipse::parameter_name(j));
    b[j] = HUGE_VAL;
    BS_CHECK(throws_invalid([&] { Ellipse e(b, 0.03, 8); }), "infinity in parameter " << Ellipse::parameter_name(j));
  }
  for(double w : {0., -0.5, 1.5})
  {
    Ellipse::Parameter_vector b = q;
    b[Ellipse::W] = w;
    BS_CHECK(throws_invalid([&] { Ellipse e(b, 0.03, 8); }), "w = " << w << " accepted");
  }
  for(double h : {-0.1, 1.1})
  {
    Ellipse::Parameter_vector b = q;
    b[Ellipse::H] = h;
    BS_CHECK(throws_invalid([&] { Ellipse e(b, 0.03, 8); }), "h = " << h << " accepted");
  }
  {
    Ellipse::Parameter_vector b = q;
    b[Ellipse::E_2] = 0.;
    BS_CHECK(throws_invalid([&] { Ellipse e(b, 0.03, 8); }), "zero axis accepted");
  }
  BS_CHECK(throws_invalid([&] { Ellipse e(q, 0.03, 8, BS::Blending_region_kind::Annulus); }),
           "h != 0 on an annulus accepted");
  BS_CHECK(throws_invalid([&] { Ellipse e(q, 0.03, 8, BS::Blending_region_kind::Disk, BS::Retained_side::Inside); }),
           "a disk region keeping its inside accepted");
  BS_CHECK(throws_invalid([&] { Ellipse e(q, 0.03, 4, BS::Blending_region_kind::Disk, BS::Retained_side::Outside,
                                          {0., 0.5, 1., 1.5}); }),
           "theta gaps above pi/2 accepted");
  // set_parameters keeps the old state when it throws.
  Ellipse e(q, 0.03, 8);
  Ellipse::Parameter_vector b = q;
  b[Ellipse::E_1] = -1.;
  BS_CHECK(throws_invalid([&] { e.set_parameters(b); }) && e.parameters() == q, "set_parameters is atomic");

  // General loops.
  const std::vector<V2> tri = {V2(1, 0), V2(-0.5, 0.9), V2(-0.5, -0.9)};
  const std::vector<double> half(3, 0.5);
  BS_CHECK(!throws_invalid([&] { BS::Blending_region r(tri, half, 0.02); }), "a valid triangle loop");
  BS_CHECK(throws_invalid([&] { BS::Blending_region r({V2(0, 0), V2(1, 0)}, {0.5, 0.5}, 0.02); }), "N = 2 accepted");
  BS_CHECK(throws_invalid([&] { BS::Blending_region r(tri, {0.5, 0.5}, 0.02); }), "missing mu accepted");
  BS_CHECK(throws_invalid([&] { BS::Blending_region r(tri, {0.5, 0., 0.5}, 0.02); }), "mu = 0 accepted");
  BS_CHECK(throws_invalid([&] { BS::Blending_region r(tri, {0.5, 1.2, 0.5}, 0.02); }), "mu > 1 accepted");
  BS_CHECK(throws_invalid([&] { BS::Blending_region r(tri, half, 0.); }), "r = 0 accepted");
  BS_CHECK(throws_invalid([&] { BS::Blending_region r(tri, half, 1.); }), "folding strip accepted");
  BS_CHECK(throws_invalid([&] { BS::Blending_region r({V2(1, 0), V2(std::nan(""), 0.9), V2(-0.5, -0.9)}, half, 0.02); }),
           "NaN control point accepted");
  BS_CHECK(throws_invalid([&] { BS::Blending_region r({V2(0, 0), V2(1, 0), V2(2, 0)}, half, 0.02); }),
           "a flat loop accepted");
  BS_CHECK(throws_invalid([&] {
             BS::Blending_region r(tri, half, 0.02, BS::Blending_region_kind::Annulus, BS::Retained_side::Outside,
                                   BS::Blending_function(), {0., 2., 1.});
           }),
           "decreasing theta accepted");
  BS::Blending_region r(tri, half, 0.02);
  BS_CHECK(throws_invalid([&] { r.locate(V2(std::nan(""), 0.)); }), "NaN chart point located");
  BS_CHECK(throws_invalid([&] { r.alpha(V2(0., HUGE_VAL)); }), "alpha at an infinite chart point");
  BS_CHECK(throws_invalid([&] { r.set_h(0.5); }) && r.h() == 0., "h on an annulus");
  BS_CHECK(throws_invalid([&] { r.split_segment_at(0, 1.); }) && r.number_of_segments() == 3, "split at gamma = 1");
  BS_CHECK(throws_invalid([&] { r.split_segment_at(3, 0.5); }), "split of a segment that does not exist");
  BS_CHECK(throws_invalid([&] { r.set_half_width(5.); }) && r.half_width() == 0.02, "set_half_width is atomic");
  BS_CHECK(throws_invalid([&] { r.set_parameters(Eigen::VectorXd::Zero(4)); }), "wrong parameter count");
  r.set_kind(BS::Blending_region_kind::Disk);
  r.set_h(0.5);
  BS_CHECK(throws_invalid([&] { r.set_kind(BS::Blending_region_kind::Annulus); }), "annulus with h = 0.5");
  BS_CHECK(throws_invalid([&] { r.set_retained_side(BS::Retained_side::Inside); }), "disk keeping its inside");
}

// Every check of this part.
void run_all()
{
  test_blending_function();
  const std::vector<Region_case> cases = regions_for_coordinates();
  test_bezier(cases);
  test_strip_coordinates(cases);
  test_derivatives();
  test_ellipse_approximation();
  test_bad_inputs();
}

} // namespace blending_region_checks

#endif // BLENDED_SHAPE_BLENDING_REGION_CHECKS_H
