// SPDX-License-Identifier: LGPL-3.0-or-later
// The hole component (sec. 4.2, App. B.2, eq. 32 and 33): its two domains,
// the domain switch that moves no surface point while the hole is closed,
// the pinch point, the exact parameter Jacobian, the tube's periodic seam,
// normals and chart orientation, the circles where the hole is glued to the
// base, the tube chart (Chart_kind::Tube: its chart mesh, random chart points,
// the generic checks on it), and the errors, with both supported kernels.
#ifndef BLENDED_SHAPE_HOLE_COMPONENT_CHECKS_H
#define BLENDED_SHAPE_HOLE_COMPONENT_CHECKS_H
// Part of test_blended_shape (one program, one compilation of the blended
// shape for each kernel; CTest runs it as `test_blended_shape_hole_component`).
#include "test_kernels.h"
#include "test_util.h"

#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>
#include <CGAL/Blended_shape/Primitives/Hole_component.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_toroid.h>
#include <CGAL/Blended_shape/Primitives/check_primitive.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <set>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace hole_component_checks {

namespace BS = CGAL::Blended_shapes;

const double two_pi = 2. * M_PI;

template <class K>
double length(const typename K::Vector_3& v)
{
  return std::sqrt(CGAL::to_double(v.squared_length()));
}

template <class P>
double distance(const P& a, const P& b)
{
  return std::sqrt(CGAL::to_double(CGAL::squared_distance(a, b)));
}

// |p|, the distance to the origin
template <class P>
double norm(const P& p)
{
  return std::sqrt(CGAL::to_double(CGAL::squared_distance(p, P(CGAL::ORIGIN))));
}

// The parameter vector (a1, a2, a3, a4, a5, e1, e2).
typedef std::array<double, 7> Params;

template <class K>
BS::Hole_component<K> make_hole(const Params& q, BS::Hole_domain d)
{
  return BS::Hole_component<K>(q[0], q[1], q[2], q[3], q[4], q[5], q[6], d);
}

// Random parameters: sizes in [0.3, 3], exponents in [e_lo, e_hi], and
// a4, a5 in [1, 3] for an open hole or exactly 1 for a closed one.
Params random_params(std::mt19937_64& rng, bool closed, double e_lo = 0.1, double e_hi = 2.)
{
  std::uniform_real_distribution<double> size(0.3, 3.), ring(1., 3.), expo(e_lo, e_hi);
  Params q;
  q[0] = size(rng); q[1] = size(rng); q[2] = size(rng);
  q[3] = closed ? 1. : ring(rng);
  q[4] = closed ? 1. : ring(rng);
  q[5] = expo(rng); q[6] = expo(rng);
  return q;
}

// Parameter sets: fixed corner cases (extreme exponents, one ring ratio at
// its bound) and random ones.
std::vector<Params> parameter_sets(std::mt19937_64& rng, bool closed, double e_lo = 0.1, double e_hi = 2.)
{
  std::vector<Params> sets;
  const double a4 = closed ? 1. : 1.7, a5 = closed ? 1. : 2.3;
  for(const auto& e : std::vector<std::array<double, 2>>{{{1., 1.}}, {{e_lo, e_lo}}, {{e_hi, e_hi}}, {{e_lo, e_hi}}})
    sets.push_back(Params{{1.2, 0.8, 1.5, a4, a5, e[0], e[1]}});
  if(!closed)
  {
    sets.push_back(Params{{1., 2., 0.7, 1., 1.9, 0.8, 1.3}}); // one axis still pinched
    sets.push_back(Params{{1., 1., 1., 1., 1., 1., 1.}});     // closed hole on the tube
  }
  for(int i = 0; i < 6; ++i)
    sets.push_back(random_params(rng, closed, e_lo, e_hi));
  return sets;
}

// The seam theta = 0, the axes, the middle circle and both boundary circles.
std::vector<BS::Chart_point> tube_special_points()
{
  std::vector<BS::Chart_point> s;
  for(int k = 0; k < 8; ++k)
    for(double r : {-1., -0.5, 0., 0.5, 1.})
      s.emplace_back(0, k * M_PI / 4., r);
  return s;
}

// The centres, the chart axes and the boundary circle of both disks.
std::vector<BS::Chart_point> disk_special_points()
{
  std::vector<BS::Chart_point> s;
  for(std::size_t c = 0; c < 2; ++c)
    for(double rho : {0., 0.25, 0.5, 1.})
      for(int k = 0; k < 8; ++k)
      {
        const double a = k * M_PI / 4.;
        s.emplace_back(c, rho * std::cos(a), rho * std::sin(a));
        s.emplace_back(c, k < 4 ? 0. : rho, k < 4 ? rho : 0.);
      }
  return s;
}

template <class Hole>
std::vector<BS::Chart_point> test_points(const Hole& h, std::size_t per_chart, std::mt19937_64& rng)
{
  std::vector<BS::Chart_point> pts =
    (h.domain() == BS::Hole_domain::Tube) ? tube_special_points() : disk_special_points();
  for(std::size_t c = 0; c < h.number_of_charts(); ++c)
    for(std::size_t i = 0; i < per_chart; ++i)
      pts.push_back(BS::random_chart_point(h, c, rng));
  return pts;
}

template <class Hole>
std::string describe(const Hole& h)
{
  std::ostringstream s;
  s << (h.domain() == BS::Hole_domain::Tube ? "tube" : "two disks") << " q = " << h.parameters().transpose();
  return s.str();
}

// The largest |s(u)| over the points: the scale of relative distances (the
// pinch point itself is at the origin).
template <class Hole>
double shape_size(const Hole& h, const std::vector<BS::Chart_point>& pts)
{
  double size = 0.;
  for(const BS::Chart_point& u : pts)
    size = (std::max)(size, norm(h.point(u)));
  return size;
}

// ---------------------------------------------------------------------------
// (1) The domain switch moves no vertex.

template <class K>
void test_domain_switch(std::mt19937_64& rng)
{
  typedef BS::Hole_component<K> Hole;
  for(const Params& q : parameter_sets(rng, true))
  {
    const Hole disks = make_hole<K>(q, BS::Hole_domain::Two_disks);
    Hole tube = disks;
    tube.set_domain(BS::Hole_domain::Tube); // the switch of the hole sequence
    BS_CHECK(tube.number_of_charts() == 1 && disks.number_of_charts() == 2, "number of charts");

    // Two disks -> tube: every vertex of the disk chart meshes, and random points.
    for(int res : {1, 4, 12})
    {
      const auto meshes = BS::make_chart_meshes(disks, res);
      BS_CHECK(meshes.size() == 2, "one mesh per disk");
      std::vector<BS::Chart_point> verts;
      for(const auto& cm : meshes)
        for(auto v : cm.mesh().vertices())
          verts.push_back(cm.chart_point(v));
      const double size = shape_size(disks, verts);
      double worst = 0.;
      for(const auto& cm : meshes)
        for(auto v : cm.mesh().vertices())
        {
          const BS::Chart_point t = Hole::to_domain(cm.chart_point(v), BS::Hole_domain::Tube);
          BS_CHECK(t.chart == 0 && t.x >= 0. && t.x < two_pi && std::abs(t.y) <= 1., "tube image out of domain");
          worst = (std::max)(worst, distance(cm.mesh().point(v), tube.point(t)) / size);
        }
      BS_CHECK(worst <= 1e-12, describe(disks) << ": the switch moves a vertex of the resolution " << res
                                               << " disk meshes by " << worst);
    }
    // Tube -> two disks: a periodic grid of the tube with its middle circle r = 0, and random points.
    std::vector<BS::Chart_point> grid = tube_special_points();
    for(int i = 0; i < 48; ++i)
      for(int j = 0; j <= 16; ++j)
        grid.emplace_back(0, two_pi * i / 48., -1. + j / 8.);
    for(int i = 0; i < 2000; ++i)
      grid.push_back(BS::random_chart_point(tube, 0, rng));
    const double size = shape_size(tube, grid);
    double worst = 0., worst_normal = 0.;
    for(const BS::Chart_point& t : grid)
    {
      const BS::Chart_point d = Hole::to_domain(t, BS::Hole_domain::Two_disks);
      BS_CHECK(d.chart == (t.y < 0. ? 1u : 0u) && std::hypot(d.x, d.y) <= 1. + 1e-15, "disk image");
      worst = (std::max)(worst, distance(tube.point(t), disks.point(d)) / size);
      // back to the tube: the same chart point (theta is arbitrary on r = 0)
      const BS::Chart_point back = Hole::to_domain(d, BS::Hole_domain::Tube);
      if(t.y != 0.)
      {
        const double dx = std::abs(back.x - t.x);
        BS_CHECK((std::min)(dx, two_pi - dx) < 1e-13 && std::abs(back.y - t.y) < 1e-15,
                 "round trip tube -> disks -> tube at (" << t.x << ", " << t.y << ")");
        worst_normal = (std::max)(worst_normal, length<K>(tube.normal(t) - disks.normal(d)));
      }
      else
        BS_CHECK(back.x == 0. && back.y == 0., "the middle circle goes to the disk centre, theta = 0");
    }
    BS_CHECK(worst <= 1e-12, describe(tube) << ": tube -> two disks moves a point by " << worst);
    BS_CHECK(worst_normal <= 1e-9, describe(tube) << ": normals differ by " << worst_normal);
  }

  // The hole sequence: closed on two disks -> switch -> open; closing it
  // again allows switching back.
  Hole h(1.2, 0.9, 1.4, 1., 1., 1., 1.);
  BS_CHECK(h.domain() == BS::Hole_domain::Two_disks && h.hole_is_closed(), "default domain and closed hole");
  const typename K::Point_3 pinch = h.point(BS::Chart_point(1, 0., 0.));
  h.set_domain(BS::Hole_domain::Tube);
  auto q = h.parameters();
  q[Hole::A4] = 1.5;
  q[Hole::A5] = 1.25;
  h.set_parameters(q);
  BS_CHECK(!h.hole_is_closed(), "open hole");
  // The middle circle opened to the radii a1 (a4 - 1), a2 (a5 - 1) (Fig. 14).
  const auto p0 = h.point(BS::Chart_point(0, 0., 0.)), p1 = h.point(BS::Chart_point(0, M_PI / 2., 0.));
  BS_CHECK(std::abs(p0.x() - 1.2 * 0.5) < 1e-15 && std::abs(p1.y() - 0.9 * 0.25) < 1e-15 &&
             std::abs(p0.z()) < 1e-15 && norm(pinch) < 1e-15,
           "hole opening: " << p0 << " / " << p1);
  bool thrown = false;
  try { h.set_domain(BS::Hole_domain::Two_disks); }
  catch(const std::logic_error& e) { thrown = std::string(e.what()).find("a4 = 1.5") != std::string::npos; }
  BS_CHECK(thrown && h.domain() == BS::Hole_domain::Tube, "switching an open hole to two disks");
  q[Hole::A4] = q[Hole::A5] = 1.;
  h.set_parameters(q);
  h.set_domain(BS::Hole_domain::Two_disks);
  BS_CHECK(h.domain() == BS::Hole_domain::Two_disks && h.number_of_charts() == 2, "closing the hole again");
}

// ---------------------------------------------------------------------------
// (2) The disk centres map to the pinch point, on the axis.

template <class K>
void test_pinch_point(std::mt19937_64& rng)
{
  typedef BS::Hole_component<K> Hole;
  std::uniform_real_distribution<double> angle(0., two_pi);
  for(const Params& q : parameter_sets(rng, true))
  {
    const Hole disks = make_hole<K>(q, BS::Hole_domain::Two_disks);
    const Hole tube = make_hole<K>(q, BS::Hole_domain::Tube);
    const auto c0 = disks.point(BS::Chart_point(0, 0., 0.)), c1 = disks.point(BS::Chart_point(1, 0., 0.));
    // on the axis exactly: a4 + C(cos pi) = 1 - 1 = 0
    BS_CHECK(c0.x() == 0. && c0.y() == 0. && c1.x() == 0. && c1.y() == 0., describe(disks) << ": pinch off the axis");
    BS_CHECK(c0 == c1, "both disk centres are the pinch point");
    // z = a3 S(pi, e1): 0 up to the rounding of pi, amplified by small e1
    if(q[5] >= 0.8)
      BS_CHECK(std::abs(c0.z()) < 1e-12 * q[2], "pinch point at " << c0.z());
    // the whole middle circle of the tube is that point
    for(int i = 0; i < 50; ++i)
    {
      const double theta = (i < 8) ? i * M_PI / 4. : angle(rng);
      BS_CHECK(tube.point(BS::Chart_point(0, theta, 0.)) == c0, "the middle circle is not collapsed");
    }
    // the pinch normal: finite, unit, horizontal (the normal at theta = 0),
    // the same on both disks and on the tube at (0, 0)
    const auto n0 = disks.normal(BS::Chart_point(0, 0., 0.)), n1 = disks.normal(BS::Chart_point(1, 0., 0.));
    const auto nt = tube.normal(BS::Chart_point(0, 0., 0.));
    BS_CHECK(std::isfinite(CGAL::to_double(n0.x())) && std::abs(length<K>(n0) - 1.) < 1e-12, "pinch normal");
    BS_CHECK(n0 == n1 && n0 == nt, "pinch normal differs between the domains");
    if(q[5] <= 1.5)
      BS_CHECK(n0.x() < -0.99, "pinch normal " << n0 << " not toward the axis");
    // the disks' Jacobians at the centre are the tube's at (0, 0)
    typename Hole::Jacobian J0, Jt;
    disks.jacobian(BS::Chart_point(1, 0., 0.), J0);
    tube.jacobian(BS::Chart_point(0, 0., 0.), Jt);
    BS_CHECK(J0 == Jt, "Jacobian at the pinch");
  }
}

// ---------------------------------------------------------------------------
// (3) Exact parameter Jacobian on both domains.

template <class Hole>
void check_hole_jacobian(const Hole& h, const std::vector<BS::Chart_point>& pts)
{
  const BS::Jacobian_check_report r = BS::check_jacobian(h, pts);
  std::ostringstream where;
  where << describe(h) << ": worst parameter " << r.worst_parameter << " at chart " << r.worst_point.chart << " ("
        << r.worst_point.x << ", " << r.worst_point.y << "), error " << r.max_relative_error;
  BS_CHECK(r.points_checked == pts.size() && pts.size() >= 1000, where.str());
  BS_CHECK(!r.has_non_finite, where.str());
  BS_CHECK(r.max_relative_error < 1e-6, where.str());
}

// A deliberately wrong column must be caught.
template <class K>
struct Wrong_jacobian_hole : BS::Hole_component<K>
{
  typedef BS::Hole_component<K> Base;
  using Base::Base;
  int column = Base::A4;
  typename Base::Point_3 point_and_jacobian(const BS::Chart_point& p, typename Base::Jacobian& J) const
  {
    const typename Base::Point_3 s = Base::point_and_jacobian(p, J);
    J.col(column) *= 1.0001;
    return s;
  }
};

template <class K>
void test_jacobians(std::mt19937_64& rng)
{
  for(bool closed : {false, true})
    for(const Params& q : parameter_sets(rng, closed))
    {
      const auto h = make_hole<K>(q, closed ? BS::Hole_domain::Two_disks : BS::Hole_domain::Tube);
      check_hole_jacobian(h, test_points(h, closed ? 600 : 1100, rng));
    }
  // the closed hole on the tube too (a4 = a5 = 1 at their bound: one-sided differences)
  const auto closed_tube = make_hole<K>(Params{{0.9, 1.3, 1.1, 1., 1., 0.6, 1.4}}, BS::Hole_domain::Tube);
  check_hole_jacobian(closed_tube, test_points(closed_tube, 1000, rng));

  Wrong_jacobian_hole<K> wrong(1., 2., 1.5, 1.6, 1.2, 0.7, 0.8, BS::Hole_domain::Tube);
  BS::Jacobian_check_report r = BS::check_jacobian(wrong, test_points(wrong, 1000, rng));
  BS_CHECK(r.max_relative_error > 1e-5 && r.worst_parameter == BS::Hole_component<K>::A4,
           "the Jacobian checker missed a wrong a4 column on the tube: " << r.max_relative_error);
  Wrong_jacobian_hole<K> wrong_disks(1., 2., 1.5, 1., 1., 0.7, 0.8);
  wrong_disks.column = BS::Hole_component<K>::E1;
  r = BS::check_jacobian(wrong_disks, test_points(wrong_disks, 500, rng));
  BS_CHECK(r.max_relative_error > 1e-5 && r.worst_parameter == BS::Hole_component<K>::E1,
           "the Jacobian checker missed a wrong e1 column on the disks: " << r.max_relative_error);
}

// ---------------------------------------------------------------------------
// (4) Chart consistency: the disks do not overlap; the tube's seam
// x ~ x + 2 pi gives the same point, normal and canonical point.

template <class K>
void test_chart_consistency(std::mt19937_64& rng)
{
  typedef BS::Hole_component<K> Hole;
  for(const Params& q : parameter_sets(rng, true))
  {
    const Hole disks = make_hole<K>(q, BS::Hole_domain::Two_disks);
    const BS::Chart_consistency_report r = BS::check_chart_consistency(disks, 2000, 3);
    BS_CHECK(r.points_sampled == 4000 && r.pairs_checked == 0 && r.max_relative_distance == 0.,
             describe(disks) << ": the disks overlap: " << r.pairs_checked << " pairs");
    for(int i = 0; i < 200; ++i)
    {
      const BS::Chart_point p = BS::random_chart_point(disks, std::size_t(i % 2), rng);
      BS::Chart_point o;
      BS_CHECK(!disks.to_chart(p, 1 - p.chart, o) && !disks.to_chart(p, 2, o), "to_chart to another disk");
      BS_CHECK(disks.to_chart(p, p.chart, o) && o.chart == p.chart && o.x == p.x && o.y == p.y, "to_chart to itself");
      const BS::Chart_point c = disks.canonical_chart_point(p);
      BS_CHECK(c.chart == p.chart && c.x == p.x && c.y == p.y, "canonical point of a disk point");
    }
  }
  for(const Params& q : parameter_sets(rng, false))
  {
    const Hole tube = make_hole<K>(q, BS::Hole_domain::Tube);
    // Random points only: shifting theta by 2 pi rounds it, and exactly on
    // the axes theta = k pi/2 the signed powers C and S turn that last bit
    // into a visible jump for tiny exponents (and flip the sign-only normal
    // of e = 2, a genuine crease) -- a property of the toroid's angles.
    std::vector<BS::Chart_point> pts;
    for(int i = 0; i < 2000; ++i)
      pts.push_back(BS::random_chart_point(tube, 0, rng));
    const double size = shape_size(tube, pts);
    double dist = 0., ndev = 0., round_trip = 0.;
    std::size_t pairs = 0;
    for(const BS::Chart_point& p : pts)
    {
      BS::Chart_point o;
      BS_CHECK(!tube.to_chart(p, 1, o), "the tube has one chart");
      const BS::Chart_point cp = tube.canonical_chart_point(p);
      BS_CHECK(cp.chart == 0 && cp.x >= 0. && cp.x < two_pi && cp.y == p.y &&
                 tube.chart_domain(0).contains(cp.x, cp.y), "canonical point out of the domain");
      for(int k : {-2, -1, 1, 2, 3})
      {
        const BS::Chart_point s(0, p.x + k * two_pi, p.y);
        ++pairs;
        dist = (std::max)(dist, distance(tube.point(s), tube.point(p)) / size);
        ndev = (std::max)(ndev, length<K>(tube.normal(s) - tube.normal(p)));
        BS_CHECK(tube.to_chart(s, 0, o), "to_chart on the tube");
        const BS::Chart_point cs = tube.canonical_chart_point(s);
        BS_CHECK(cs.chart == 0 && cs.x >= 0. && cs.x < two_pi && cs.y == s.y, "canonical point not reduced");
        const double dx = std::abs(cs.x - cp.x);
        round_trip = (std::max)(round_trip, (std::min)(dx, two_pi - dx) + std::abs(o.x - cs.x) + std::abs(o.y - p.y));
        dist = (std::max)(dist, distance(tube.point(cs), tube.point(cp)) / size);
      }
    }
    BS_CHECK(pairs > 1000 && dist < 1e-12 && round_trip < 1e-12,
             describe(tube) << ": seam distance " << dist << ", canonical points " << round_trip);
    BS_CHECK(ndev < 1e-9, describe(tube) << ": seam normals " << ndev);
  }
}

// ---------------------------------------------------------------------------
// (5) Normals: unit, orthogonal to the chart tangents, and in the direction
// of d s/dx x d s/dy (counterclockwise chart triangles face outward) where
// the map is regular; outward means into the hole, toward the axis.

template <class Hole>
void check_normals(const Hole& h, std::mt19937_64& rng, bool of_revolution)
{
  typedef typename Hole::Vector_3 Vector_3;
  const auto& q = h.parameters();
  int checked = 0, total = 0;
  for(std::size_t c = 0; c < h.number_of_charts(); ++c)
    for(int i = 0; i < 800; ++i)
    {
      const BS::Chart_point u = BS::random_chart_point(h, c, rng);
      ++total;
      const Vector_3 n = h.normal(u);
      BS_CHECK(std::abs(CGAL::to_double(n.squared_length()) - 1.) < 1e-12, "normal not unit");
      const double eps = 1e-6;
      const Vector_3 tx = h.point(BS::Chart_point(c, u.x + eps, u.y)) - h.point(BS::Chart_point(c, u.x - eps, u.y));
      const Vector_3 ty = h.point(BS::Chart_point(c, u.x, u.y + eps)) - h.point(BS::Chart_point(c, u.x, u.y - eps));
      const Vector_3 cr = CGAL::cross_product(tx, ty);
      if(length<typename Hole::Geom_traits>(cr) < 1e-14)
        continue;
      ++checked;
      BS_CHECK(std::abs(CGAL::to_double(n * tx)) <= 1e-5 * length<typename Hole::Geom_traits>(tx) &&
                 std::abs(CGAL::to_double(n * ty)) <= 1e-5 * length<typename Hole::Geom_traits>(ty),
               describe(h) << ": normal not orthogonal to the tangents at " << u.chart << " (" << u.x << ", " << u.y << ")");
      BS_CHECK(n * cr > 0., describe(h) << ": normal and counterclockwise chart orientation disagree at "
                                        << u.chart << " (" << u.x << ", " << u.y << ")");
      // toward the axis: the horizontal part of the normal points inward
      const auto p = h.point(u);
      const double r = 2. * (h.toroid_chart_point(u).y / M_PI - 1.); // u = (1 + r/2) pi
      if(std::abs(r) < 0.9) // away from the glue circles, where the normal turns vertical
        BS_CHECK(CGAL::to_double(n.x() * p.x() + n.y() * p.y()) < 0., describe(h) << ": normal away from the axis");
      if(of_revolution)
      {
        // outward of the torus: away from the centre circle of the tube
        const double rho = std::hypot(CGAL::to_double(p.x()), CGAL::to_double(p.y()));
        const double cx = rho > 0. ? q[Hole::A1] * q[Hole::A4] * CGAL::to_double(p.x()) / rho : 0.;
        const double cy = rho > 0. ? q[Hole::A1] * q[Hole::A4] * CGAL::to_double(p.y()) / rho : 0.;
        const double d = CGAL::to_double(n.x()) * (CGAL::to_double(p.x()) - cx) +
                         CGAL::to_double(n.y()) * (CGAL::to_double(p.y()) - cy) +
                         CGAL::to_double(n.z()) * CGAL::to_double(p.z());
        BS_CHECK(d > 0., describe(h) << ": normal not outward of the torus");
      }
    }
  BS_CHECK(checked > total * 9 / 10, describe(h) << ": too few regular points: " << checked << " of " << total);
}

template <class K>
void check_disk_meshes(const BS::Hole_component<K>& h)
{
  for(int res : {2, 8})
    for(const auto& cm : BS::make_chart_meshes(h, res))
    {
      const auto& m = cm.mesh();
      const int chi = int(m.number_of_vertices()) - int(m.number_of_edges()) + int(m.number_of_faces());
      BS_CHECK(m.is_valid(false) && chi == 1, "disk chart mesh");
      int agree = 0, total = 0;
      for(auto f : m.faces())
      {
        const auto v = cm.face_vertices(f);
        const auto n3 = CGAL::normal(m.point(v[0]), m.point(v[1]), m.point(v[2]));
        const auto np = h.normal(cm.chart_point(f, {{1. / 3., 1. / 3., 1. / 3.}}));
        ++total;
        if(n3 * np > 0.)
          ++agree;
      }
      BS_CHECK(agree == total, describe(h) << ": " << agree << " of " << total
                                           << " mesh faces agree with the normal, resolution " << res);
    }
}

template <class K>
void test_normals(std::mt19937_64& rng)
{
  typedef BS::Hole_component<K> Hole;
  for(bool closed : {false, true})
    for(const Params& q : parameter_sets(rng, closed, 0.5, 1.5))
    {
      const Hole h = make_hole<K>(q, closed ? BS::Hole_domain::Two_disks : BS::Hole_domain::Tube);
      check_normals(h, rng, false);
      if(closed)
        check_disk_meshes(h);
    }
  // surfaces of revolution, with profile exponents
  std::uniform_real_distribution<double> size(0.3, 3.), ring(1., 3.), expo(0.5, 1.5);
  for(int i = 0; i < 6; ++i)
  {
    const double a = size(rng), a4 = (i < 3) ? 1. : ring(rng);
    const Hole h(a, a, size(rng), a4, a4, expo(rng), 1., i < 3 ? BS::Hole_domain::Two_disks : BS::Hole_domain::Tube);
    check_normals(h, rng, true);
  }
}

// ---------------------------------------------------------------------------
// (6) The boundary circles r = -1, 1 are the toroid's circles u = pi/2,
// 3 pi/2 (z = a3, -a3), where the hole is glued to the base.

double spow(double c, double e) { return c == 0. ? 0. : std::copysign(std::pow(std::abs(c), e), c); }

template <class K>
void test_boundary_circles(std::mt19937_64& rng)
{
  typedef BS::Hole_component<K> Hole;
  std::uniform_real_distribution<double> angle(0., two_pi);
  for(bool closed : {false, true})
    for(const Params& q : parameter_sets(rng, closed))
    {
      const Hole tube = make_hole<K>(q, BS::Hole_domain::Tube);
      const BS::Superquadric_toroid<K> toroid(q[0], q[1], q[2], q[3], q[4], q[5], q[6]);
      const double size = q[0] * q[3] + q[1] * q[4] + q[2];
      for(int i = 0; i < 64; ++i)
      {
        const double theta = (i < 8) ? i * M_PI / 4. : angle(rng);
        for(int side : {-1, 1})
        {
          const double u = (side < 0) ? M_PI / 2. : 3. * M_PI / 2.;
          const auto p = tube.point(BS::Chart_point(0, theta, double(side)));
          BS_CHECK(p == toroid.point(BS::Chart_point(0, theta, u)),
                   describe(tube) << ": circle r = " << side << " is not the toroid's u = " << u);
          BS_CHECK(tube.normal(BS::Chart_point(0, theta, double(side))) == toroid.normal(BS::Chart_point(0, theta, u)),
                   "boundary normal");
          // eq. 32 at cos u = 0, sin u = -+1; theta's cosine and sine exact at
          // the quarter turns (as the toroid computes them), else std::cos
          BS_CHECK(p.z() == -side * q[2], "glue circle height " << p.z());
          {
            const int quarter = (i < 8 && i % 2 == 0) ? (i / 2) : -1;
            const double ct = quarter < 0 ? std::cos(theta) : (quarter == 0 ? 1. : quarter == 2 ? -1. : 0.);
            const double st = quarter < 0 ? std::sin(theta) : (quarter == 1 ? 1. : quarter == 3 ? -1. : 0.);
            const double ex = q[0] * q[3] * spow(ct, q[6]);
            const double ey = q[1] * q[4] * spow(st, q[6]);
            BS_CHECK(std::abs(CGAL::to_double(p.x()) - ex) < 1e-12 * size &&
                       std::abs(CGAL::to_double(p.y()) - ey) < 1e-12 * size,
                     describe(tube) << ": glue circle point " << p << " instead of " << ex << " " << ey);
          }
          if(q[5] <= 1.5) // the glue circle's normal is vertical: up on top, down below
            BS_CHECK(CGAL::to_double(tube.normal(BS::Chart_point(0, theta, double(side))).z()) * -side > 1. - 1e-6,
                     "glue circle normal");
        }
      }
      if(!closed)
        continue;
      // the rims of the disks: chart 0 at the bottom circle, chart 1 at the top one
      const Hole disks = make_hole<K>(q, BS::Hole_domain::Two_disks);
      // (on the chart axes |(x, y)| = 1 exactly; elsewhere the rounding of
      // rho moves r off +-1 by an ulp, which e1 below 0.8 amplifies)
      for(int i = 0; i < 64; ++i)
      {
        const double a = (i < 4) ? i * M_PI / 2. : angle(rng);
        if(i >= 4 && q[5] < 0.8)
          break;
        const double x = (i < 4) ? double((1 - i) * (i % 2 == 0)) : std::cos(a);
        const double y = (i < 4) ? double((2 - i) * (i % 2 == 1)) : std::sin(a);
        for(std::size_t c : {0u, 1u})
        {
          const auto p = disks.point(BS::Chart_point(c, x, y));
          const double theta = Hole::to_domain(BS::Chart_point(c, x, y), BS::Hole_domain::Tube).x;
          BS_CHECK(std::abs(std::remainder(theta - (c == 0 ? -a : a), two_pi)) < 1e-14, "rim angle");
          const auto e = toroid.point(BS::Chart_point(0, theta, c == 0 ? 3. * M_PI / 2. : M_PI / 2.));
          BS_CHECK(distance(p, e) < 1e-12 * size && std::abs(CGAL::to_double(p.z()) + (c == 0 ? q[2] : -q[2])) < 1e-12 * size,
                   describe(disks) << ": rim of disk " << c << " at " << p << " instead of " << e);
        }
      }
    }
  // eq. 33 in the interior, against eq. 32 written out (e1 = e2 = 1)
  const Hole h(1.3, 0.7, 1.1, 1.4, 1.8, 1., 1., BS::Hole_domain::Tube);
  for(int i = 0; i < 200; ++i)
  {
    const BS::Chart_point t = BS::random_chart_point(h, 0, rng);
    const double u = (1. + t.y / 2.) * M_PI, v = t.x;
    const typename K::Point_3 e(1.3 * (1.4 + std::cos(u)) * std::cos(v), 0.7 * (1.8 + std::cos(u)) * std::sin(v),
                                1.1 * std::sin(u));
    BS_CHECK(distance(h.point(t), e) < 1e-14, "eq. 33 at (" << t.x << ", " << t.y << ")");
  }
}

// ---------------------------------------------------------------------------
// (7) The tube chart (Chart_kind::Tube): its chart mesh, random chart points,
// the chart-consistency check and the Jacobian check through them.

// The structure of a tube chart mesh of the domain [0, 2 pi) x [y_min, y_max]
// at resolution n: valid, closed in x, an annulus whose two boundary loops
// are the rows y = y_min and y = y_max exactly, rows at most 1/n apart
// (with a row at y = 0 when it is inside), counterclockwise, near-uniform
// chart triangles. Returns the rows.
template <class K>
std::vector<double> check_tube_mesh_structure(const BS::Chart_mesh<K>& cm, int n, const std::string& what)
{
  typedef typename BS::Chart_mesh<K>::Mesh Mesh;
  const Mesh& m = cm.mesh();
  const BS::Chart_domain& d = cm.domain();
  BS_CHECK(d.kind == BS::Chart_kind::Tube, what << ": not a tube mesh");
  BS_CHECK(m.is_valid(false) && CGAL::is_triangle_mesh(m), what << ": invalid tube mesh");
  const int chi = int(m.number_of_vertices()) - int(m.number_of_edges()) + int(m.number_of_faces());
  BS_CHECK(chi == 0, what << ": Euler characteristic " << chi);
  // rows: every vertex on a row of 4n vertices at x = 2 pi i / 4n
  std::map<double, std::set<double>> rows;
  for(auto v : m.vertices())
  {
    const BS::Chart_point u = cm.chart_point(v);
    BS_CHECK(u.chart == cm.chart_index() && d.contains(u.x, u.y) && u.x >= 0. && u.x < two_pi,
             what << ": vertex (" << u.x << ", " << u.y << ") out of the domain");
    rows[u.y].insert(u.x);
  }
  std::vector<double> ys;
  for(const auto& r : rows)
  {
    ys.push_back(r.first);
    BS_CHECK(r.second.size() == std::size_t(4 * n), what << ": row y = " << r.first << " has " << r.second.size()
                                                          << " vertices instead of " << 4 * n);
    for(double x : r.second)
    {
      const double i = x * (4 * n) / two_pi;
      BS_CHECK(std::abs(i - std::round(i)) < 1e-9, what << ": column x = " << x);
    }
  }
  BS_CHECK(ys.size() >= 2 && ys.front() == d.y_min && ys.back() == d.y_max,
           what << ": no row exactly at y_min = " << d.y_min << " and y_max = " << d.y_max);
  if(d.y_min < 0. && 0. < d.y_max)
    BS_CHECK(rows.count(0.) == 1, what << ": no row at y = 0");
  for(std::size_t j = 1; j < ys.size(); ++j)
    BS_CHECK(ys[j] - ys[j - 1] <= 1. / n + 1e-12, what << ": rows " << ys[j - 1] << " and " << ys[j] << " too far apart");
  BS_CHECK(m.number_of_faces() == 2 * std::size_t(4 * n) * (ys.size() - 1), what << ": " << m.number_of_faces() << " faces");
  // two boundary loops, y = y_min and y = y_max exactly, each a whole row;
  // no other border: the mesh is closed across the seam in x
  std::vector<typename Mesh::Halfedge_index> cycles;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(m, std::back_inserter(cycles));
  BS_CHECK(cycles.size() == 2, what << ": " << cycles.size() << " boundary loops instead of 2");
  std::set<double> loop_rows;
  std::size_t border_halfedges = 0;
  for(auto h0 : cycles)
  {
    std::set<double> ys_of_loop;
    std::size_t count = 0;
    for(auto h : CGAL::halfedges_around_face(h0, m))
    {
      ++count;
      ys_of_loop.insert(cm.chart_point(m.target(h)).y);
    }
    border_halfedges += count;
    BS_CHECK(ys_of_loop.size() == 1 && count == std::size_t(4 * n),
             what << ": a boundary loop of " << count << " edges not on one row");
    if(ys_of_loop.size() == 1)
      loop_rows.insert(*ys_of_loop.begin());
  }
  BS_CHECK(loop_rows.size() == 2 && loop_rows.count(d.y_min) == 1 && loop_rows.count(d.y_max) == 1,
           what << ": the boundary loops are not the rows y_min and y_max");
  std::size_t all_border = 0;
  for(auto h : m.halfedges())
    if(m.is_border(h))
      ++all_border;
  BS_CHECK(all_border == border_halfedges && all_border == std::size_t(8 * n), what << ": " << all_border
                                                                                  << " border halfedges: not closed in x");
  // counterclockwise, near-uniform chart triangles, none wider than half a period
  double min_area = HUGE_VAL, max_area = 0.;
  for(auto f : m.faces())
  {
    const auto c = cm.face_chart_coordinates(f);
    const double area = 0.5 * ((c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) - (c[2][0] - c[0][0]) * (c[1][1] - c[0][1]));
    min_area = (std::min)(min_area, area);
    max_area = (std::max)(max_area, area);
    for(int k = 1; k < 3; ++k)
      BS_CHECK(std::abs(c[k][0] - c[0][0]) <= two_pi / (4 * n) + 1e-12 && std::abs(c[k][1] - c[0][1]) <= 1. / n + 1e-12,
               what << ": a face is not unwrapped to a small triangle");
  }
  BS_CHECK(min_area > 0., what << ": a chart triangle is not counterclockwise (area " << min_area << ")");
  BS_CHECK(max_area < 4. * min_area, what << ": chart triangles far from uniform: " << max_area / min_area);
  return ys;
}

template <class K>
void test_tube_chart_mesh(std::mt19937_64& rng)
{
  typedef BS::Hole_component<K> Hole;
  typedef typename K::Point_3 Point_3;
  std::uniform_real_distribution<double> unit(0., 1.);

  // The hole's tube chart: [-1, 1], rows y = -1, 0, 1 exactly, 1/n apart.
  Hole tube(1., 1., 1., 1.5, 1.5, 1., 1., BS::Hole_domain::Tube);
  const BS::Chart_domain td = tube.chart_domain(0);
  double previous_error = 0.;
  for(int n : {1, 2, 3, 8, 16})
  {
    const auto meshes = BS::make_chart_meshes(tube, n);
    BS_CHECK(meshes.size() == 1, "one tube chart mesh");
    if(meshes.size() != 1)
      return;
    const BS::Chart_mesh<K>& cm = meshes.front();
    std::ostringstream what;
    what << "hole tube mesh, resolution " << n;
    const std::vector<double> ys = check_tube_mesh_structure(cm, n, what.str());
    BS_CHECK(ys.size() == std::size_t(2 * n + 1), what.str() << ": " << ys.size() << " rows instead of " << 2 * n + 1);
    for(std::size_t j = 0; j < ys.size(); ++j)
      BS_CHECK(std::abs(ys[j] - (-1. + double(j) / n)) < 1e-15, what.str() << ": row " << j << " at y = " << ys[j]);
    // The rows are the rings of the two disks of the closed hole at the same
    // resolution (their images on the tube), and the triangles have the
    // disks' mean chart area: twice as many, the strip's chart area 4 pi
    // being twice the disks' 2 pi.
    const Hole closed(1., 1., 1., 1., 1., 1., 1.);
    std::size_t disk_faces = 0;
    for(const auto& dm : BS::make_chart_meshes(closed, n))
    {
      disk_faces += dm.mesh().number_of_faces();
      for(auto v : dm.mesh().vertices())
      {
        const double y = Hole::to_domain(dm.chart_point(v), BS::Hole_domain::Tube).y;
        BS_CHECK(std::any_of(ys.begin(), ys.end(), [&](double r) { return std::abs(r - y) < 1e-14; }),
                 what.str() << ": the disk ring r = " << y << " is not a row of the tube");
      }
    }
    BS_CHECK(cm.mesh().number_of_faces() == 2 * disk_faces,
             what.str() << ": " << cm.mesh().number_of_faces() << " faces, the disks " << disk_faces);

    // Placed by the open hole: positions, face normals agree with normal(),
    // and chart points of the faces (across the seam too) map onto the faces.
    const auto& m = cm.mesh();
    double h_max = 0.;
    for(auto e : m.edges())
      h_max = (std::max)(h_max, distance(m.point(m.source(m.halfedge(e))), m.point(m.target(m.halfedge(e)))));
    int agree = 0, total = 0, seam_faces = 0, seam_points = 0;
    double worst = 0., worst_plane = 0.;
    for(auto v : m.vertices())
      BS_CHECK(m.point(v) == tube.point(cm.chart_point(v)), what.str() << ": vertex position");
    for(auto f : m.faces())
    {
      const auto v = cm.face_vertices(f);
      const Point_3 &p0 = m.point(v[0]), &p1 = m.point(v[1]), &p2 = m.point(v[2]);
      const auto n3 = CGAL::normal(p0, p1, p2);
      ++total;
      if(n3 * tube.normal(cm.chart_point(f, {{1. / 3., 1. / 3., 1. / 3.}})) > 0.)
        ++agree;
      double xs[3] = {cm.chart_point(v[0]).x, cm.chart_point(v[1]).x, cm.chart_point(v[2]).x};
      const bool seam = (std::max)({xs[0], xs[1], xs[2]}) - (std::min)({xs[0], xs[1], xs[2]}) > M_PI;
      seam_faces += seam;
      const double unit_n = length<K>(n3);
      for(int s = 0; s < (seam ? 20 : 2); ++s)
      {
        double a = unit(rng), b = unit(rng);
        if(a + b > 1.) { a = 1. - a; b = 1. - b; }
        const std::array<double, 3> bc = {{1. - a - b, a, b}};
        const BS::Chart_point u = cm.chart_point(f, bc);
        BS_CHECK(u.chart == 0 && td.contains(u.x, u.y), what.str() << ": chart point (" << u.x << ", " << u.y
                                                                   << ") of a face out of the domain");
        const BS::Chart_point cu = tube.canonical_chart_point(u);
        BS_CHECK(cu.x >= 0. && cu.x < two_pi && td.contains(cu.x, cu.y), "canonical chart point of a face point");
        const Point_3 s3 = tube.point(u);
        const Point_3 lin(bc[0] * p0.x() + bc[1] * p1.x() + bc[2] * p2.x(),
                          bc[0] * p0.y() + bc[1] * p1.y() + bc[2] * p2.y(),
                          bc[0] * p0.z() + bc[1] * p1.z() + bc[2] * p2.z());
        const double e = distance(s3, lin);
        const double plane = std::abs(CGAL::to_double((s3 - p0) * n3)) / unit_n;
        worst = (std::max)(worst, e);
        worst_plane = (std::max)(worst_plane, plane);
        seam_points += seam;
      }
    }
    BS_CHECK(seam_faces == 2 * (2 * n) && seam_points == 20 * seam_faces, what.str() << ": " << seam_faces << " seam faces");
    BS_CHECK(agree == total, what.str() << ": " << agree << " of " << total << " faces agree with the hole's normal");
    // O(h^2): the curvature of this torus is at most 2 (inner radius 0.5)
    BS_CHECK(worst <= h_max * h_max && worst_plane <= h_max * h_max,
             what.str() << ": face points off the surface by " << worst << " (plane " << worst_plane << "), h = " << h_max);
    if(n == 16)
      BS_CHECK(worst < previous_error / 3., what.str() << ": error " << worst << " not O(h^2) after " << previous_error);
    previous_error = worst;
  }

  // The closed hole on the tube: its middle row collapses to the pinch point.
  {
    const Hole pinched(1.2, 0.9, 1.4, 1., 1., 1., 1., BS::Hole_domain::Tube);
    const auto meshes = BS::make_chart_meshes(pinched, 4);
    check_tube_mesh_structure(meshes.front(), 4, "closed hole tube mesh");
    const auto& m = meshes.front().mesh();
    const Point_3 pinch = pinched.point(BS::Chart_point(0, 0., 0.));
    int on_pinch = 0;
    for(auto v : m.vertices())
      on_pinch += (meshes.front().chart_point(v).y == 0. && m.point(v) == pinch);
    BS_CHECK(on_pinch == 16, "the middle row of the closed hole is the pinch point: " << on_pinch);
  }

  // Other y ranges, through Chart_mesh directly.
  {
    const BS::Chart_mesh<K> a(3, BS::Chart_domain::tube(-0.35, 1.), 4);
    BS_CHECK(a.chart_index() == 3, "chart index");
    const std::vector<double> ya = check_tube_mesh_structure(a, 4, "tube [-0.35, 1]");
    BS_CHECK(ya.size() == 7, "tube [-0.35, 1] rows: " << ya.size()); // -0.35, -0.175, 0, 0.25, ..., 1
    const BS::Chart_mesh<K> b(0, BS::Chart_domain::tube(0.2, 0.9), 5);
    const std::vector<double> yb = check_tube_mesh_structure(b, 5, "tube [0.2, 0.9]");
    BS_CHECK(yb.size() == 5 && std::count(yb.begin(), yb.end(), 0.) == 0, "tube [0.2, 0.9] rows: " << yb.size());
    const BS::Chart_mesh<K> c(0, BS::Chart_domain::tube(-2., 0.), 1);
    const std::vector<double> yc = check_tube_mesh_structure(c, 1, "tube [-2, 0]");
    BS_CHECK(yc.size() == 3, "tube [-2, 0] rows: " << yc.size());
    // copies keep their chart coordinates
    BS::Chart_mesh<K> copy = a;
    check_tube_mesh_structure(copy, 4, "copy of a tube mesh");
    int thrown = 0;
    for(const BS::Chart_domain& bad : {BS::Chart_domain::tube(1., -1.), BS::Chart_domain::tube(0.5, 0.5),
                                       BS::Chart_domain::tube(0., HUGE_VAL), BS::Chart_domain::tube(std::nan(""), 1.)})
    {
      try { BS::Chart_mesh<K>(0, bad, 4); } catch(const std::invalid_argument&) { ++thrown; }
    }
    BS_CHECK(thrown == 4, "empty or infinite tube ranges accepted: " << 4 - thrown);
  }

  // random_chart_point on the tube: uniform over the whole strip.
  {
    double y_lo = HUGE_VAL, y_hi = -HUGE_VAL, x_lo = HUGE_VAL, x_hi = -HUGE_VAL, x_sum = 0., y_sum = 0.;
    const int N = 20000;
    int below = 0;
    for(int i = 0; i < N; ++i)
    {
      const BS::Chart_point p = BS::random_chart_point(tube, 0, rng);
      BS_CHECK(p.chart == 0 && p.x >= 0. && p.x < two_pi && p.y >= -1. && p.y <= 1. && td.contains(p.x, p.y),
               "random tube point (" << p.x << ", " << p.y << ")");
      x_lo = (std::min)(x_lo, p.x); x_hi = (std::max)(x_hi, p.x);
      y_lo = (std::min)(y_lo, p.y); y_hi = (std::max)(y_hi, p.y);
      x_sum += p.x; y_sum += p.y;
      below += (p.y < -0.5);
    }
    BS_CHECK(x_lo < 0.01 && x_hi > two_pi - 0.01 && y_lo < -0.99 && y_hi > 0.99 &&
               std::abs(x_sum / N - M_PI) < 0.05 && std::abs(y_sum / N) < 0.02 && std::abs(below - N / 4) < N / 40,
             "random tube points not uniform: x in [" << x_lo << ", " << x_hi << "], y in [" << y_lo << ", " << y_hi
                                                      << "], means " << x_sum / N << ", " << y_sum / N);
  }

  // check_chart_consistency on the tube: one shift in x per point, none in y.
  for(const Params& q : parameter_sets(rng, false))
  {
    const Hole h = make_hole<K>(q, BS::Hole_domain::Tube);
    const BS::Chart_consistency_report r = BS::check_chart_consistency(h, 1500, 11);
    BS_CHECK(r.points_sampled == 1500 && r.pairs_checked == 1500,
             describe(h) << ": " << r.pairs_checked << " pairs checked (the y of a tube is not periodic)");
    BS_CHECK(r.max_relative_distance < 1e-12 && r.max_round_trip_error == 0. && r.max_normal_deviation < 1e-9,
             describe(h) << ": chart consistency " << r.max_relative_distance << " at (" << r.worst_point.x << ", "
                         << r.worst_point.y << "), normals " << r.max_normal_deviation);
    // the Jacobian check through random_chart_point alone
    std::vector<BS::Chart_point> pts;
    for(int i = 0; i < 1000; ++i)
      pts.push_back(BS::random_chart_point(h, 0, rng));
    check_hole_jacobian(h, pts);
  }
  // and the checker still catches a wrong column there
  Wrong_jacobian_hole<K> wrong(1., 2., 1.5, 1.6, 1.2, 0.7, 0.8, BS::Hole_domain::Tube);
  wrong.column = BS::Hole_component<K>::A3;
  std::vector<BS::Chart_point> pts;
  for(int i = 0; i < 1000; ++i)
    pts.push_back(BS::random_chart_point(wrong, 0, rng));
  const BS::Jacobian_check_report r = BS::check_jacobian(wrong, pts);
  BS_CHECK(r.max_relative_error > 1e-5 && r.worst_parameter == BS::Hole_component<K>::A3,
           "the Jacobian checker missed a wrong a3 column on random tube points: " << r.max_relative_error);
}

// ---------------------------------------------------------------------------
// (8) Errors, the chart descriptions, and the parameter table.

template <class K>
void test_errors_and_domains()
{
  typedef BS::Hole_component<K> Hole;
  int thrown = 0;
  try { Hole(1., 1., -1.); } catch(const std::invalid_argument&) { ++thrown; }
  try { Hole(1., 1., 1., 0.5, 1., 1., 1., BS::Hole_domain::Tube); } catch(const std::invalid_argument&) { ++thrown; }
  try { Hole(1., 1., 1., 1., 0.99); } catch(const std::invalid_argument&) { ++thrown; }
  try { Hole(1., 1., 1., 1., 1., 2.5); } catch(const std::invalid_argument&) { ++thrown; }
  try { Hole(1., 1., 1., 1., 1., 1., 0.); } catch(const std::invalid_argument&) { ++thrown; }
  try { Hole(std::nan(""), 1., 1.); } catch(const std::invalid_argument&) { ++thrown; }
  BS_CHECK(thrown == 6, "out-of-bound parameters accepted: " << 6 - thrown);
  std::string message;
  try { Hole(1., 1., 1., 2., 1.); } catch(const std::logic_error& e) { message = e.what(); }
  BS_CHECK(message.find("Two_disks") != std::string::npos && message.find("a4 = 2") != std::string::npos,
           "an open hole on two disks accepted, or an unclear message: '" << message << "'");
  try { Hole(1., 1., -1.); } catch(const std::invalid_argument& e) { message = e.what(); }
  BS_CHECK(message.find("Hole_component") != std::string::npos && message.find("a3") != std::string::npos,
           "message: '" << message << "'");
  // a failed set_parameters leaves the component unchanged
  Hole h(1., 2., 3., 1.5, 1.5, 1., 1., BS::Hole_domain::Tube);
  auto q = h.parameters();
  q[Hole::E2] = 3.;
  try { h.set_parameters(q); } catch(const std::invalid_argument&) {}
  BS_CHECK(h.parameters()[Hole::E2] == 1. && h.parameters()[Hole::A4] == 1.5, "parameters changed by a failed set");
  // the tube chart: x periodic with period 2 pi, y in [-1, 1]
  const BS::Chart_domain td = h.chart_domain(0);
  BS_CHECK(td.kind == BS::Chart_kind::Tube && td.period() == two_pi && td.x_period() == two_pi &&
             td.y_period() == 0. && td.y_min == -1. && td.y_max == 1. && td.contains(-7., 1.) &&
             td.contains(20., -1.) && !td.contains(0., 1.01) && !td.contains(0., -1.01) &&
             !td.contains(HUGE_VAL, 0.) && !td.contains(0., std::nan("")), "tube domain");
  const Hole d;
  BS_CHECK(d.domain() == BS::Hole_domain::Two_disks && d.hole_is_closed(), "default: closed hole on two disks");
  for(std::size_t c : {0u, 1u})
  {
    const BS::Chart_domain dd = d.chart_domain(c);
    BS_CHECK(dd.kind == BS::Chart_kind::Disk && dd.radius == 1. && dd.period() == 0. && dd.x_period() == 0. &&
               dd.y_period() == 0. && dd.contains(0.6, -0.8) && !dd.contains(0.8, 0.8), "disk chart domain");
  }
  // the factories of the three kinds
  const BS::Chart_domain torus = BS::Chart_domain::torus(), disk = BS::Chart_domain::disk(1.2),
                         strip = BS::Chart_domain::tube(-0.5, 2.);
  BS_CHECK(torus.kind == BS::Chart_kind::Torus && torus.x_period() == two_pi && torus.y_period() == two_pi &&
             torus.contains(-9., 17.) && !torus.contains(0., HUGE_VAL), "torus domain");
  BS_CHECK(disk.kind == BS::Chart_kind::Disk && disk.radius == 1.2 && disk.y_min == -1.2 && disk.y_max == 1.2 &&
             disk.contains(0., 1.2) && !disk.contains(1., 1.), "disk domain");
  BS_CHECK(strip.kind == BS::Chart_kind::Tube && strip.y_min == -0.5 && strip.y_max == 2. && strip.contains(100., 2.) &&
             !strip.contains(0., -0.6), "tube(-0.5, 2)");
  thrown = 0;
  try { Hole::to_domain(BS::Chart_point(2, 0., 0.), BS::Hole_domain::Tube); } catch(const std::invalid_argument&) { ++thrown; }
  try { Hole::to_domain(BS::Chart_point(1, 0., 0.), BS::Hole_domain::Two_disks); } catch(const std::invalid_argument&) { ++thrown; }
  BS_CHECK(thrown == 2, "to_domain with a chart of neither domain");
  // the parameter table: the toroid's, the hole starting closed
  typedef BS::Superquadric_toroid<K> Toroid;
  for(int i = 0; i < Hole::number_of_parameters; ++i)
  {
    BS_CHECK(std::string(Hole::parameter_name(i)) == Toroid::parameter_name(i) &&
               Hole::parameter_lower_bound(i) == Toroid::parameter_lower_bound(i) &&
               Hole::parameter_upper_bound(i) == Toroid::parameter_upper_bound(i) &&
               Hole::parameter_info(i).kind == Toroid::parameter_info(i).kind, "parameter " << i);
    BS_CHECK(Hole::parameter_default_value(i) ==
               ((i == Hole::A4 || i == Hole::A5) ? 1. : Toroid::parameter_default_value(i)), "default " << i);
  }
}

template <class K>
void run_with_kernel(const char* kernel)
{
  std::mt19937_64 rng(20261201);
  const int before = blended_shape_test::failures();
  test_domain_switch<K>(rng);
  test_pinch_point<K>(rng);
  test_jacobians<K>(rng);
  test_chart_consistency<K>(rng);
  test_normals<K>(rng);
  test_boundary_circles<K>(rng);
  test_tube_chart_mesh<K>(rng);
  test_errors_and_domains<K>();
  blended_shape_test::report(std::string("hole component with ") + kernel, before);
}

// Every check of this part.
void run_all()
{
  blended_shape_test::for_each_kernel([](auto kernel, const char* name) { run_with_kernel<decltype(kernel)>(name); });
}

} // namespace hole_component_checks

#endif // BLENDED_SHAPE_HOLE_COMPONENT_CHECKS_H
