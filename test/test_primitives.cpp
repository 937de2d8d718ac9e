// SPDX-License-Identifier: LGPL-3.0-or-later
// Superquadric primitives, their charts and chart meshes, their parameter
// and chart Jacobians, the generic checkers, quaternion derivatives and the
// moment initialization, with both supported kernels.
#include "test_util.h"

#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model.h>
#include <CGAL/Blended_shape/Primitives/Hole_component.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_toroid.h>
#include <CGAL/Blended_shape/Primitives/check_primitive.h>
#include <CGAL/Blended_shape/Fitting/initialize_from_moments.h>
#include <CGAL/Blended_shape/internal/quaternion.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Polygon_mesh_processing/border.h>

#include <algorithm>
#include <random>
#include <sstream>
#include <typeinfo>
#include <vector>

namespace BS = CGAL::Blended_shapes;

namespace {

template <class Primitive>
std::vector<BS::Chart_point> test_points(const Primitive& p, std::size_t per_chart, std::mt19937_64& rng,
                                         const std::vector<BS::Chart_point>& special)
{
  std::vector<BS::Chart_point> pts = special;
  for(std::size_t c = 0; c < p.number_of_charts(); ++c)
    for(std::size_t i = 0; i < per_chart; ++i)
      pts.push_back(BS::random_chart_point(p, c, rng));
  return pts;
}

// Poles, the equator, the outer edge of the margin, and the coordinate axes
// of the chart (cos omega = 0 or sin omega = 0), on both charts.
std::vector<BS::Chart_point> ellipsoid_special_points(double margin)
{
  std::vector<BS::Chart_point> s;
  for(std::size_t c = 0; c < 2; ++c)
    for(double r : {0., 0.25, 1. - margin, 1., 1. + margin})
      for(int k = 0; k < 8; ++k)
      {
        const double a = k * M_PI / 4.;
        s.emplace_back(c, r * std::cos(a), r * std::sin(a));
        s.emplace_back(c, k < 4 ? 0. : r, k < 4 ? r : 0.);
      }
  return s;
}

std::vector<BS::Chart_point> toroid_special_points()
{
  std::vector<BS::Chart_point> s;
  for(int i = 0; i < 8; ++i)
    for(int j = 0; j < 8; ++j)
      s.emplace_back(0, i * M_PI / 4., j * M_PI / 4.);
  return s;
}

template <class Primitive>
void check_primitive_jacobians(const Primitive& p, const std::vector<BS::Chart_point>& pts, const std::string& label)
{
  const BS::Jacobian_check_report r = BS::check_jacobian(p, pts);
  std::ostringstream where;
  where << label << " q = " << p.parameters().transpose() << ": worst parameter "
        << r.worst_parameter << " at chart " << r.worst_point.chart << " (" << r.worst_point.x << ", "
        << r.worst_point.y << "), error " << r.max_relative_error;
  BS::Chart_point u;
  BS_CHECK(r.points_checked == pts.size(), where.str());
  BS_CHECK(!r.has_non_finite, where.str());
  BS_CHECK(r.max_relative_error < 1e-6, where.str());
}

// A deliberately wrong Jacobian must be caught: the checker can fail.
template <class K>
struct Wrong_jacobian_ellipsoid : BS::Superquadric_ellipsoid<K>
{
  typedef BS::Superquadric_ellipsoid<K> Base;
  using Base::Base;
  typename Base::Point_3 point_and_jacobian(const BS::Chart_point& p, typename Base::Jacobian& J) const
  {
    const typename Base::Point_3 s = Base::point_and_jacobian(p, J);
    J(2, Base::E1) *= 1.0001;
    return s;
  }
};

// Chart Jacobians (point_and_chart_jacobian()) against finite differences.
//
// The accuracy check (relative error < 1e-6, step 1e-5) excludes the chart
// points within kChartMargin (in chart coordinates) of the loci where a signed
// power meets a zero of its cosine or sine: there the map is not
// differentiable for exponents other than 1 (for exponents below 1 the
// derivative is unbounded), and nearby the central differences themselves are
// off by about (step / distance)^2 |(e - 1)(e - 2)| / 6, under 1e-8 at a
// distance of 0.05. The loci are the chart axes x = 0 and y = 0 (longitude a
// multiple of pi/2) and the equator rho = 1 for the ellipsoid, which also keeps
// 0.05 from the pole; the lines where u or v is a multiple of pi/2 for the
// toroid and the hole's tube (|cos|, |sin| >= 0.05 there); the chart axes, the
// centre and the rim for the hole's disks. Every point, on those loci too (the
// special points: poles, axes, equator, rims, pinch, centres), is checked for
// NaN and infinity.
constexpr double kChartMargin = 0.05;

bool away_from_zero(double c) { return std::abs(c) >= kChartMargin; }

bool ellipsoid_smooth_at(const BS::Chart_point& p)
{
  return away_from_zero(p.x) && away_from_zero(p.y) && away_from_zero(std::hypot(p.x, p.y) - 1.);
}

// Toroid chart point (x, y) = (v, u).
bool toroid_smooth_at(const BS::Chart_point& p)
{
  return away_from_zero(std::cos(p.x)) && away_from_zero(std::sin(p.x)) && away_from_zero(std::cos(p.y)) &&
         away_from_zero(std::sin(p.y));
}

// n random chart points of each chart, kept where `smooth(p)` holds.
template <class Primitive, class Smooth>
std::vector<BS::Chart_point> smooth_points(const Primitive& p, std::size_t per_chart, std::mt19937_64& rng,
                                           const Smooth& smooth)
{
  std::vector<BS::Chart_point> pts;
  for(std::size_t c = 0; c < p.number_of_charts(); ++c)
    for(std::size_t i = 0; i < per_chart;)
    {
      const BS::Chart_point u = BS::random_chart_point(p, c, rng);
      if(smooth(u))
      {
        pts.push_back(u);
        ++i;
      }
    }
  return pts;
}

// `smooth`: the accuracy check; `anywhere`: finiteness only.
template <class Primitive>
BS::Chart_jacobian_check_report check_chart_jacobians(const Primitive& p, const std::vector<BS::Chart_point>& smooth,
                                                      const std::vector<BS::Chart_point>& anywhere,
                                                      const std::string& label)
{
  const BS::Chart_jacobian_check_report r = BS::check_chart_jacobian(p, smooth);
  std::ostringstream where;
  where << label << " q = " << p.parameters().transpose() << ": worst column " << r.worst_column << " at chart "
        << r.worst_point.chart << " (" << r.worst_point.x << ", " << r.worst_point.y << "), error "
        << r.max_relative_error;
  BS_CHECK(r.points_checked == smooth.size() && r.points_checked >= 1000, where.str());
  BS_CHECK(r.skipped_columns == 0, where.str() << ", skipped columns " << r.skipped_columns);
  BS_CHECK(!r.has_non_finite, where.str());
  BS_CHECK(r.max_relative_error < 1e-6, where.str());
  const BS::Chart_jacobian_check_report all = BS::check_chart_jacobian(p, anywhere);
  BS_CHECK(!all.has_non_finite && all.points_checked == anywhere.size(),
           label << " q = " << p.parameters().transpose() << ": NaN or infinity in the chart Jacobian");
  return r;
}

template <class K>
void check_ellipsoid_chart_jacobian(const BS::Superquadric_ellipsoid<K>& ell, std::mt19937_64& rng)
{
  std::vector<BS::Chart_point> smooth =
    smooth_points(ell, 1000, rng, ellipsoid_smooth_at);
  // On the rim of both charts, away from the axes: one-sided differences.
  const double rim = 1. + ell.chart_margin();
  for(std::size_t c = 0; c < 2; ++c)
    for(double a : {0.5, 2., 2.5, 4., 5.5})
      smooth.emplace_back(c, rim * std::cos(a), rim * std::sin(a));
  const auto r = check_chart_jacobians(ell, smooth, test_points(ell, 200, rng, ellipsoid_special_points(ell.chart_margin())),
                                       "ellipsoid chart Jacobian");
  BS_CHECK(r.one_sided_columns >= 20, "one-sided differences on the rim: " << r.one_sided_columns);
}

template <class K>
void check_toroid_chart_jacobian(const BS::Superquadric_toroid<K>& tor, std::mt19937_64& rng, const std::string& label)
{
  check_chart_jacobians(tor, smooth_points(tor, 1000, rng, toroid_smooth_at),
                        test_points(tor, 200, rng, toroid_special_points()), label);
}

// Both domains of the hole (Two_disks only while it is closed), chained
// through toroid_chart_point(); the special points are the glue circles
// r = +-1, the middle circle r = 0 and the disk centres.
template <class K>
void check_hole_chart_jacobian(BS::Hole_component<K> hole, std::mt19937_64& rng)
{
  std::vector<BS::Hole_domain> domains = {BS::Hole_domain::Tube};
  if(hole.hole_is_closed())
    domains.push_back(BS::Hole_domain::Two_disks);
  for(BS::Hole_domain d : domains)
  {
    hole.set_domain(d);
    std::vector<BS::Chart_point> special;
    for(int k = 0; k < 8; ++k)
    {
      const double t = k * M_PI / 4.;
      if(d == BS::Hole_domain::Tube)
        for(double r : {-1., -0.5, 0., 0.5, 1.})
          special.emplace_back(0, t, r);
      else
        for(std::size_t c = 0; c < 2; ++c)
          for(double r : {0., 1e-300, 1e-17, 0.5, 1.})
            special.emplace_back(c, r * std::cos(t), r * std::sin(t));
    }
    check_chart_jacobians(hole,
                          smooth_points(hole, 1000, rng,
                                        [&](const BS::Chart_point& u) {
                                          return toroid_smooth_at(hole.toroid_chart_point(u)) &&
                                                 (d == BS::Hole_domain::Tube || ellipsoid_smooth_at(u));
                                        }),
                          test_points(hole, 200, rng, special),
                          d == BS::Hole_domain::Tube ? "hole (tube) chart Jacobian" : "hole (two disks) chart Jacobian");
  }
}

// A deliberately wrong chart Jacobian must be caught.
template <class K>
struct Wrong_chart_jacobian_ellipsoid : BS::Superquadric_ellipsoid<K>
{
  typedef BS::Superquadric_ellipsoid<K> Base;
  using Base::Base;
  typename Base::Point_3 point_and_chart_jacobian(const BS::Chart_point& p, typename Base::Chart_jacobian& D) const
  {
    const typename Base::Point_3 s = Base::point_and_chart_jacobian(p, D);
    D(2, 1) *= 1.0001;
    return s;
  }
};

template <class K>
void test_chart_jacobian_special_cases(std::mt19937_64& rng)
{
  // The derivative of the signed power: within 1e-6 of 0 the one at 1e-6
  // (a cap for e < 1, a non-zero slope for e > 1), exact elsewhere.
  const double floor = BS::internal::signed_power_derivative_floor;
  for(double e : {0.01, 0.3, 1., 1.5, 2.})
  {
    const double d0 = BS::internal::signed_pow_derivative(0., e);
    BS_CHECK(std::isfinite(d0) && d0 > 0. && std::abs(d0 - e * std::pow(floor, e - 1.)) <= 1e-15 * d0 &&
               BS::internal::signed_pow_derivative(-0.3 * floor, e) == d0,
             "derivative of the signed power at 0, e = " << e << ": " << d0);
    BS_CHECK(std::abs(BS::internal::signed_pow_derivative(-1e-3, e) - e * std::pow(1e-3, e - 1.)) <=
               1e-14 * e * std::pow(1e-3, e - 1.), "derivative of the signed power at -1e-3, e = " << e);
  }
  double d = 0.;
  const double v = BS::internal::signed_pow_and_derivative(-0.3, 0.7, d);
  BS_CHECK(std::abs(v + std::pow(0.3, 0.7)) < 1e-15 && std::abs(d - 0.7 * std::pow(0.3, -0.3)) < 1e-14,
           "signed_pow_and_derivative: " << v << ", " << d);

  // The lowest exponents: finite on every locus.
  const BS::Superquadric_ellipsoid<K> flat(1., 2., 0.5, 0.01, 0.01);
  BS_CHECK(!BS::check_chart_jacobian(flat, ellipsoid_special_points(flat.chart_margin())).has_non_finite,
           "ellipsoid with e = 0.01");
  const BS::Superquadric_toroid<K> flat_torus(1., 2., 0.5, 1., 1., 0.01, 0.01);
  BS_CHECK(!BS::check_chart_jacobian(flat_torus, toroid_special_points()).has_non_finite, "toroid with e = 0.01");

  // At the pole the columns are the partial derivatives along the chart axes:
  // (pi/2) (a1, 0, 0) and (pi/2) (0, +-a2, 0) for e1 = 1, whatever e2.
  const BS::Superquadric_ellipsoid<K> ell(1., 2., 0.5, 1., 0.4);
  for(std::size_t c = 0; c < 2; ++c)
  {
    typename BS::Superquadric_ellipsoid<K>::Chart_jacobian D;
    ell.point_and_chart_jacobian(BS::Chart_point(c, 0., 0.), D);
    Eigen::Matrix<double, 3, 2> expected;
    expected << 1., 0., 0., (c == 0 ? 2. : -2.), 0., 0.;
    BS_CHECK((D - 0.5 * M_PI * expected).norm() < 1e-15, "pole of chart " << c << ":\n" << D);
    // the one-sided difference along each axis agrees
    const double h = 1e-7;
    const auto s0 = ell.point(BS::Chart_point(c, 0., 0.)), sx = ell.point(BS::Chart_point(c, h, 0.)),
               sy = ell.point(BS::Chart_point(c, 0., h));
    BS_CHECK(std::abs((sx.x() - s0.x()) / h - D(0, 0)) < 1e-6 && std::abs((sy.y() - s0.y()) / h - D(1, 1)) < 1e-6,
             "one-sided differences at the pole");
  }
  // The point is the same as point() (the projection compares both).
  std::vector<BS::Chart_point> pts = test_points(ell, 100, rng, ellipsoid_special_points(ell.chart_margin()));
  const BS::Superquadric_toroid<K> tor(1., 2., 0.5, 1.5, 2.5, 0.3, 1.7);
  bool same = true;
  for(const BS::Chart_point& u : pts)
  {
    typename BS::Superquadric_ellipsoid<K>::Chart_jacobian D;
    same = same && ell.point_and_chart_jacobian(u, D) == ell.point(u);
  }
  for(const BS::Chart_point& u : test_points(tor, 100, rng, toroid_special_points()))
  {
    typename BS::Superquadric_toroid<K>::Chart_jacobian D;
    same = same && tor.point_and_chart_jacobian(u, D) == tor.point(u);
  }
  BS_CHECK(same, "point_and_chart_jacobian() and point() disagree");

  // The placed model: R times the shape's chart Jacobian.
  const BS::Deformable_model<BS::Superquadric_ellipsoid<K>> model(
    BS::Superquadric_ellipsoid<K>(1.2, 0.7, 2., 0.6, 1.4), Eigen::Vector3d(1., -2., 3.), Eigen::Vector4d(0.3, -0.5, 0.2, 0.8));
  const auto rm = BS::check_chart_jacobian(model, smooth_points(model.shape(), 500, rng, ellipsoid_smooth_at));
  BS_CHECK(!rm.has_non_finite && rm.max_relative_error < 1e-6, "Deformable_model chart Jacobian: " << rm.max_relative_error);

  // The checker catches a wrong column.
  const Wrong_chart_jacobian_ellipsoid<K> wrong(1., 2., 3., 0.7, 0.8);
  const auto rw = BS::check_chart_jacobian(wrong, smooth_points(wrong, 100, rng, ellipsoid_smooth_at));
  BS_CHECK(rw.max_relative_error > 1e-5 && rw.worst_column == 1,
           "the chart Jacobian checker missed a wrong column: " << rw.max_relative_error << ", column " << rw.worst_column);
}

template <class K>
void test_jacobians(std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> size(0.3, 3.), expo(0.1, 2.), ring(1., 4.);
  std::vector<std::array<double, 2>> exponents = {{{1., 1.}}, {{0.1, 0.1}}, {{2., 2.}}, {{0.1, 2.}}, {{2., 0.1}}};
  for(int i = 0; i < 5; ++i)
    exponents.push_back({{expo(rng), expo(rng)}});
  std::mt19937_64 chart_rng(17);
  for(const auto& e : exponents)
  {
    const BS::Superquadric_ellipsoid<K> ell(size(rng), size(rng), size(rng), e[0], e[1]);
    check_primitive_jacobians(ell, test_points(ell, 600, rng, ellipsoid_special_points(ell.chart_margin())),
                              "ellipsoid");
    const BS::Superquadric_toroid<K> tor(size(rng), size(rng), size(rng), ring(rng), ring(rng), e[0], e[1]);
    check_primitive_jacobians(tor, test_points(tor, 1100, rng, toroid_special_points()), "toroid");
    // The chart Jacobians of the same shapes, and of holes with these exponents (open and closed).
    // (Their own random engine: the shapes drawn from `rng` stay those of the parameter checks.)
    check_ellipsoid_chart_jacobian(ell, chart_rng);
    check_toroid_chart_jacobian(tor, chart_rng, "toroid chart Jacobian");
    const auto& qt = tor.parameters();
    check_hole_chart_jacobian(BS::Hole_component<K>(qt[0], qt[1], qt[2], qt[3], qt[4], e[0], e[1], BS::Hole_domain::Tube),
                              chart_rng);
    check_hole_chart_jacobian(BS::Hole_component<K>(qt[0], qt[1], qt[2], 1., 1., e[0], e[1]), chart_rng);
  }
  // a4 = a5 = 1: the pinched toroid of the hole blend
  const BS::Superquadric_toroid<K> pinched(1., 1.2, 0.8, 1., 1., 0.7, 1.3);
  check_primitive_jacobians(pinched, test_points(pinched, 1000, rng, toroid_special_points()), "pinched toroid");
  check_toroid_chart_jacobian(pinched, chart_rng, "pinched toroid chart Jacobian");
  test_chart_jacobian_special_cases<K>(chart_rng);

  const Wrong_jacobian_ellipsoid<K> wrong(1., 2., 3., 0.7, 0.8);
  const BS::Jacobian_check_report r = BS::check_jacobian(wrong, test_points(wrong, 100, rng, {}));
  BS_CHECK(r.max_relative_error > 1e-5 && r.worst_parameter == BS::Superquadric_ellipsoid<K>::E1,
           "the Jacobian checker missed a wrong column: " << r.max_relative_error);
}

template <class Primitive>
void check_consistency(const Primitive& p, const std::string& label)
{
  const BS::Chart_consistency_report r = BS::check_chart_consistency(p, 4000, 7);
  std::ostringstream where;
  where << label << " q = " << p.parameters().transpose() << ": pairs " << r.pairs_checked
        << ", distance " << r.max_relative_distance << ", round trip " << r.max_round_trip_error
        << ", normals " << r.max_normal_deviation;
  BS_CHECK(r.pairs_checked > 1000, where.str());
  BS_CHECK(r.max_relative_distance < 1e-12, where.str());
  BS_CHECK(r.max_round_trip_error < 1e-12, where.str());
  BS_CHECK(r.max_normal_deviation < 1e-9, where.str());
}

template <class K>
void test_chart_consistency()
{
  for(double e : {0.1, 0.5, 1., 1.7, 2.})
  {
    check_consistency(BS::Superquadric_ellipsoid<K>(1., 2., 0.5, e, 2.1 - e), "ellipsoid");
    check_consistency(BS::Superquadric_toroid<K>(1., 2., 0.5, 1.5, 2.5, e, 2.1 - e), "toroid");
  }
  // The overlap is real: a point just past the equator of chart 0 is found in chart 1.
  const BS::Superquadric_ellipsoid<K> ell(1., 1., 1.);
  BS::Chart_point q;
  BS_CHECK(ell.to_chart(BS::Chart_point(0, 1.1, 0.), 1, q) && std::abs(q.x - 0.9) < 1e-15, "overlap");
  BS_CHECK(!ell.to_chart(BS::Chart_point(0, 0.5, 0.), 1, q), "no overlap near the pole");
  const BS::Chart_point c = ell.canonical_chart_point(BS::Chart_point(1, 0., -1.1));
  BS_CHECK(c.chart == 0 && std::abs(c.y - 0.9) < 1e-15, "canonical point of the southern margin of chart 1");
}

// Normals: unit, orthogonal to both chart tangents (finite differences), and
// outward (these shapes are star-shaped about the origin).
template <class Primitive>
void check_normals(const Primitive& p, std::mt19937_64& rng, bool star_shaped)
{
  typedef typename Primitive::Vector_3 Vector_3;
  int checked = 0;
  for(std::size_t c = 0; c < p.number_of_charts(); ++c)
    for(int i = 0; i < 800; ++i)
    {
      const BS::Chart_point u = BS::random_chart_point(p, c, rng);
      const Vector_3 n = p.normal(u);
      BS_CHECK(std::abs(n.squared_length() - 1.) < 1e-12, "normal not unit");
      const double h = 1e-6;
      const Vector_3 tx = p.point(BS::Chart_point(c, u.x + h, u.y)) - p.point(BS::Chart_point(c, u.x - h, u.y));
      const Vector_3 ty = p.point(BS::Chart_point(c, u.x, u.y + h)) - p.point(BS::Chart_point(c, u.x, u.y - h));
      const Vector_3 cr = CGAL::cross_product(tx, ty);
      const double len = std::sqrt(cr.squared_length());
      if(len < 1e-14)
        continue;
      ++checked;
      BS_CHECK(std::abs(n * tx) <= 1e-5 * std::sqrt(tx.squared_length()) &&
                 std::abs(n * ty) <= 1e-5 * std::sqrt(ty.squared_length()),
               "normal not orthogonal to the tangents at (" << u.x << ", " << u.y << ")");
      BS_CHECK(n * cr > 0., "normal and counterclockwise chart orientation disagree");
      if(star_shaped)
        BS_CHECK(n * (p.point(u) - CGAL::ORIGIN) > 0., "normal not outward");
    }
  BS_CHECK(checked > int(700 * p.number_of_charts()), "too few normals checked: " << checked);
}

template <class K>
void test_normals(std::mt19937_64& rng)
{
  check_normals(BS::Superquadric_ellipsoid<K>(1., 2., 0.5, 0.8, 1.3), rng, true);
  check_normals(BS::Superquadric_toroid<K>(1., 2., 0.5, 1.5, 2.5, 0.8, 1.3), rng, false);
  // Closed-form normals at the poles and, for a pinched toroid, at the pinch: finite.
  const BS::Superquadric_ellipsoid<K> ell(1., 2., 0.5, 0.1, 2.);
  BS_CHECK(ell.normal(BS::Chart_point(0, 0., 0.)).z() > 0.999999, "north pole normal");
  BS_CHECK(ell.normal(BS::Chart_point(1, 0., 0.)).z() < -0.999999, "south pole normal");
  const BS::Superquadric_toroid<K> pinched(1., 1., 1., 1., 1.);
  const auto n = pinched.normal(BS::Chart_point(0, 0.3, M_PI));
  BS_CHECK(std::isfinite(n.x()) && std::abs(n.squared_length() - 1.) < 1e-12, "pinch normal");
  const BS::Superquadric_toroid<K> half_pinched(1., 1., 1., 1., 2.);
  const auto m = half_pinched.normal(BS::Chart_point(0, M_PI / 2., M_PI));
  BS_CHECK(std::isfinite(m.x()) && std::abs(m.squared_length() - 1.) < 1e-12, "degenerate tube normal");
}

template <class Primitive>
void check_chart_meshes(const Primitive& p, int resolution, int euler, std::size_t borders)
{
  typedef typename Primitive::Geom_traits K;
  const auto meshes = BS::make_chart_meshes(p, resolution);
  BS_CHECK(meshes.size() == p.number_of_charts(), "one mesh per chart");
  for(const auto& cm : meshes)
  {
    const auto& m = cm.mesh();
    BS_CHECK(m.is_valid(false), "invalid chart mesh");
    const int chi = int(m.number_of_vertices()) - int(m.number_of_edges()) + int(m.number_of_faces());
    BS_CHECK(chi == euler, "Euler characteristic " << chi << " instead of " << euler);
    std::vector<typename std::remove_reference_t<decltype(m)>::Halfedge_index> border_cycles;
    CGAL::Polygon_mesh_processing::extract_boundary_cycles(m, std::back_inserter(border_cycles));
    BS_CHECK(border_cycles.size() == borders, "boundary loops: " << border_cycles.size());
    double min_area = HUGE_VAL, max_area = 0.;
    int agree = 0, total = 0;
    for(auto f : m.faces())
    {
      const auto c = cm.face_chart_coordinates(f);
      const double area = 0.5 * ((c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) - (c[2][0] - c[0][0]) * (c[1][1] - c[0][1]));
      min_area = (std::min)(min_area, area);
      max_area = (std::max)(max_area, area);
      // The face's geometric normal agrees with the primitive normal at its centre.
      const auto v = cm.face_vertices(f);
      const auto n3 = CGAL::normal(m.point(v[0]), m.point(v[1]), m.point(v[2]));
      const auto np = p.normal(cm.chart_point(f, {{1. / 3., 1. / 3., 1. / 3.}}));
      ++total;
      if(n3 * np > 0.)
        ++agree;
    }
    BS_CHECK(min_area > 0., "a chart triangle is not counterclockwise");
    BS_CHECK(max_area < 8. * min_area, "chart triangles far from uniform: " << max_area / min_area);
    BS_CHECK(agree == total, agree << " of " << total << " faces agree with the primitive normal");
    // Vertex positions are the primitive's points.
    for(auto vd : m.vertices())
      BS_CHECK(CGAL::squared_distance(m.point(vd), p.point(cm.chart_point(vd))) == 0., "position");
  }
  (void)sizeof(K);
}

template <class K>
void test_chart_meshes()
{
  for(int res : {1, 2, 8})
  {
    check_chart_meshes(BS::Superquadric_ellipsoid<K>(1., 2., 0.5), res, 1, 1);
    check_chart_meshes(BS::Superquadric_toroid<K>(1., 2., 0.5, 1.5, 2.5), res, 0, 0);
  }
  bool thrown = false;
  try { BS::Chart_mesh<K>(0, BS::Chart_domain::disk(1.), 0); } catch(const std::invalid_argument&) { thrown = true; }
  BS_CHECK(thrown, "resolution 0 accepted");
}

void test_quaternion(std::mt19937_64& rng)
{
  std::normal_distribution<double> g(0., 1.);
  for(int t = 0; t < 200; ++t)
  {
    Eigen::Vector4d q(g(rng), g(rng), g(rng), g(rng));
    q *= 1.7;
    const Eigen::Matrix3d R = BS::internal::rotation_matrix(q);
    BS_CHECK((R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-13 && R.determinant() > 0.,
             "not a rotation");
    const Eigen::Vector4d back = BS::internal::quaternion_from_matrix(R);
    BS_CHECK((BS::internal::rotation_matrix(back) - R).norm() < 1e-13 && back[0] >= 0., "round trip");
    const auto dR = BS::internal::rotation_matrix_derivatives(q);
    for(int k = 0; k < 4; ++k)
    {
      const double h = 1e-6;
      Eigen::Vector4d qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      const Eigen::Matrix3d fd = (BS::internal::rotation_matrix(qp) - BS::internal::rotation_matrix(qm)) / (2 * h);
      BS_CHECK((fd - dR[std::size_t(k)]).norm() < 1e-7 * (1. + fd.norm()), "dR/dq_" << k);
    }
  }
}

// Points spread uniformly (by area) on an ellipsoid: sphere samples mapped by
// diag(a), kept with probability proportional to the area stretch.
template <class K>
std::vector<typename K::Point_3> sample_ellipsoid(const std::array<double, 3>& a, const Eigen::Matrix3d& R,
                                                  const Eigen::Vector3d& t, std::size_t n, std::mt19937_64& rng)
{
  std::normal_distribution<double> g(0., 1.);
  std::uniform_real_distribution<double> unit(0., 1.);
  const double max_stretch = (std::max)({a[0] * a[1], a[1] * a[2], a[0] * a[2]});
  std::vector<typename K::Point_3> pts;
  while(pts.size() < n)
  {
    Eigen::Vector3d s(g(rng), g(rng), g(rng));
    s.normalize();
    const Eigen::Vector3d stretch(a[1] * a[2] * s[0], a[0] * a[2] * s[1], a[0] * a[1] * s[2]);
    if(unit(rng) * max_stretch > stretch.norm())
      continue;
    const Eigen::Vector3d p = R * Eigen::Vector3d(a[0] * s[0], a[1] * s[1], a[2] * s[2]) + t;
    pts.emplace_back(p[0], p[1], p[2]);
  }
  return pts;
}

template <class K>
void test_initialization(std::mt19937_64& rng)
{
  typedef typename K::Point_3 Point_3;
  std::uniform_real_distribution<double> size(0.5, 2.5), shift(-100., 100.);
  std::normal_distribution<double> g(0., 1.);
  for(int t = 0; t < 20; ++t)
  {
    std::array<double, 3> a = {{size(rng), size(rng), size(rng)}};
    std::sort(a.begin(), a.end(), std::greater<double>());
    if(a[0] / a[1] < 1.1 || a[1] / a[2] < 1.1) // directions are only defined for distinct axes
    { --t; continue; }
    const Eigen::Matrix3d R = BS::internal::rotation_matrix(Eigen::Vector4d(g(rng), g(rng), g(rng), g(rng)));
    const Eigen::Vector3d c(shift(rng), shift(rng), shift(rng));
    const auto pts = sample_ellipsoid<K>(a, R, c, 20000, rng);
    const BS::Ellipsoid_fit<K> fit = BS::initialize_from_moments(pts);
    BS_CHECK(fit.degeneracy == BS::Point_cloud_degeneracy::None && fit.axes_refined, "refinement rejected");
    for(int i = 0; i < 3; ++i)
    {
      BS_CHECK(std::abs(fit.axes[std::size_t(i)] / a[std::size_t(i)] - 1.) < 0.02,
               "axis " << i << ": " << fit.axes[std::size_t(i)] << " instead of " << a[std::size_t(i)]);
      const Eigen::Vector3d d = fit.rotation_matrix().col(i);
      BS_CHECK(std::abs(d.dot(R.col(i))) > 0.99, "direction " << i);
    }
    const Eigen::Vector3d center(CGAL::to_double(fit.center.x()), CGAL::to_double(fit.center.y()),
                                 CGAL::to_double(fit.center.z()));
    // the centroid of N samples scatters by about a_i / sqrt(3 N) per axis: 0.02 a1 is over 3 sigma
    BS_CHECK((center - c).norm() < 0.02 * a[0], "centre off by " << (center - c).norm());
    BS_CHECK(std::abs(fit.rotation.norm() - 1.) < 1e-12 && fit.rotation_matrix().determinant() > 0., "rotation");
    // The moment estimate alone is exact only for a sphere: check it is the refinement that helps.
    const auto raw = BS::initialize_from_moments(pts, BS::parameters::refine_axes(false));
    BS_CHECK(!raw.axes_refined && raw.axes == raw.moment_axes, "refine_axes(false) ignored");
  }
  // Degenerate clouds: documented results, finite numbers.
  std::vector<Point_3> plane, line, same(20, Point_3(1., 2., 3.));
  for(int i = 0; i < 50; ++i)
  {
    plane.emplace_back(i % 7, i / 7, 5.);
    line.emplace_back(i, 2. * i, -i);
  }
  const auto fp = BS::initialize_from_moments(plane);
  BS_CHECK(fp.degeneracy == BS::Point_cloud_degeneracy::Coplanar &&
             std::abs(fp.axes[2] - 0.01 * fp.axes[0]) < 1e-12 * fp.axes[0], "coplanar");
  const auto fl = BS::initialize_from_moments(line, BS::parameters::minimum_axis_ratio(0.1));
  BS_CHECK(fl.degeneracy == BS::Point_cloud_degeneracy::Collinear &&
             std::abs(fl.axes[1] - 0.1 * fl.axes[0]) < 1e-12 * fl.axes[0] && std::isfinite(fl.rotation.sum()),
           "collinear");
  bool thrown = false;
  try { BS::initialize_from_moments(same); }
  catch(const BS::Input_error& e) { thrown = e.code() == BS::Input_error::All_points_identical; }
  BS_CHECK(thrown, "identical points accepted");
  thrown = false;
  try { BS::initialize_from_moments(plane, BS::parameters::minimum_axis_ratio(0.)); }
  catch(const std::invalid_argument&) { thrown = true; }
  BS_CHECK(thrown, "minimum_axis_ratio 0 accepted");
  // A custom point map (CGAL named parameters) gives the same fit.
  std::vector<std::pair<Point_3, int>> tagged;
  for(const Point_3& p : plane) tagged.emplace_back(p, 0);
  const auto ft = BS::initialize_from_moments(tagged, CGAL::parameters::point_map(CGAL::First_of_pair_property_map<std::pair<Point_3, int>>()));
  BS_CHECK(ft.axes == fp.axes && ft.rotation == fp.rotation, "point_map");
}

// The ellipsoid's map is the radial projection of the chart's direction onto
// the superquadric: every point is on the implicit surface (also for the
// lowest exponents), e1 = e2 = 1 gives the classic map, and the faces of a
// near-cube take chart regions of comparable size (the classic map squeezes
// the sides into a band of width ~1e-3 at the equator).
template <class K>
void test_radial_projection(std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> size(0.3, 3.), expo(0.01, 2.), coord(-1.2, 1.2);
  double worst = 0.;
  for(int t = 0; t < 2000; ++t)
  {
    const BS::Superquadric_ellipsoid<K> ell(size(rng), size(rng), size(rng), t % 10 == 0 ? 0.01 : expo(rng),
                                            t % 7 == 0 ? 0.01 : expo(rng));
    const BS::Chart_point u(std::size_t(t % 2), coord(rng), coord(rng));
    if(std::hypot(u.x, u.y) > 1.2)
      continue;
    const auto q = ell.parameters();
    const auto s = ell.point(u);
    const double e1 = q[3], e2 = q[4];
    const double X = std::abs(s.x() / q[0]), Y = std::abs(s.y() / q[1]), Z = std::abs(s.z() / q[2]);
    // H(s / a) - 1, scaled as in the map (largest coordinate 1) so that no power underflows
    const double m = (std::max)({X, Y, Z});
    const double H = std::pow(std::pow(X / m, 2. / e2) + std::pow(Y / m, 2. / e2), e2 / e1) + std::pow(Z / m, 2. / e1);
    const double h = std::pow(H, -0.5 * e1) / m; // 1 on the surface
    worst = (std::max)(worst, std::abs(h - 1.));
    // the point is along the chart's direction
    const Eigen::Vector3d d = ell.direction(u), x(s.x() / q[0], s.y() / q[1], s.z() / q[2]);
    BS_CHECK(d.cross(x).norm() <= 1e-12 * x.norm() && d.dot(x) > 0., "point not along the direction at " << u.x << ", " << u.y);
  }
  BS_CHECK(worst < 1e-12, "radial projection: points off the implicit surface by " << worst);

  const BS::Superquadric_ellipsoid<K> ellipsoid(1.3, 0.7, 2.1, 1., 1.);
  for(double r : {0., 0.3, 0.8, 1., 1.15})
    for(std::size_t c = 0; c < 2; ++c)
    {
      const BS::Chart_point u(c, r * std::cos(1.1), r * std::sin(1.1));
      const auto a = ellipsoid.angles(u);
      const auto s = ellipsoid.point(u);
      const Eigen::Vector3d classic(1.3 * a.cos_eta * a.cos_omega, 0.7 * a.cos_eta * a.sin_omega, 2.1 * a.sin_eta);
      BS_CHECK((Eigen::Vector3d(s.x(), s.y(), s.z()) - classic).norm() < 1e-15, "e = 1: not the classic map");
    }

  // A near-cube: chart radius 0.4 lies on the top face, 0.7 on the side
  // (its rim is at 0.5 to 0.61); the chart Jacobian at the pole is finite, of rank 2.
  const BS::Superquadric_ellipsoid<K> cube(1., 1., 1., 0.1, 0.1);
  for(double w : {0., 0.5, 1.})
  {
    const auto top = cube.point(BS::Chart_point(0, 0.4 * std::cos(w), 0.4 * std::sin(w)));
    const auto side = cube.point(BS::Chart_point(0, 0.7 * std::cos(w), 0.7 * std::sin(w)));
    BS_CHECK(top.z() > 0.99 && top.z() < 1.001 && (std::max)(std::abs(top.x()), std::abs(top.y())) < 0.95,
             "near-cube, chart radius 0.4: " << top);
    BS_CHECK((std::max)(std::abs(side.x()), std::abs(side.y())) > 0.99 && side.z() < 0.95,
             "near-cube, chart radius 0.7: " << side);
  }
  typename BS::Superquadric_ellipsoid<K>::Chart_jacobian D;
  BS::Superquadric_ellipsoid<K>(1., 2., 0.5, 0.3, 0.3).point_and_chart_jacobian(BS::Chart_point(0, 0., 0.), D);
  BS_CHECK(D.allFinite() && D.col(0).cross(D.col(1)).norm() > 0.1, "pole of a flat-topped ellipsoid:\n" << D);
}

// The radial projection's gradient G (of H over 2/e1) takes its factors as
// quotients of the powers already taken, and the powers themselves where a
// quotient could overflow (w < 1e-100) or a power is subnormal: each way
// against a long double evaluation of G's formula, and Euler's u . G = H.
void test_radial_projection_gradient()
{
  struct Case
  {
    Eigen::Vector3d v;
    double e1, e2;
    const char* what;
  };
  const Case cases[] = {{Eigen::Vector3d(0.3, -0.7, 1.), 0.7, 1.4, "quotients"},
                        {Eigen::Vector3d(-0.9, 0.4, 0.2), 1.8, 0.05, "quotients, x largest"},
                        {Eigen::Vector3d(1e-60, -2e-60, 1.), 1.5, 1., "w < 1e-100"},
                        {Eigen::Vector3d(1e-16, 0.5, 1.), 1., 0.1, "subnormal |ux|^(2/e2)"},
                        {Eigen::Vector3d(1., 0.2, -1e-16), 0.1, 0.8, "subnormal |uz|^(2/e1)"}};
  for(const Case& c : cases)
  {
    const BS::internal::Superquadric_radial_projection rp(c.v, c.e1, c.e2);
    const Eigen::Vector3d G = rp.gradient();
    typedef long double L;
    const L ux = std::abs(L(rp.u.x())), uy = std::abs(L(rp.u.y())), uz = std::abs(L(rp.u.z()));
    const L w = std::pow(ux, L(2) / c.e2) + std::pow(uy, L(2) / c.e2);
    const auto gxy = [&](L a) { return std::exp((L(c.e2) / c.e1 - 1) * std::log(w) + (L(2) / c.e2 - 1) * std::log(a)); };
    const L reference[3] = {gxy(ux), gxy(uy), std::pow(uz, L(2) / c.e1 - 1)};
    for(int i = 0; i < 3; ++i)
    {
      const L error = std::abs(std::abs(L(G[i])) - reference[i]);
      BS_CHECK(std::isfinite(G[i]) && error <= 1e-12L * reference[i] && std::signbit(G[i]) == std::signbit(rp.u[i]),
               c.what << ": gradient component " << i << " is " << G[i] << ", its formula gives " << double(reference[i]));
    }
    BS_CHECK(std::abs(rp.u.dot(G) - rp.H) <= 1e-13 * rp.H, c.what << ": u . G = " << rp.u.dot(G) << ", H = " << rp.H);
  }
}

template <class K>
void test_bad_parameters()
{
  int thrown = 0;
  try { BS::Superquadric_ellipsoid<K>(1., 1., -1.); } catch(const std::invalid_argument&) { ++thrown; }
  try { BS::Superquadric_ellipsoid<K>(1., 1., 1., 2.5); } catch(const std::invalid_argument&) { ++thrown; }
  try { BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1., 0.); } catch(const std::invalid_argument&) { ++thrown; }
  try { BS::Superquadric_toroid<K>(1., 1., 1., 0.5); } catch(const std::invalid_argument&) { ++thrown; }
  try { BS::Superquadric_toroid<K>(1., std::nan(""), 1.); } catch(const std::invalid_argument&) { ++thrown; }
  BS_CHECK(thrown == 5, "out-of-bound parameters accepted: " << 5 - thrown);
  BS_CHECK(std::string(BS::Superquadric_toroid<K>::parameter_name(3)) == "a4", "names");
}

template <class K>
void run_all(const char* kernel)
{
  std::mt19937_64 rng(20261121);
  const int before = blended_shape_test::failures();
  test_jacobians<K>(rng);
  test_chart_consistency<K>();
  test_normals<K>(rng);
  test_chart_meshes<K>();
  test_initialization<K>(rng);
  test_bad_parameters<K>();
  test_radial_projection<K>(rng);
  blended_shape_test::report(std::string("primitives with ") + kernel, before);
}

} // namespace

int main()
{
  std::mt19937_64 rng(5);
  test_quaternion(rng);
  test_radial_projection_gradient();
#ifndef BLENDED_SHAPE_ONE_KERNEL // sanitizer builds: Epick only (see test/CMakeLists.txt)
  run_all<CGAL::Simple_cartesian<double>>("Simple_cartesian<double>");
#endif
  run_all<CGAL::Exact_predicates_inexact_constructions_kernel>("Epick");
  blended_shape_test::report("test_primitives");
  return blended_shape_test::exit_code();
}
