// SPDX-License-Identifier: LGPL-3.0-or-later
// The hole component (sec. 4.2, App. B.2, eq. 32 and 33): its two domains,
// the domain switch that moves no surface point while the hole is closed,
// the pinch point, the exact parameter Jacobian, the tube's periodic seam,
// normals and chart orientation, the circles where the hole is glued to the
// base, and the errors, with both supported kernels.
#include "test_util.h"

#include <CGAL/Blended_shape/Chart_mesh.h>
#include <CGAL/Blended_shape/Hole_component.h>
#include <CGAL/Blended_shape/Superquadric_toroid.h>
#include <CGAL/Blended_shape/check_primitive.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace BS = CGAL::Blended_shapes;

namespace {

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

// A uniform chart point of chart c of the hole's current domain (the tube
// is a strip that random_chart_point() does not know yet).
template <class Hole>
BS::Chart_point random_hole_point(const Hole& h, std::size_t c, std::mt19937_64& rng)
{
  const BS::Hole_chart_domain d = h.hole_chart_domain(c);
  if(d.domain == BS::Hole_domain::Tube)
  {
    std::uniform_real_distribution<double> unit(0., 1.);
    return BS::Chart_point(c, d.period * unit(rng), d.y_min + (d.y_max - d.y_min) * unit(rng));
  }
  return BS::random_chart_point(h, c, rng);
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
      pts.push_back(random_hole_point(h, c, rng));
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
      grid.push_back(random_hole_point(tube, 0, rng));
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
      const BS::Chart_point p = random_hole_point(disks, std::size_t(i % 2), rng);
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
      pts.push_back(random_hole_point(tube, 0, rng));
    const double size = shape_size(tube, pts);
    double dist = 0., ndev = 0., round_trip = 0.;
    std::size_t pairs = 0;
    for(const BS::Chart_point& p : pts)
    {
      BS::Chart_point o;
      BS_CHECK(!tube.to_chart(p, 1, o), "the tube has one chart");
      const BS::Chart_point cp = tube.canonical_chart_point(p);
      BS_CHECK(cp.chart == 0 && cp.x >= 0. && cp.x < two_pi && cp.y == p.y &&
                 tube.hole_chart_domain(0).contains(cp.x, cp.y), "canonical point out of the domain");
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
      const BS::Chart_point u = random_hole_point(h, c, rng);
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
    const BS::Chart_point t = random_hole_point(h, 0, rng);
    const double u = (1. + t.y / 2.) * M_PI, v = t.x;
    const typename K::Point_3 e(1.3 * (1.4 + std::cos(u)) * std::cos(v), 0.7 * (1.8 + std::cos(u)) * std::sin(v),
                                1.1 * std::sin(u));
    BS_CHECK(distance(h.point(t), e) < 1e-14, "eq. 33 at (" << t.x << ", " << t.y << ")");
  }
}

// ---------------------------------------------------------------------------
// (7) Errors, the chart descriptions, and the parameter table.

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
  // the tube has no Chart_domain yet: chart_domain() says so instead of lying
  bool refused = false;
  try { h.chart_domain(0); } catch(const std::logic_error&) { refused = true; }
  BS_CHECK(refused, "chart_domain() of the tube");
  const BS::Hole_chart_domain td = h.hole_chart_domain(0);
  BS_CHECK(td.domain == BS::Hole_domain::Tube && td.period == two_pi && td.y_min == -1. && td.y_max == 1. &&
             td.contains(-7., 1.) && !td.contains(0., 1.01) && !td.contains(HUGE_VAL, 0.), "tube domain");
  const Hole d;
  BS_CHECK(d.domain() == BS::Hole_domain::Two_disks && d.hole_is_closed(), "default: closed hole on two disks");
  BS_CHECK(d.chart_domain(1).kind == BS::Chart_kind::Disk && d.chart_domain(1).radius == 1., "disk chart domain");
  const BS::Hole_chart_domain dd = d.hole_chart_domain(0);
  BS_CHECK(dd.domain == BS::Hole_domain::Two_disks && dd.radius == 1. && dd.period == 0. && dd.contains(0.6, -0.8) &&
             !dd.contains(0.8, 0.8), "disk domain");
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
void run_all(const char* kernel)
{
  std::mt19937_64 rng(20261201);
  const int before = blended_shape_test::failures();
  test_domain_switch<K>(rng);
  test_pinch_point<K>(rng);
  test_jacobians<K>(rng);
  test_chart_consistency<K>(rng);
  test_normals<K>(rng);
  test_boundary_circles<K>(rng);
  test_errors_and_domains<K>();
  std::cout << "hole component with " << kernel
            << (blended_shape_test::failures() == before ? ": SUCCESS" : ": FAILED") << std::endl;
}

} // namespace

int main()
{
  run_all<CGAL::Simple_cartesian<double>>("Simple_cartesian<double>");
  run_all<CGAL::Exact_predicates_inexact_constructions_kernel>("Epick");
  blended_shape_test::report("test_hole_component");
  return blended_shape_test::exit_code();
}
