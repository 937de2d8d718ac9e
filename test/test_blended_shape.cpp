// SPDX-License-Identifier: LGPL-3.0-or-later
// Blended shapes (sec. 3, eq. 3, 10, 11): the model Jacobian against finite
// differences in strips, disks and nested blends; split and hole-switch
// invariance; continuity across strip boundaries; the quotient's canonical
// points; evolution: add_part / add_hole at h = 1 and remove_component()
// move no point, removal renumbers, every documented error throws and leaves
// the shape unchanged, regions in discarded parts are refused, a part on a
// part; the per-component pieces (sec. 3.3) against a brute-force
// classification. Both supported kernels.
#include "test_kernels.h"
#include "test_util.h"
#include "blended_shape_test_util.h"

// The program's other parts (see main()).
#include "blended_shape_io_checks.h"
#include "blended_shape_mesh_io_checks.h"
#include "blending_hierarchy_checks.h"
#include "blending_region_checks.h"
#include "hole_component_checks.h"
#include "quotient_domain_checks.h"

#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>

#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/helpers.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace BS = CGAL::Blended_shapes;

namespace {

using blended_shape_test::parameter_index;
using blended_shape_test::set_parameter;
using blended_shape_test::perturb_component;

typedef BS::Ellipse_blending_region Region;

template <class K>
Eigen::Vector3d eig(const typename K::Point_3& p)
{
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

template <class K>
using Shape = BS::Blended_shape<K>;

template <class K>
Shape<K> sphere(double e1 = 0.8, double e2 = 1.1)
{
  return Shape<K>(BS::Superquadric_ellipsoid<K>(1.0, 0.9, 1.1, e1, e2));
}

// A gradual part on chart 1, tilted and off-centre (it joins shapes that differ).
template <class K>
void add_tilted_part(Shape<K>& s)
{
  s.add_part(0, 1, Region::make_parameters(-0.2, 0.25, 0.32, 0.28, -0.4, 0.85, 1.), 0.07,
             BS::Superquadric_ellipsoid<K>(0.5, 0.45, 0.8, 0.6, 1.2), "superquadric_ellipsoid",
             Eigen::Vector3d(0.1, -0.2, -0.9), Eigen::Vector4d(0.95, 0.2, -0.1, 0.05), 0,
             Region::make_parameters(0.05, 0., 0.55, 0.5, 0.1, 1., 0.), 0.1);
}

// A unit sphere with a closed hole from near the north pole to near the south pole.
template <class K>
Shape<K> sphere_with_pole_hole()
{
  Shape<K> s = sphere<K>(1., 1.);
  s.add_hole(BS::Shape_point(0, BS::Chart_point(0, 0.05, 0.)), BS::Shape_point(0, BS::Chart_point(1, 0., 0.05)), 0.3,
             0.08, 0.1);
  return s;
}

// Configurations used by several tests.
template <class K>
std::map<std::string, std::function<Shape<K>()>> configurations()
{
  std::map<std::string, std::function<Shape<K>()>> m;
  m["split"] = [] {
    Shape<K> s = sphere<K>();
    s.split(0, 0, Region::make_parameters(0.15, -0.1, 0.5, 0.42, 0.3, 0.9, 0.), 0.08);
    perturb_component(s, 1, 1.);
    return s;
  };
  m["seam_split"] = [] { // a region across the equator, in chart 0's margin
    Shape<K> s = sphere<K>();
    s.split(0, 0, Region::make_parameters(0.93, 0.1, 0.12, 0.16, 0.2, 0.8, 0.), 0.035);
    perturb_component(s, 1, 0.5);
    return s;
  };
  m["part"] = [] {
    Shape<K> s = sphere<K>();
    add_tilted_part(s);
    set_parameter(s, "b0.h", 0.4);
    return s;
  };
  m["nested"] = [] {
    Shape<K> s = sphere<K>();
    s.split(0, 0, Region::make_parameters(0.15, -0.1, 0.5, 0.42, 0.3, 0.9, 0.), 0.08);
    perturb_component(s, 1, 0.6);
    s.split(1, 0, Region::make_parameters(0.2, -0.05, 0.13, 0.11, -0.2, 0.7, 0.), 0.04);
    perturb_component(s, 2, 0.5);
    add_tilted_part(s);
    set_parameter(s, "b2.h", 0.6);
    return s;
  };
  m["hole_disks"] = [] {
    Shape<K> s = sphere_with_pole_hole<K>();
    set_parameter(s, "b0.h", 0.5);
    set_parameter(s, "b1.h", 0.3);
    set_parameter(s, "b0.w", 0.9);
    set_parameter(s, "b1.w", 0.8);
    return s;
  };
  m["hole_tube"] = [] {
    Shape<K> s = sphere_with_pole_hole<K>();
    blended_shape_test::open_pole_hole(s);
    return s;
  };
  return m;
}

// A uniform random point of chart c of component k.
template <class K>
BS::Shape_point random_point(const Shape<K>& s, std::size_t k, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u01(0., 1.);
  const BS::Component_shape& cs = s.component(k).shape();
  const std::size_t c = std::size_t(u01(rng) * double(cs.number_of_charts())) % cs.number_of_charts();
  const BS::Chart_domain d = cs.chart_domain(c);
  if(d.kind == BS::Chart_kind::Disk)
    for(;;)
    {
      const double x = d.radius * (2. * u01(rng) - 1.), y = d.radius * (2. * u01(rng) - 1.);
      if(d.contains(x, y))
        return BS::Shape_point(k, BS::Chart_point(c, x, y));
    }
  const double x = 2. * M_PI * u01(rng);
  double y = 2. * M_PI * u01(rng);
  if(d.kind != BS::Chart_kind::Torus)
    y = -1. + 2. * u01(rng);
  return BS::Shape_point(k, BS::Chart_point(c, x, y));
}

enum Place { Plain, Strip, Disk };

// Whether chart point u of component c is near a crease of its primitive:
// an ellipsoid chart's axes map to the coordinate planes, where the signed
// powers |sin omega|^e2, |cos omega|^e2 are not twice differentiable for
// e2 != 1 (and the pole, where |cos eta|^e1 is not, lies on both): central
// differences lose their accuracy there (truncation error ~ h^(e - 1)), the
// analytic Jacobian does not.
template <class K>
bool near_crease(const Shape<K>& s, std::size_t c, const BS::Chart_point& u)
{
  if(!s.component(c).shape().template primitive<BS::Superquadric_ellipsoid<K>>())
    return false;
  return std::abs(u.x) < 1e-3 || std::abs(u.y) < 1e-3;
}

// Where a canonical point lies, with the margin that keeps finite differences
// on one side of every boundary (strip edges, disk centres).
template <class K>
Place classify(const Shape<K>& s, const BS::Shape_point& p, bool& near_boundary)
{
  near_boundary = false;
  for(std::size_t b = 0; b < s.number_of_blends(); ++b)
  {
    const BS::Blend& B = s.blend(b);
    if(B.base_component() != p.component || B.base_region().chart() != p.u.chart)
      continue;
    const Eigen::Vector2d v(p.u.x, p.u.y);
    const BS::Region_location loc = B.base_region().locate(v);
    if(loc.side == BS::Region_side::Retained)
    {
      near_boundary = bool(B.base_region().strip_coordinates(v + Eigen::Vector2d(1e-4, 0.)));
      continue;
    }
    const bool tube = s.component(B.added_component()).shape().number_of_charts() == 1 &&
                      B.added_side().kind() == BS::Added_side::Hole_end;
    if(loc.side == BS::Region_side::Strip)
    {
      const BS::Chart_point u2 = B.added_side().strip_point(-loc.coordinates.d, loc.coordinates.theta, tube);
      near_boundary = std::abs(loc.coordinates.d) > 1. - 1e-3 || near_crease(s, p.component, p.u) ||
                      near_crease(s, B.added_component(), u2);
      return Strip;
    }
    const std::optional<BS::Core_coordinates> k = B.base_region().core_coordinates(v, -1., B.core_stretch());
    near_boundary = !k || k->t < 0.05 || k->t > 0.995 || near_crease(s, p.component, p.u) ||
                    near_crease(s, B.added_component(), B.added_side().core_point(k->t, k->theta, B.core_stretch()));
    return Disk;
  }
  near_boundary = near_boundary || near_crease(s, p.component, p.u);
  return Plain;
}

// The model Jacobian against central differences, at random points and at
// points sampled in every strip and disk (base and added side).
template <class K>
void test_jacobian(const std::string& name, Shape<K> s, std::mt19937& rng)
{
#ifdef BLENDED_SHAPE_REDUCED_TESTS
  const int random_points = 60, per_blend = 60; // sanitizer builds: same checks, fewer points
  const std::size_t blended_points = 100;
#else
  const int random_points = 300, per_blend = 280;
  const std::size_t blended_points = 500; // in strips and disks (the issue asks for >= 500)
#endif
  std::vector<BS::Shape_point> pts;
  for(int i = 0; i < random_points; ++i)
    pts.push_back(random_point(s, std::size_t(rng() % s.number_of_components()), rng));
  std::uniform_real_distribution<double> u01(0., 1.);
  for(std::size_t b = 0; b < s.number_of_blends(); ++b)
  {
    const BS::Blend& B = s.blend(b);
    const bool tube = B.added_side().kind() == BS::Added_side::Hole_end &&
                      s.component(B.added_component()).shape().number_of_charts() == 1;
    for(int i = 0; i < per_blend; ++i)
    {
      const double d = -1. + 2. * u01(rng), th = 2. * M_PI * u01(rng);
      const Eigen::Vector2d v = B.base_region().strip_point(d, th);
      pts.push_back(BS::Shape_point(B.base_component(), BS::Chart_point(B.base_region().chart(), v.x(), v.y())));
      pts.push_back(BS::Shape_point(B.added_component(), B.added_side().strip_point(d, th, tube)));
      if(B.is_gradual())
      {
        const Eigen::Vector2d w = B.base_region().core_point(u01(rng), th, -1., B.core_stretch());
        pts.push_back(BS::Shape_point(B.base_component(), BS::Chart_point(B.base_region().chart(), w.x(), w.y())));
        pts.push_back(BS::Shape_point(B.added_component(), B.added_side().core_point(u01(rng), th, B.core_stretch())));
      }
    }
  }
  const Eigen::VectorXd q0 = s.parameters();
  // The shapes moved by +-h along each parameter, once for all points.
  std::vector<Shape<K>> plus, minus;
  std::vector<double> steps;
  for(std::size_t i = 0; i < s.number_of_parameters(); ++i)
  {
    const double h = 1e-6 * std::max(1., std::abs(q0[Eigen::Index(i)]));
    Eigen::VectorXd qp = q0, qm = q0;
    qp[Eigen::Index(i)] += h;
    qm[Eigen::Index(i)] -= h;
    plus.push_back(s);
    minus.push_back(s);
    if(!s.is_fixed_parameter(i))
    {
      plus.back().set_parameters(qp);
      minus.back().set_parameters(qm);
    }
    steps.push_back(h);
  }
  std::size_t counts[3] = {0, 0, 0};
  double worst = 0., worst_chart = 0.;
  std::string worst_what, worst_chart_what;
  for(const BS::Shape_point& p0 : pts)
  {
    const std::optional<BS::Shape_point> cp = s.canonical_point(p0);
    if(!cp)
      continue;
    bool near = false;
    const Place place = classify(s, *cp, near);
    if(near)
      continue;
    ++counts[place];
    const Eigen::MatrixXd J = s.dense_jacobian(*cp);
    const double scale = eig<K>(s.point(*cp)).norm();
    // The chart Jacobian (ds/du at the canonical point) against central
    // differences of point() in the canonical point's chart.
    {
      Eigen::Matrix<double, 3, 2> D;
      BS::Shape_point c2;
      s.point_and_chart_jacobian(p0, D, &c2);
      BS_CHECK(c2.component == cp->component && c2.u.chart == cp->u.chart && c2.u.x == cp->u.x && c2.u.y == cp->u.y,
               name << ": point_and_chart_jacobian() reports another canonical point");
      const double h = 1e-6;
      for(int k = 0; k < 2; ++k)
      {
        auto at = [&](double sign) {
          return eig<K>(s.point(BS::Shape_point(cp->component, BS::Chart_point(cp->u.chart, cp->u.x + (k == 0 ? sign * h : 0.),
                                                                                 cp->u.y + (k == 1 ? sign * h : 0.)))));
        };
        const Eigen::Vector3d fd = (at(1.) - at(-1.)) / (2. * h);
        const double err = (D.col(k) - fd).norm() / std::max(fd.norm(), 1e-4 * scale);
        if(err > worst_chart)
        {
          worst_chart = err;
          std::ostringstream w;
          w << "d/du" << k << " at component " << cp->component << " chart " << cp->u.chart << " (" << cp->u.x << ", "
            << cp->u.y << "), place " << place << ": analytic " << D.col(k).transpose() << " vs FD " << fd.transpose();
          worst_chart_what = w.str();
        }
      }
    }
    for(std::size_t i = 0; i < s.number_of_parameters(); ++i)
    {
      if(s.is_fixed_parameter(i))
      {
        BS_CHECK(J.col(Eigen::Index(i)).norm() == 0., name << ": fixed parameter " << s.parameter_name(i) << " moves the point");
        continue;
      }
      const Eigen::Vector3d fd = (eig<K>(plus[i].point(*cp)) - eig<K>(minus[i].point(*cp))) / (2. * steps[i]);
      const double err = (J.col(Eigen::Index(i)) - fd).norm() / std::max(fd.norm(), 1e-4 * scale);
      if(err > worst)
      {
        worst = err;
        std::ostringstream w;
        w << s.parameter_name(i) << " at component " << cp->component << " chart " << cp->u.chart << " (" << cp->u.x
          << ", " << cp->u.y << "), place " << place << ": analytic " << J.col(Eigen::Index(i)).transpose()
          << " vs FD " << fd.transpose();
        worst_what = w.str();
      }
    }
  }
  std::cout << "  " << name << ": " << counts[Plain] << " plain, " << counts[Strip] << " strip, " << counts[Disk]
            << " disk points; worst relative Jacobian error " << worst << ", chart Jacobian " << worst_chart << std::endl;
  BS_CHECK(worst < 1e-5, name << ": Jacobian error " << worst << ": " << worst_what);
  BS_CHECK(worst_chart < 1e-5, name << ": chart Jacobian error " << worst_chart << ": " << worst_chart_what);
  BS_CHECK(counts[Strip] >= std::size_t(per_blend), name << ": too few strip points");
  BS_CHECK(counts[Strip] + counts[Disk] >= blended_points, name << ": too few points in strips and disks");
}

// The unified mesh of the whole model: closed, manifold, oriented outward,
// without self-intersections, with Euler characteristic 2 - 2 genus.
template <class K>
void check_unified_mesh(const std::string& name, const Shape<K>& s, int expected_genus)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  typedef CGAL::Surface_mesh<typename K::Point_3> Mesh;
  Mesh m;
  try
  {
    m = BS::make_unified_mesh(s, 20, 3);
  }
  catch(const std::exception& e)
  {
    BS_CHECK(false, name << ": make_unified_mesh threw: " << e.what());
    return;
  }
  const long chi = long(m.number_of_vertices()) - long(m.number_of_edges()) + long(m.number_of_faces());
  std::cout << "  unified mesh " << name << ": " << m.number_of_vertices() << " vertices, " << m.number_of_faces()
            << " faces, chi " << chi << std::endl;
  BS_CHECK(CGAL::is_valid_polygon_mesh(m), name << ": invalid mesh");
  BS_CHECK(CGAL::is_closed(m), name << ": not closed");
  Mesh copy = m;
  BS_CHECK(PMP::duplicate_non_manifold_vertices(copy) == 0, name << ": non-manifold vertices");
  BS_CHECK(s.genus() == std::size_t(expected_genus), name << ": genus " << s.genus());
  BS_CHECK(chi == 2 - 2 * expected_genus, name << ": Euler characteristic " << chi << ", expected " << 2 - 2 * expected_genus);
  const bool self = PMP::does_self_intersect(m);
  BS_CHECK(!self, name << ": self-intersections");
  if(!self)
    BS_CHECK(PMP::is_outward_oriented(m), name << ": not outward oriented");
}

template <class K>
void test_unified_meshes()
{
  auto configs = configurations<K>();
  check_unified_mesh<K>("sphere", sphere<K>(), 0);
  // The Jacobian configurations move the added components far enough to fold
  // their narrow strips (a true self-intersection of the model: the offset
  // between the two sides times the slope of alpha exceeds the strip's own
  // width); here they move by a tenth of that.
  Shape<K> split = sphere<K>();
  split.split(0, 0, Region::make_parameters(0.15, -0.1, 0.5, 0.42, 0.3, 0.9, 0.), 0.08);
  perturb_component(split, 1, 0.1);
  check_unified_mesh<K>("split", split, 0);
  check_unified_mesh<K>("seam_split", configs["seam_split"](), 0);
  // A nose on the south pole: the part's lower cap replaces the base's.
  auto add_nose = [](Shape<K>& x) {
    x.add_part(0, 1, Region::make_parameters(0., 0.05, 0.35, 0.33, 0., 0.9, 1.), 0.07,
               BS::Superquadric_ellipsoid<K>(0.4, 0.42, 0.6, 0.9, 1.), "superquadric_ellipsoid",
               Eigen::Vector3d(0.02, 0., -0.9), Eigen::Vector4d(1., 0.02, 0., 0.), 1,
               Region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1);
  };
  Shape<K> part = sphere<K>();
  add_nose(part);
  set_parameter(part, "b0.h", 0.);
  part.finish_gradual_blend(0);
  check_unified_mesh<K>("part", part, 0);
  Shape<K> nested = split; // three levels: a split of the split-off cap, and a gradual part
  nested.split(1, 0, Region::make_parameters(0.2, -0.05, 0.13, 0.11, -0.2, 0.7, 0.), 0.04);
  perturb_component(nested, 2, 0.1);
  add_nose(nested);
  set_parameter(nested, "b2.h", 0.6);
  check_unified_mesh<K>("nested (three levels)", nested, 0);
  set_parameter(nested, "b2.h", 0.);
  nested.finish_gradual_blend(2);
  check_unified_mesh<K>("nested, part finished", nested, 0);
  check_unified_mesh<K>("pinched hole (two disks)", configs["hole_disks"](), 0);
  check_unified_mesh<K>("one hole (torus)", configs["hole_tube"](), 1);
  Shape<K> two(BS::Superquadric_ellipsoid<K>(1.6, 1., 0.6, 1., 1.));
  for(double x : {-0.45, 0.45})
    two.add_hole(BS::Shape_point(0, BS::Chart_point(0, x, 0.)), BS::Shape_point(0, BS::Chart_point(1, x, 0.)), 0.2,
                 0.06, 0.1);
  for(std::size_t b = 0; b < 4; ++b)
    set_parameter(two, "b" + std::to_string(b) + ".h", 0.);
  // Opened to a4 = a5 = 1.15: at 1.3 these holes, near the rim of a flat
  // body, fold their strips (the blended surface itself turns over, its
  // normals flip: the offset between the two sides exceeds what the strip
  // width can bend), so any mesh of it self-intersects.
  for(std::size_t h = 0; h < 2; ++h)
  {
    two.switch_hole_to_tube(h);
    const std::string c = "c" + std::to_string(two.holes()[h].component);
    set_parameter(two, c + ".a4", 1.15);
    set_parameter(two, c + ".a5", 1.15);
  }
  check_unified_mesh<K>("two holes (genus 2)", two, 2);
}

// "No vertex moves" (split, finish_gradual_blend, hole domain switch): every
// vertex of every chart mesh of `before` that is on its surface, mapped into
// `after` by `to_after` (one or more images: a split also gives the copy's
// point), is at the same place where it is on the surface of `after`
// (relative 1e-12).
template <class K>
void check_no_vertex_moves(const std::string& name, const Shape<K>& before, const Shape<K>& after,
                           const std::function<std::vector<BS::Shape_point>(const BS::Shape_point&)>& to_after)
{
  std::size_t compared = 0;
  double worst = 0.;
  const BS::Blended_shape_pieces<K> pieces(before, 16);
  for(const auto& piece : pieces.pieces())
    for(auto v : piece.mesh.mesh().vertices())
    {
      const BS::Shape_point p(piece.component, piece.mesh.chart_point(v));
      if(!before.is_on_surface(p))
        continue;
      const Eigen::Vector3d x = eig<K>(before.point(p));
      for(const BS::Shape_point& q : to_after(p))
      {
        if(!after.is_on_surface(q))
          continue;
        ++compared;
        worst = std::max(worst, (eig<K>(after.point(q)) - x).norm() / std::max(1., x.norm()));
      }
    }
  std::cout << "  " << name << ": " << compared << " vertices compared, largest relative motion " << worst << std::endl;
  BS_CHECK(compared >= 500, name << ": only " << compared << " vertices compared");
  BS_CHECK(worst <= 1e-12, name << ": a vertex moved by " << worst << " (relative)");
}

template <class K>
void test_no_vertex_moves()
{
  auto same = [](const BS::Shape_point& p) { return std::vector<BS::Shape_point>{p}; };
  // Split: the base keeps its points, and the copy (last component) takes the
  // base's place point for point.
  auto split_images = [](std::size_t c, std::size_t copy) {
    return [c, copy](const BS::Shape_point& p) {
      std::vector<BS::Shape_point> r{p};
      if(p.component == c)
        r.push_back(BS::Shape_point(copy, p.u));
      return r;
    };
  };
  {
    const Shape<K> before = sphere<K>();
    Shape<K> after = before;
    after.split(0, 0, Region::make_parameters(0.15, -0.1, 0.5, 0.42, 0.3, 0.9, 0.), 0.08);
    check_no_vertex_moves<K>("split", before, after, split_images(0, 1));
    Shape<K> seam = before;
    seam.split(0, 0, Region::make_parameters(0.93, 0.1, 0.12, 0.16, 0.2, 0.8, 0.), 0.035);
    check_no_vertex_moves<K>("split across the seam", before, seam, split_images(0, 1));
  }
  {
    // A split of the root of a model that already has a gradual part.
    Shape<K> before = sphere<K>();
    add_tilted_part(before);
    set_parameter(before, "b0.h", 0.4);
    Shape<K> after = before;
    after.split(0, 0, Region::make_parameters(0.15, -0.1, 0.5, 0.42, 0.3, 0.9, 0.), 0.08);
    check_no_vertex_moves<K>("split next to a part", before, after, split_images(0, 2));
    // Finishing a part at h = 0 (disk -> annulus) moves nothing either. The
    // part's e1 = 0.6 would make its pole non-Lipschitz (a chart rounding
    // error of 1e-17 moves the point by 1e-17^0.6): e1 = 1 for this check.
    set_parameter(before, "b0.h", 0.);
    set_parameter(before, "c1.e1", 1.);
    after = before;
    after.finish_gradual_blend(0);
    check_no_vertex_moves<K>("finish_gradual_blend", before, after, same);
  }
  {
    // The hole domain switch at a4 = a5 = 1 (sec. 4.2): the hole's
    // two-disk points go to the same points of its tube domain.
    Shape<K> before = sphere_with_pole_hole<K>();
    set_parameter(before, "b0.h", 0.);
    set_parameter(before, "b1.h", 0.);
    Shape<K> after = before;
    after.switch_hole_to_tube(0);
    const std::size_t hc = before.holes()[0].component;
    check_no_vertex_moves<K>("hole domain switch", before, after, [hc](const BS::Shape_point& p) {
      if(p.component != hc)
        return std::vector<BS::Shape_point>{p};
      return std::vector<BS::Shape_point>{
          BS::Shape_point(hc, BS::Hole_component<K>::to_domain(p.u, BS::Hole_domain::Tube))};
    });
  }
}

// Continuity across the strip boundaries d = +-1 of every blend, along the
// strip's normal lines at fixed theta: g(d) is the surface point at base
// strip coordinate d; past d = -1 the surface continues on the added side
// (an annulus: its strip point at -d) or in the base disk (a gradual blend).
// C0 and C1 (one-sided difference quotients agree) everywhere: alpha_0 is
// C1, and so is beta, also where it switches from strip to disk coordinates
// at d = -1 of a gradual blend (the disk coordinates end with the strip's
// transversal velocity: Ellipse_blending_region::core_point()).
template <class K>
void test_continuity(const std::string& name, const Shape<K>& s)
{
  const double eps = 1e-4;
  double worst_c0 = 0., worst_c1 = 0., worst_c1_disk = 0.;
  std::size_t lines = 0;
  for(std::size_t b = 0; b < s.number_of_blends(); ++b)
  {
    const BS::Blend& B = s.blend(b);
    const BS::Ellipse_blending_region& R = B.base_region();
    const bool tube = B.added_side().kind() == BS::Added_side::Hole_end &&
                      s.component(B.added_component()).shape().number_of_charts() == 1;
    for(int k = 0; k < 48; ++k)
    {
      const double theta = 2. * M_PI * (k + 0.37) / 48.;
      auto g = [&](double d) {
        if(d < -1. && !B.is_gradual())
          return eig<K>(s.point(BS::Shape_point(B.added_component(), B.added_side().strip_point(-d, theta, tube))));
        const Eigen::Vector2d u = R.strip_point(d, theta);
        return eig<K>(s.point(BS::Shape_point(B.base_component(), BS::Chart_point(R.chart(), u.x(), u.y()))));
      };
      for(double edge : {1., -1.})
      {
        const Eigen::Vector3d x0 = g(edge), xp = g(edge + eps), xpp = g(edge + 2. * eps), xm = g(edge - eps),
                              xmm = g(edge - 2. * eps);
        // One-sided second-order difference quotients.
        const Eigen::Vector3d dp = (-3. * x0 + 4. * xp - xpp) / (2. * eps);
        const Eigen::Vector3d dm = (3. * x0 - 4. * xm + xmm) / (2. * eps);
        const double speed = std::max({dp.norm(), dm.norm(), 1e-3});
        // A jump J shows as |xp - xm| = J + O(eps speed).
        worst_c0 = std::max(worst_c0, (xp - xm).norm() / (4. * eps * speed));
        const double c1 = (dp - dm).norm() / speed;
        if(edge < 0. && B.is_gradual())
          worst_c1_disk = std::max(worst_c1_disk, c1);
        else
          worst_c1 = std::max(worst_c1, c1);
        ++lines;
      }
    }
  }
  std::cout << "  continuity " << name << ": " << lines << " boundary crossings, jump/(4 eps speed) " << worst_c0
            << ", C1 mismatch " << worst_c1 << " (disk boundaries of gradual blends: " << worst_c1_disk << ")"
            << std::endl;
  BS_CHECK(worst_c0 <= 1., name << ": surface not continuous across a strip boundary (" << worst_c0 << ")");
  BS_CHECK(worst_c1 <= 1e-3, name << ": surface not C1 across a strip boundary (" << worst_c1 << ")");
  BS_CHECK(worst_c1_disk <= 1e-3, name << ": surface not C1 across the disk boundary of a gradual blend ("
                                       << worst_c1_disk << ")");
}

// Chart points outside their chart's domain are refused with
// std::invalid_argument; points on the rim (up to rounding) are accepted.
template <class K>
void test_points_outside_domains()
{
  const Shape<K> s = sphere<K>(); // chart margin 0.2: disks of radius 1.2
  const double rim = 1.2;
  for(int k = 0; k < 64; ++k)
  {
    const double a = 2. * M_PI * k / 64.;
    const BS::Shape_point on(0, BS::Chart_point(std::size_t(k % 2), rim * std::cos(a), rim * std::sin(a)));
    bool ok = true;
    try
    {
      (void)s.point(on);
    }
    catch(const std::exception&)
    {
      ok = false;
    }
    BS_CHECK(ok, "a rim point of the chart domain is refused");
  }
  for(const BS::Chart_point& u : {BS::Chart_point(0, 1.21, 0.), BS::Chart_point(1, 0.9, 0.9),
                                  BS::Chart_point(2, 0., 0.), BS::Chart_point(0, std::nan(""), 0.)})
  {
    bool refused = false;
    try
    {
      (void)s.point(BS::Shape_point(0, u));
    }
    catch(const std::invalid_argument& e)
    {
      refused = std::string(e.what()).find("chart point") != std::string::npos;
    }
    BS_CHECK(refused, "chart point (" << u.chart << ", " << u.x << ", " << u.y << ") not refused with a message");
  }
}

// Placements are relative to the parent (sec. 3.5): moving or turning a
// part moves the part attached to it rigidly with it, and the root placement
// is the composition along the parents.
template <class K>
void test_placements_follow_parents()
{
  Shape<K> s = sphere<K>();
  // component 1: the root's northern cap, split off; component 2: a part on it
  s.split(0, 0, Region::make_parameters(0.05, -0.02, 0.55, 0.5, 0.2, 1., 0.), 0.06);
  s.add_part(1, 0, Region::make_parameters(0.1, 0.05, 0.2, 0.18, 0.3, 0.85, 1.), 0.05,
             BS::Superquadric_ellipsoid<K>(0.3, 0.25, 0.5, 0.7, 1.1), "superquadric_ellipsoid",
             Eigen::Vector3d(0.1, 0.05, 1.2), Eigen::Vector4d(0.98, 0.1, -0.05, 0.1), 0,
             Region::make_parameters(0., 0., 0.6, 0.6, 0., 1., 0.), 0.1);
  BS_CHECK(s.parent(1) == 0 && s.parent(2) == 1 && s.parent(0) == Shape<K>::no_parent, "parents");
  std::vector<BS::Shape_point> pts; // chart points of component 2 (a grid over both charts)
  for(std::size_t chart = 0; chart < 2; ++chart)
    for(int i = 0; i < 10; ++i)
      for(int j = 0; j < 10; ++j)
        pts.push_back(BS::Shape_point(2, BS::Chart_point(chart, 0.11 * i * std::cos(0.628 * j), 0.11 * i * std::sin(0.628 * j))));
  const Shape<K> before = s;
  // a rigid motion of component 1 relative to the root: a turn about its origin, then a shift
  Eigen::VectorXd q = s.parameters();
  const std::size_t o = s.component_offset(1);
  const Eigen::Vector4d turn = Eigen::Vector4d(0.9, -0.2, 0.3, 0.1).normalized();
  const Eigen::Vector3d shift(0.1, -0.3, 0.05);
  q.segment<3>(Eigen::Index(o)) = shift;
  q.segment<4>(Eigen::Index(o + 3)) = turn;
  s.set_parameters(q);
  const Eigen::Matrix3d R = BS::internal::rotation_matrix(turn);
  double worst = 0.;
  for(const BS::Shape_point& p : pts)
  {
    const Eigen::Vector3d expected = shift + R * eig<K>(before.component_point(p));
    worst = (std::max)(worst, (eig<K>(s.component_point(p)) - expected).norm());
  }
  BS_CHECK(worst < 1e-12, "a part does not follow its parent's motion: off by " << worst);
  BS_CHECK((s.root_translation(2) - (shift + R * before.root_translation(2))).norm() < 1e-12 &&
             (s.root_rotation(2) - R * before.root_rotation(2)).norm() < 1e-12,
           "root placement is not the composition along the parents");
  // A blend may not add a component that precedes its base (parents first).
  Shape<K> t = sphere<K>();
  t.split(0, 0, Region::make_parameters(0.05, -0.02, 0.55, 0.5, 0.2, 1., 0.), 0.06);
  bool refused = false;
  try
  {
    t.append_blend(BS::Blend(t.blend(0).kind(), 1, t.blend(0).base_region(), 0, t.blend(0).added_side()), false);
  }
  catch(const std::invalid_argument&) { refused = true; }
  BS_CHECK(refused, "a blend whose base follows its added component was accepted");
}

// ---------------------------------------------------------------------------
// Evolution: invariance, removal, refusals (sec. 4).

// The structure of a shape as text: components (type, charts, hole domain),
// blends (kind, components, chart, gradual, hole, strip half-width, core
// stretch), holes. With parameters(), it determines the shape.
template <class K>
std::string structure(const Shape<K>& s)
{
  std::ostringstream o;
  o.precision(17);
  for(std::size_t c = 0; c < s.number_of_components(); ++c)
    o << "c" << c << ":" << s.component(c).shape().type_name() << "/" << s.component(c).shape().number_of_charts()
      << ";";
  for(std::size_t b = 0; b < s.number_of_blends(); ++b)
  {
    const BS::Blend& B = s.blend(b);
    o << "b" << b << ":" << BS::blend_kind_name(B.kind()) << " " << B.base_component() << "/"
      << B.base_region().chart() << "->" << B.added_component() << (B.is_gradual() ? " gradual" : " final")
      << " hole " << (B.hole() == BS::Blend::no_hole ? -1 : long(B.hole())) << " r " << B.base_region().half_width()
      << " k " << B.core_stretch() << ";";
  }
  for(std::size_t h = 0; h < s.holes().size(); ++h)
    o << "h" << h << ":" << s.holes()[h].component << "(" << s.holes()[h].blends[0] << "," << s.holes()[h].blends[1]
      << ")" << (s.hole_is_tube(h) ? " tube" : " two disks") << ";";
  return o.str();
}

bool same_vector(const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
  return a.size() == b.size() && (a.array() == b.array()).all();
}

// `change` must throw E (or a type derived from it) and leave the shape as it
// was: the same parameters (exactly), components, blends and holes.
template <class E, class K, class F>
void expect_refused(const std::string& what, Shape<K>& s, const F& change)
{
  const Eigen::VectorXd q = s.parameters();
  const std::string st = structure(s);
  const std::size_t nc = s.number_of_components(), nb = s.number_of_blends();
  bool refused = false;
  try
  {
    change(s);
  }
  catch(const E& e)
  {
    refused = true;
    std::cout << "  refused: " << what << ": " << e.what() << std::endl;
  }
  catch(const std::exception& e)
  {
    BS_CHECK(false, what << ": wrong exception type: " << e.what());
  }
  BS_CHECK(refused, what << ": not refused");
  BS_CHECK(s.number_of_components() == nc && s.number_of_blends() == nb,
           what << ": the shape now has " << s.number_of_components() << " components and " << s.number_of_blends()
                << " blends, was " << nc << " and " << nb);
  BS_CHECK(same_vector(s.parameters(), q), what << ": the parameters changed");
  BS_CHECK(structure(s) == st, what << ": the structure changed: " << structure(s) << " was " << st);
}

// A part on the north pole of `base` (chart 0): a small ellipsoid whose
// upper cap (its chart 0) replaces the base's, like the nose of
// test_unified_meshes on the other pole. h = 1 (unexpressed).
template <class K>
std::size_t add_north_part(Shape<K>& s, std::size_t base, double radius = 0.22, double z = 0.9)
{
  return s.add_part(base, 0, Region::make_parameters(0., 0., radius, radius, 0., 0.9, 1.), 0.06,
                    BS::Superquadric_ellipsoid<K>(0.3, 0.3, 0.45, 1., 1.), "superquadric_ellipsoid",
                    Eigen::Vector3d(0., 0., z), Eigen::Vector4d(1., 0., 0., 0.), 0,
                    Region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1);
}

// A small part off the pole of chart 0 (rho 0.72, the equator is at 1),
// clear of the pole-to-pole hole of sphere_with_pole_hole().
template <class K>
std::size_t add_side_part(Shape<K>& s)
{
  return s.add_part(0, 0, Region::make_parameters(0.72, 0., 0.14, 0.14, 0., 0.9, 1.), 0.05,
                    BS::Superquadric_ellipsoid<K>(0.15, 0.15, 0.25, 1., 1.), "superquadric_ellipsoid",
                    Eigen::Vector3d(0.85, 0., 0.4), Eigen::Vector4d(0.95, 0., 0.3, 0.), 0,
                    Region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1);
}

// The points of component `c` of `after` that are on its surface are
// expressed elsewhere (canonical_point() leaves c) and are where `before`
// has that canonical point (relative 1e-12): c added at h = 1 is invisible.
template <class K>
void check_added_component_invisible(const std::string& name, const Shape<K>& before, const Shape<K>& after,
                                     std::size_t c)
{
  std::size_t compared = 0, own = 0;
  double worst = 0.;
  const BS::Blended_shape_pieces<K> pieces(after, 16);
  for(const auto& piece : pieces.pieces())
  {
    if(piece.component != c)
      continue;
    for(auto v : piece.mesh.mesh().vertices())
    {
      const std::optional<BS::Shape_point> q = after.canonical_point(BS::Shape_point(c, piece.mesh.chart_point(v)));
      if(!q)
        continue;
      if(q->component == c)
      {
        ++own;
        continue;
      }
      const Eigen::Vector3d x = eig<K>(before.point(*q));
      worst = std::max(worst, (eig<K>(after.point(BS::Shape_point(c, piece.mesh.chart_point(v)))) - x).norm() /
                                std::max(1., x.norm()));
      ++compared;
    }
  }
  std::cout << "  " << name << ": " << compared << " points of the new component compared, largest relative motion "
            << worst << std::endl;
  BS_CHECK(own == 0, name << ": " << own << " points of the new component are their own canonical points");
  BS_CHECK(compared >= 100, name << ": only " << compared << " points of the new component compared");
  BS_CHECK(worst <= 1e-12, name << ": a point of the new component is off the old surface by " << worst);
}

// add_part and add_hole at h = 1 move no point of the surface; nor does
// removing what they added (remove_component), which restores the shape.
template <class K>
void test_add_and_remove_invisible()
{
  auto same = [](const BS::Shape_point& p) { return std::vector<BS::Shape_point>{p}; };
  auto without = [](std::size_t gone) {
    return [gone](const BS::Shape_point& p) {
      if(p.component == gone)
        return std::vector<BS::Shape_point>{};
      return std::vector<BS::Shape_point>{BS::Shape_point(p.component > gone ? p.component - 1 : p.component, p.u)};
    };
  };
  {
    const Shape<K> before = sphere<K>();
    Shape<K> with = before;
    add_tilted_part(with);
    check_no_vertex_moves<K>("add_part at h = 1", before, with, same);
    check_added_component_invisible<K>("add_part at h = 1", before, with, 1);
    Shape<K> removed = with;
    removed.remove_component(1);
    check_no_vertex_moves<K>("remove_component of a part at h = 1", with, removed, without(1));
    BS_CHECK(same_vector(removed.parameters(), before.parameters()) && structure(removed) == structure(before),
             "remove_component of a part: not the shape before add_part: " << structure(removed));
  }
  {
    const Shape<K> before = sphere<K>(1., 1.);
    const Shape<K> with = sphere_with_pole_hole<K>();
    check_no_vertex_moves<K>("add_hole at h = 1", before, with, same);
    check_added_component_invisible<K>("add_hole at h = 1", before, with, 1);
    Shape<K> removed = with;
    removed.remove_component(1);
    check_no_vertex_moves<K>("remove_component of a hole at h = 1", with, removed, without(1));
    BS_CHECK(removed.holes().empty() && same_vector(removed.parameters(), before.parameters()) &&
               structure(removed) == structure(before),
             "remove_component of a hole: not the shape before add_hole: " << structure(removed));
  }
  {
    // A part on a shape that already has a gradual part (not on its base
    // component: the later part's region is on component 0 too).
    Shape<K> before = sphere<K>();
    add_tilted_part(before);
    set_parameter(before, "b0.h", 0.4);
    Shape<K> with = before;
    add_north_part(with, 0);
    check_no_vertex_moves<K>("add_part at h = 1 next to a gradual part", before, with, same);
  }
}

// Removing the first of two parts renumbers the second one's component and
// blend: the parameters lose exactly the removed ones, and the surface is
// the same point for point. Likewise a hole after a removed part.
template <class K>
void test_remove_renumbering()
{
  auto renumbered = [](const BS::Shape_point& p) {
    if(p.component == 1)
      return std::vector<BS::Shape_point>{};
    return std::vector<BS::Shape_point>{BS::Shape_point(p.component == 0 ? 0 : p.component - 1, p.u)};
  };
  // The parameters of `s` without component 1 and blend 0.
  auto expected = [](const Shape<K>& s) {
    const Eigen::VectorXd q = s.parameters();
    std::vector<double> r;
    for(std::size_t i = 0; i < s.number_of_parameters(); ++i)
    {
      const std::string n = s.parameter_name(i);
      if(n.rfind("c1.", 0) != 0 && n.rfind("b0.", 0) != 0)
        r.push_back(q[Eigen::Index(i)]);
    }
    return Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(r.data(), Eigen::Index(r.size())));
  };
  {
    Shape<K> before = sphere<K>();
    add_north_part(before, 0);                     // component 1, blend 0, h = 1
    add_tilted_part(before);                       // component 2, blend 1
    set_parameter(before, "b1.h", 0.5);
    perturb_component(before, 2, 0.3);
    Shape<K> after = before;
    after.remove_component(1);
    BS_CHECK(after.number_of_components() == 2 && after.number_of_blends() == 1,
             "remove the first of two parts: " << structure(after));
    if(after.number_of_blends() == 1)
      BS_CHECK(after.blend(0).base_component() == 0 && after.blend(0).added_component() == 1 &&
                 after.blend(0).is_gradual() && after.blend(0).base_region().chart() == 1,
               "remove the first of two parts: the second blend is " << structure(after));
    BS_CHECK(same_vector(after.parameters(), expected(before)),
             "remove the first of two parts: the parameters are not those of the second part");
    check_no_vertex_moves<K>("remove the first of two parts", before, after, renumbered);
  }
  {
    Shape<K> before = sphere<K>(1., 1.);
    add_side_part(before); // component 1, blend 0, h = 1
    before.add_hole(BS::Shape_point(0, BS::Chart_point(0, 0.05, 0.)), BS::Shape_point(0, BS::Chart_point(1, 0., 0.05)),
                    0.3, 0.08, 0.1); // component 2, blends 1, 2, hole 0
    set_parameter(before, "b1.h", 0.5);
    set_parameter(before, "b2.h", 0.3);
    Shape<K> after = before;
    after.remove_component(1);
    BS_CHECK(after.number_of_components() == 2 && after.number_of_blends() == 2 && after.holes().size() == 1,
             "remove a part before a hole: " << structure(after));
    if(after.holes().size() == 1 && after.number_of_blends() == 2)
    {
      const auto& h = after.holes()[0];
      BS_CHECK(h.component == 1 && h.blends[0] == 0 && h.blends[1] == 1 && after.blend(0).hole() == 0 &&
                 after.blend(1).hole() == 0 && after.blend(0).added_component() == 1 &&
                 after.blend(1).added_component() == 1,
               "remove a part before a hole: the hole is now " << structure(after));
    }
    BS_CHECK(same_vector(after.parameters(), expected(before)),
             "remove a part before a hole: the parameters are not those of the hole");
    check_no_vertex_moves<K>("remove a part before a hole", before, after, renumbered);
    // The renumbered hole still evolves: expressed, it switches to a tube.
    try
    {
      set_parameter(after, "b0.h", 0.);
      set_parameter(after, "b1.h", 0.);
      after.switch_hole_to_tube(0);
      BS_CHECK(after.genus() == 1, "remove a part before a hole: genus " << after.genus() << " after the switch");
    }
    catch(const std::exception& e)
    {
      BS_CHECK(false, "remove a part before a hole: the hole no longer switches: " << e.what());
    }
  }
}

// remove_component() refuses (std::logic_error, shape unchanged) what still
// contributes or holds something up.
template <class K>
void test_remove_refusals()
{
  {
    Shape<K> s = sphere<K>();
    expect_refused<std::logic_error>("remove the root", s, [](Shape<K>& x) { x.remove_component(0); });
    expect_refused<std::logic_error>("remove a missing component", s, [](Shape<K>& x) { x.remove_component(1); });
  }
  {
    Shape<K> s = sphere<K>();
    add_tilted_part(s);
    set_parameter(s, "b0.h", 0.4);
    expect_refused<std::logic_error>("remove a part at h = 0.4", s, [](Shape<K>& x) { x.remove_component(1); });
    set_parameter(s, "b0.h", 1. - 1e-9);
    expect_refused<std::logic_error>("remove a part at h = 1 - 1e-9", s, [](Shape<K>& x) { x.remove_component(1); });
    set_parameter(s, "b0.h", 0.);
    s.finish_gradual_blend(0);
    expect_refused<std::logic_error>("remove a finished part", s, [](Shape<K>& x) { x.remove_component(1); });
  }
  {
    Shape<K> s = configurations<K>()["split"]();
    expect_refused<std::logic_error>("remove a split-off component", s, [](Shape<K>& x) { x.remove_component(1); });
  }
  {
    // One end of a hole at h = 1, the other expressed.
    Shape<K> s = sphere_with_pole_hole<K>();
    set_parameter(s, "b1.h", 0.5);
    expect_refused<std::logic_error>("remove a hole with one end expressed", s,
                                     [](Shape<K>& x) { x.remove_component(1); });
  }
  {
    // A component at h = 1 that is the base of another blend. The evolution
    // operations refuse regions on gradually blended components, so the
    // second blend comes in as a model file would bring it (append_blend).
    Shape<K> s = sphere<K>();
    add_north_part(s, 0); // component 1, h = 1
    const std::size_t c2 = s.append_component(
      BS::make_component_shape(BS::Superquadric_ellipsoid<K>(0.1, 0.1, 0.15, 1., 1.), "superquadric_ellipsoid"),
      Eigen::Vector3d(0., 0.3, 1.2), Eigen::Vector4d(1., 0., 0., 0.));
    BS::Ellipse_blending_region base(Region::make_parameters(0., 0.4, 0.1, 0.1, 0., 0.9, 1.), 0.04, 8,
                                     BS::Blending_region_kind::Disk, BS::Retained_side::Outside);
    base.set_chart(0);
    BS::Ellipse_blending_region added(Region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1, 8,
                                      BS::Blending_region_kind::Annulus, BS::Retained_side::Inside);
    added.set_chart(0);
    s.append_blend(BS::Blend(BS::Blend_kind::Part, 1, base, c2, BS::Added_side::ellipse(added)));
    expect_refused<std::logic_error>("remove the base of another blend", s, [](Shape<K>& x) { x.remove_component(1); });
  }
}

// A fit may drive a blend's steepness w to its lower bound (a transition as
// sharp as a cut): the surface must still evaluate there, on the region
// curves too (d = 0), where alpha0 was 0 / 0 with the bound before (the
// smallest positive double) and a fit's mesh vertices became NaN. For a
// split (annulus) and for a gradual part (disk, h = 0.3).
template <class K>
void test_sharpest_blend()
{
  for(const bool gradual : {false, true})
  {
    Shape<K> s = sphere<K>();
    if(gradual)
    {
      add_north_part(s, 0);
      set_parameter(s, "b0.h", 0.3);
    }
    else
      s.split(0, 0, Region::make_parameters(0.15, -0.1, 0.5, 0.42, 0.3, 0.9, 0.), 0.08);
    const char* what = gradual ? "gradual part" : "split";
    const std::size_t w_index = parameter_index(s, "b0.w");
    BS_CHECK(s.parameter_lower_bound(w_index) == BS::Blending_function::minimum_w,
             what << ": the lower bound of w is " << s.parameter_lower_bound(w_index));
    bool refused = false;
    try
    {
      set_parameter(s, "b0.w", std::numeric_limits<double>::min());
    }
    catch(const std::invalid_argument&)
    {
      refused = true;
    }
    BS_CHECK(refused, what << ": w below its lower bound accepted");
    set_parameter(s, "b0.w", BS::Blending_function::minimum_w);
    // the two curves: the base region's, on the base, and the added side's, on the part
    const auto& blend = s.blend(0);
    const Region* added = &blend.added_side().ellipse_region();
    const std::pair<std::size_t, const Region*> curves[2] = {{0, &blend.base_region()}, {1, added}};
    std::size_t bad = 0, evaluated = 0;
    for(const auto& [component, region] : curves)
    {
      for(int k = 0; k < 32; ++k)
      {
        const auto u = region->region().strip_point_at_theta(0., 2. * M_PI * k / 32.); // d = 0: on the curve
        const BS::Shape_point p(component, BS::Chart_point(region->chart(), u.x(), u.y()));
        if(!s.is_on_surface(p))
          continue;
        ++evaluated;
        const auto X = s.point(p);
        const auto n = s.normal(p);
        const Eigen::MatrixXd J = s.dense_jacobian(p);
        if(!(std::isfinite(X.x()) && std::isfinite(X.y()) && std::isfinite(X.z()) && std::isfinite(n.x()) &&
             std::isfinite(n.y()) && std::isfinite(n.z()) && J.allFinite()))
          ++bad;
      }
    }
    BS_CHECK(evaluated >= 32 && bad == 0, what << ": " << bad << " of " << evaluated
                                              << " points on the region curves do not evaluate at w = minimum_w");
  }
}

// Every documented evolution error throws the documented type and leaves
// the shape unchanged.
template <class K>
void test_evolution_errors()
{
  typedef std::invalid_argument Invalid;
  auto configs = configurations<K>();
  {
    Shape<K> s = configs["split"]();
    expect_refused<Invalid>("split: region leaving its chart", s, [](Shape<K>& x) {
      x.split(0, 1, Region::make_parameters(0.95, 0., 0.3, 0.25, 0., 0.9, 0.), 0.05);
    });
    expect_refused<Invalid>("split: region and strip reaching past the chart margin", s, [](Shape<K>& x) {
      x.split(0, 1, Region::make_parameters(0., 1., 0.25, 0.25, 0., 0.9, 0.), 0.08);
    });
    expect_refused<Invalid>("split: region meeting another blend's region", s, [](Shape<K>& x) {
      x.split(0, 0, Region::make_parameters(0.6, -0.3, 0.2, 0.2, 0., 0.9, 0.), 0.05);
    });
    expect_refused<Invalid>("add_part: region meeting another blend's region", s, [](Shape<K>& x) {
      x.add_part(0, 0, Region::make_parameters(0.55, 0.2, 0.2, 0.2, 0., 0.9, 1.), 0.05,
                 BS::Superquadric_ellipsoid<K>(0.3, 0.3, 0.4, 1., 1.), "superquadric_ellipsoid",
                 Eigen::Vector3d(0.5, 0., 0.8), Eigen::Vector4d(1., 0., 0., 0.), 0,
                 Region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1);
    });
    expect_refused<Invalid>("split: no such component", s, [](Shape<K>& x) {
      x.split(5, 0, Region::make_parameters(0., 0., 0.2, 0.2, 0., 0.9, 0.), 0.05);
    });
    expect_refused<Invalid>("split: no such chart", s, [](Shape<K>& x) {
      x.split(0, 2, Region::make_parameters(0., 0., 0.2, 0.2, 0., 0.9, 0.), 0.05);
    });
    expect_refused<Invalid>("split: h != 0", s, [](Shape<K>& x) {
      x.split(0, 1, Region::make_parameters(0., 0., 0.2, 0.2, 0., 0.9, 0.3), 0.05);
    });
    expect_refused<Invalid>("add_part: zero quaternion", s, [](Shape<K>& x) {
      x.add_part(0, 1, Region::make_parameters(0., 0., 0.3, 0.3, 0., 0.9, 1.), 0.05,
                 BS::Superquadric_ellipsoid<K>(0.3, 0.3, 0.4, 1., 1.), "superquadric_ellipsoid",
                 Eigen::Vector3d(0., 0., -0.9), Eigen::Vector4d(0., 0., 0., 0.), 1,
                 Region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1);
    });
    expect_refused<std::logic_error>("finish_gradual_blend: an already final blend", s,
                                     [](Shape<K>& x) { x.finish_gradual_blend(0); });
    expect_refused<Invalid>("add_hole: coinciding places", s, [](Shape<K>& x) {
      const BS::Shape_point p(0, BS::Chart_point(1, 0.1, 0.2));
      x.add_hole(p, p, 0.2, 0.05);
    });
    expect_refused<Invalid>("add_hole: a place in a discarded part", s, [](Shape<K>& x) {
      x.add_hole(BS::Shape_point(0, BS::Chart_point(0, 0.15, -0.1)), BS::Shape_point(0, BS::Chart_point(1, 0., 0.)), 0.1,
                 0.04);
    });
  }
  {
    // The seam split's region (chart 0, across the equator) seen from chart 1:
    // chart 0's (0.93, 0.1) is chart 1's (1.059, -0.114).
    Shape<K> s = configs["seam_split"]();
    expect_refused<Invalid>("split: region in the other chart meeting another blend's region", s, [](Shape<K>& x) {
      x.split(0, 1, Region::make_parameters(1.05, -0.1, 0.08, 0.08, 0., 0.9, 0.), 0.03);
    });
  }
  {
    Shape<K> s = configs["part"](); // h = 0.4
    expect_refused<Invalid>("split of a component still blended in gradually", s, [](Shape<K>& x) {
      x.split(1, 1, Region::make_parameters(0., 0., 0.2, 0.2, 0., 0.9, 0.), 0.05);
    });
    expect_refused<Invalid>("add_part on a component still blended in gradually", s,
                            [](Shape<K>& x) { add_north_part(x, 1); });
    expect_refused<std::logic_error>("finish_gradual_blend at h = 0.4", s, [](Shape<K>& x) { x.finish_gradual_blend(0); });
    expect_refused<std::logic_error>("finish_gradual_blend: no such blend", s,
                                     [](Shape<K>& x) { x.finish_gradual_blend(3); });
    // set_parameters: wrong size, NaN (shape, placement, blend), out of
    // bounds, a changed fixed parameter.
    const Eigen::VectorXd q = s.parameters();
    expect_refused<Invalid>("set_parameters: one parameter too many", s, [&](Shape<K>& x) {
      Eigen::VectorXd r(q.size() + 1);
      r << q, 0.;
      x.set_parameters(r);
    });
    expect_refused<Invalid>("set_parameters: one parameter too few", s,
                            [&](Shape<K>& x) { x.set_parameters(q.head(q.size() - 1)); });
    for(const std::string name : {"c0.a1", "c1.tx", "c1.qw", "c1.e2", "b0.e_u", "b0.w", "b0.h"})
      expect_refused<Invalid>("set_parameters: NaN " + name, s,
                              [&](Shape<K>& x) { set_parameter(x, name, std::nan("")); });
    expect_refused<Invalid>("set_parameters: infinite c1.ty", s, [&](Shape<K>& x) { set_parameter(x, "c1.ty", HUGE_VAL); });
    expect_refused<Invalid>("set_parameters: negative c0.a2", s, [&](Shape<K>& x) { set_parameter(x, "c0.a2", -0.5); });
    expect_refused<Invalid>("set_parameters: h = 1.5", s, [&](Shape<K>& x) { set_parameter(x, "b0.h", 1.5); });
  }
  {
    Shape<K> s = configs["split"]();
    expect_refused<Invalid>("set_parameters: a changed fixed parameter (h of a split)", s,
                            [&](Shape<K>& x) { set_parameter(x, "b0.h", 0.2); });
  }
  {
    Shape<K> s = sphere_with_pole_hole<K>();
    expect_refused<Invalid>("set_parameters: a changed fixed parameter (a4 of a closed hole)", s,
                            [&](Shape<K>& x) { set_parameter(x, "c1.a4", 1.2); });
    expect_refused<std::logic_error>("finish_gradual_blend on a hole end", s,
                                     [](Shape<K>& x) { x.finish_gradual_blend(0); });
    expect_refused<std::logic_error>("switch_hole_to_tube at h = 1", s, [](Shape<K>& x) { x.switch_hole_to_tube(0); });
    set_parameter(s, "b0.h", 0.);
    expect_refused<std::logic_error>("finish_gradual_blend on a hole end at h = 0", s,
                                     [](Shape<K>& x) { x.finish_gradual_blend(0); });
    set_parameter(s, "b1.h", 1e-9);
    expect_refused<std::logic_error>("switch_hole_to_tube with one end at h = 1e-9", s,
                                     [](Shape<K>& x) { x.switch_hole_to_tube(0); });
    set_parameter(s, "b1.h", 0.);
    s.switch_hole_to_tube(0);
    expect_refused<std::logic_error>("switch_hole_to_tube: already a tube", s,
                                     [](Shape<K>& x) { x.switch_hole_to_tube(0); });
    expect_refused<std::logic_error>("finish_gradual_blend on a tube's end", s,
                                     [](Shape<K>& x) { x.finish_gradual_blend(1); });
  }
}

// A region wholly inside a part of the base that another blend already
// discards would blend in a piece that is not on the surface: refused with
// std::invalid_argument, the shape unchanged.
template <class K>
void test_region_in_discarded_part()
{
  Shape<K> base = sphere<K>();
  // Component 0 keeps the outside of this ellipse of chart 0, component 1 the inside.
  base.split(0, 0, Region::make_parameters(0.15, -0.1, 0.5, 0.42, 0.3, 0.9, 0.), 0.08);
  // Each case on a fresh copy (a wrongly accepted region must not change the next case).
  auto expect = [&](const std::string& what, const std::function<void(Shape<K>&)>& change) {
    Shape<K> s = base;
    expect_refused<std::invalid_argument>(what, s, change);
  };
  expect("split inside the discarded disk of an earlier split", [](Shape<K>& x) {
    x.split(0, 0, Region::make_parameters(0.15, -0.1, 0.12, 0.1, 0., 0.9, 0.), 0.04);
  });
  expect("add_part inside the discarded disk of an earlier split", [](Shape<K>& x) {
    x.add_part(0, 0, Region::make_parameters(0.15, -0.1, 0.12, 0.1, 0., 0.9, 1.), 0.04,
               BS::Superquadric_ellipsoid<K>(0.2, 0.2, 0.3, 1., 1.), "superquadric_ellipsoid",
               Eigen::Vector3d(0.1, -0.1, 1.), Eigen::Vector4d(1., 0., 0., 0.), 0,
               Region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1);
  });
  // The split-off cap (component 1) discards all of its chart 1 and the
  // outside of the ellipse in its chart 0.
  expect("split of the cap in its discarded chart 1", [](Shape<K>& x) {
    x.split(1, 1, Region::make_parameters(0., 0., 0.2, 0.2, 0., 0.9, 0.), 0.05);
  });
  expect("split of the cap outside its ellipse in chart 0", [](Shape<K>& x) {
    x.split(1, 0, Region::make_parameters(-0.75, 0.45, 0.15, 0.15, 0., 0.9, 0.), 0.04);
  });
  expect("add_part on the cap in its discarded chart 1", [](Shape<K>& x) {
    x.add_part(1, 1, Region::make_parameters(0., 0., 0.2, 0.2, 0., 0.9, 1.), 0.05,
               BS::Superquadric_ellipsoid<K>(0.2, 0.2, 0.3, 1., 1.), "superquadric_ellipsoid",
               Eigen::Vector3d(0., 0., -1.), Eigen::Vector4d(1., 0., 0., 0.), 1,
               Region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1);
  });
  expect("add_hole from the cap's discarded chart 1", [](Shape<K>& x) {
    x.add_hole(BS::Shape_point(1, BS::Chart_point(1, 0., 0.)), BS::Shape_point(0, BS::Chart_point(1, 0.6, 0.)), 0.15,
               0.04);
  });
}

// A real part on a part (sec. 3.6): split the root (the copy's placement is
// the identity, so placements relative to the root and relative to the base
// agree), add a part on the split-off cap, express it and finish it: the
// unified mesh stays closed, manifold, outward and free of self-intersections.
template <class K>
void test_part_on_a_part()
{
  Shape<K> s = sphere<K>();
  s.split(0, 0, Region::make_parameters(0., 0., 0.5, 0.45, 0.2, 0.9, 0.), 0.08);
  BS_CHECK(s.component(1).translation() == Eigen::Vector3d::Zero() &&
             s.component(1).quaternion() == Eigen::Vector4d(1., 0., 0., 0.),
           "part on a part: the split-off component is not at the identity placement");
  // The cap keeps the inside of its ellipse: a smaller region at its centre.
  try
  {
    add_north_part(s, 1);
  }
  catch(const std::exception& e)
  {
    BS_CHECK(false, "part on a part: add_part on the split-off cap threw: " << e.what());
    return;
  }
  BS_CHECK(s.blend(1).base_component() == 1 && s.blend(1).added_component() == 2, "part on a part: " << structure(s));
  check_unified_mesh<K>("part on a part, h = 1", s, 0);
  set_parameter(s, "b1.h", 0.5);
  check_unified_mesh<K>("part on a part, h = 0.5", s, 0);
  set_parameter(s, "b1.h", 0.);
  s.finish_gradual_blend(1);
  check_unified_mesh<K>("part on a part, finished", s, 0);
  // The part stands out of the cap: its top is above the old surface.
  const Eigen::Vector3d top = eig<K>(s.point(BS::Shape_point(2, BS::Chart_point(0, 0., 0.))));
  BS_CHECK(s.is_on_surface(BS::Shape_point(2, BS::Chart_point(0, 0., 0.))) && top.z() > 1.2,
           "part on a part: the part's top is at " << top.transpose());
}

// ---------------------------------------------------------------------------
// Per-component pieces (sec. 3.3, Blended_shape_pieces).

struct Pieces_check
{
  std::size_t faces = 0, kept = 0, mismatches = 0, bad_positions = 0, omitted_touching = 0;
  std::size_t chord_faces = 0;
  double worst_chord_ratio = 0., worst_chart_point = 0.;
  std::vector<std::vector<bool>> retained;
};

// Checks `pieces` against `s` by brute force:
// - one piece per chart of every component, in order;
// - every vertex at s.point() of its chart point (bit for bit);
// - a face is kept iff one of its corners is on the surface (the documented
//   rule: faces wholly in a discarded part are omitted);
// - kept faces map barycentric points back to the domain: chart_point(f, b)
//   is the interpolation of the corners' chart coordinates (unwrapped here
//   independently), and where the face lies on the surface (corners, edge
//   midpoints and the sample on it), s there is within the chord error of
//   the flat face: |s(u(b)) - sum b_i x_i| <= 2 * 4 (b0 b1 + b1 b2 + b2 b0)
//   * (the largest edge sagitta |s(mid) - (x_i + x_j) / 2|), twice what a
//   quadratic map gives.
template <class K>
Pieces_check check_pieces(const std::string& name, const Shape<K>& s, const BS::Blended_shape_pieces<K>& pieces)
{
  Pieces_check r;
  std::size_t expected = 0;
  for(std::size_t c = 0; c < s.number_of_components(); ++c)
    for(std::size_t ch = 0; ch < s.component(c).shape().number_of_charts(); ++ch, ++expected)
      BS_CHECK(expected < pieces.pieces().size() && pieces.pieces()[expected].component == c &&
                 pieces.pieces()[expected].mesh.chart_index() == ch,
               name << ": piece " << expected << " is not chart " << ch << " of component " << c);
  BS_CHECK(pieces.pieces().size() == expected, name << ": " << pieces.pieces().size() << " pieces, expected " << expected);
  const std::array<std::array<double, 3>, 4> samples = {
    {{{1. / 3., 1. / 3., 1. / 3.}}, {{2. / 3., 1. / 6., 1. / 6.}}, {{1. / 6., 2. / 3., 1. / 6.}}, {{1. / 6., 1. / 6., 2. / 3.}}}};
  for(const auto& piece : pieces.pieces())
  {
    const auto& m = piece.mesh.mesh();
    const BS::Chart_domain dom = piece.mesh.domain();
    std::vector<bool> on(m.number_of_vertices());
    for(auto v : m.vertices())
    {
      const BS::Shape_point p(piece.component, piece.mesh.chart_point(v));
      on[std::size_t(v)] = s.is_on_surface(p);
      const Eigen::Vector3d x = eig<K>(s.point(p)), y = eig<K>(m.point(v));
      r.bad_positions += (x == y) ? 0 : 1;
    }
    r.retained.push_back(piece.retained);
    BS_CHECK(piece.retained.size() == m.number_of_faces(), name << ": a classification per face expected");
    auto eval = [&](double x, double y) {
      return eig<K>(s.point(BS::Shape_point(piece.component, BS::Chart_point(piece.mesh.chart_index(), x, y))));
    };
    auto surface = [&](double x, double y) {
      return s.is_on_surface(BS::Shape_point(piece.component, BS::Chart_point(piece.mesh.chart_index(), x, y)));
    };
    for(auto f : m.faces())
    {
      ++r.faces;
      const auto vs = piece.mesh.face_vertices(f);
      bool any = false;
      std::array<Eigen::Vector2d, 3> u;
      std::array<Eigen::Vector3d, 3> x;
      for(int i = 0; i < 3; ++i)
      {
        any = any || on[std::size_t(vs[std::size_t(i)])];
        const BS::Chart_point c = piece.mesh.chart_point(vs[std::size_t(i)]);
        u[std::size_t(i)] = Eigen::Vector2d(c.x, c.y);
        x[std::size_t(i)] = eig<K>(m.point(vs[std::size_t(i)]));
      }
      const bool kept = std::size_t(f) < piece.retained.size() && piece.retained[std::size_t(f)];
      r.mismatches += (kept == any) ? 0 : 1;
      // Unwrap the periodic coordinates toward corner 0 (independently of Chart_mesh).
      const double period[2] = {dom.x_period(), dom.y_period()};
      for(int i = 1; i < 3; ++i)
        for(int k = 0; k < 2; ++k)
          if(period[k] > 0.)
            u[std::size_t(i)][k] -= period[k] * std::round((u[std::size_t(i)][k] - u[0][k]) / period[k]);
      if(!kept)
      {
        // Wholly discarded: the centroid and the edge midpoints too.
        const Eigen::Vector2d g = (u[0] + u[1] + u[2]) / 3.;
        bool touching = surface(g.x(), g.y());
        for(int i = 0; i < 3; ++i)
        {
          const Eigen::Vector2d mid = 0.5 * (u[std::size_t(i)] + u[std::size_t((i + 1) % 3)]);
          touching = touching || surface(mid.x(), mid.y());
        }
        r.omitted_touching += touching ? 1 : 0;
        continue;
      }
      ++r.kept;
      bool smooth = on[std::size_t(vs[0])] && on[std::size_t(vs[1])] && on[std::size_t(vs[2])];
      double sagitta = 0.;
      for(int i = 0; i < 3 && smooth; ++i)
      {
        const std::size_t a = std::size_t(i), b = std::size_t((i + 1) % 3);
        const Eigen::Vector2d mid = 0.5 * (u[a] + u[b]);
        smooth = smooth && surface(mid.x(), mid.y());
        sagitta = std::max(sagitta, (eval(mid.x(), mid.y()) - 0.5 * (x[a] + x[b])).norm());
      }
      for(const auto& b : samples)
      {
        const Eigen::Vector2d ub = b[0] * u[0] + b[1] * u[1] + b[2] * u[2];
        const BS::Chart_point cp = piece.mesh.chart_point(f, b);
        const Eigen::Vector3d xb = eval(ub.x(), ub.y());
        r.worst_chart_point = std::max(r.worst_chart_point, (eval(cp.x, cp.y) - xb).norm() / std::max(1., xb.norm()));
        if(!smooth || !surface(ub.x(), ub.y()))
          continue;
        const Eigen::Vector3d flat = b[0] * x[0] + b[1] * x[1] + b[2] * x[2];
        const double p2 = 4. * (b[0] * b[1] + b[1] * b[2] + b[2] * b[0]) * sagitta;
        r.worst_chord_ratio = std::max(r.worst_chord_ratio, ((xb - flat).norm() - 1e-12 * std::max(1., xb.norm())) /
                                                                std::max(p2, 1e-300));
      }
      r.chord_faces += smooth ? 1 : 0;
    }
  }
  std::cout << "  pieces " << name << ": " << r.faces << " faces, " << r.kept << " kept (" << r.chord_faces
            << " wholly on the surface); largest (deviation from the face) / (quadratic chord bound) "
            << r.worst_chord_ratio << ", chart_point(f, b) off by " << r.worst_chart_point << std::endl;
  BS_CHECK(r.bad_positions == 0, name << ": " << r.bad_positions << " vertices not at s(chart point)");
  BS_CHECK(r.mismatches == 0, name << ": " << r.mismatches << " faces classified against the rule");
  BS_CHECK(r.omitted_touching == 0, name << ": " << r.omitted_touching << " omitted faces reach the surface");
  BS_CHECK(r.worst_chart_point <= 1e-12, name << ": chart_point(f, b) is not the barycentric point of the face");
  BS_CHECK(r.worst_chord_ratio <= 2., name << ": a face is " << r.worst_chord_ratio
                                           << " times the quadratic chord bound away from the surface");
  BS_CHECK(r.chord_faces > r.kept / 2, name << ": only " << r.chord_faces << " faces checked against the surface");
  return r;
}

template <class K>
void test_pieces()
{
  const int resolution = 12;
  for(const auto& c : configurations<K>())
  {
    const Shape<K> s = c.second();
    const BS::Blended_shape_pieces<K> pieces(s, resolution);
    const Pieces_check r = check_pieces<K>(c.first, s, pieces);
    if(c.first == "split" || c.first == "hole_tube")
      BS_CHECK(r.kept < r.faces, c.first << ": no face omitted");
  }
  // Moving a region (e_u of the split's blend) and update(): the
  // classification follows the new region, as a fresh tessellation does.
  Shape<K> s = configurations<K>()["split"]();
  BS::Blended_shape_pieces<K> pieces(s, resolution);
  const Pieces_check before = check_pieces<K>("split", s, pieces);
  set_parameter(s, "b0.e_u", s.blend(0).base_region().parameters()[0] + 0.15);
  set_parameter(s, "b0.e_2", s.blend(0).base_region().parameters()[3] * 0.8);
  pieces.update(s);
  const Pieces_check after = check_pieces<K>("split, region moved, update()", s, pieces);
  std::size_t changed[2] = {0, 0};
  for(std::size_t p = 0; p < before.retained.size() && p < after.retained.size(); ++p)
    for(std::size_t f = 0; f < before.retained[p].size() && f < after.retained[p].size(); ++f)
      changed[pieces.pieces()[p].component == 0 ? 0 : 1] += (before.retained[p][f] != after.retained[p][f]) ? 1 : 0;
  std::cout << "  region moved: " << changed[0] << " faces of the base and " << changed[1]
            << " of the split-off cap changed class" << std::endl;
  BS_CHECK(changed[0] > 0, "moving the region changed no face of the base");
  const BS::Blended_shape_pieces<K> fresh(s, resolution);
  std::size_t differ = 0;
  for(std::size_t p = 0; p < fresh.pieces().size() && p < pieces.pieces().size(); ++p)
  {
    differ += fresh.pieces()[p].retained == pieces.pieces()[p].retained ? 0 : 1;
    for(auto v : fresh.pieces()[p].mesh.mesh().vertices())
      differ += fresh.pieces()[p].mesh.mesh().point(v) == pieces.pieces()[p].mesh.mesh().point(v) ? 0 : 1;
  }
  BS_CHECK(differ == 0 && fresh.pieces().size() == pieces.pieces().size(),
           "update() after moving a region differs from a fresh tessellation (" << differ << ")");
  // A structural change (a further split) re-tessellates on update().
  s.split(0, 1, Region::make_parameters(0., 0., 0.3, 0.25, 0., 0.9, 0.), 0.06);
  pieces.update(s);
  check_pieces<K>("split, then a second split, update()", s, pieces);
}

template <class K>
void run(const char* kernel)
{
  std::cout << "kernel " << kernel << std::endl;
  std::mt19937 rng(7);
  for(const auto& c : configurations<K>())
    test_jacobian<K>(c.first, c.second(), rng);
  test_no_vertex_moves<K>();
  test_points_outside_domains<K>();
  for(const auto& c : configurations<K>())
    test_continuity<K>(c.first, c.second());
  test_unified_meshes<K>();
  test_placements_follow_parents<K>();
  test_add_and_remove_invisible<K>();
  test_remove_renumbering<K>();
  test_remove_refusals<K>();
  test_evolution_errors<K>();
  test_sharpest_blend<K>();
  test_region_in_discarded_part<K>();
  test_part_on_a_part<K>();
  test_pieces<K>();
}

} // namespace

// The blended shape's representation as one program of seven parts: this
// file's checks (`core`) and those of the headers included above.
int main(int argc, char** argv)
{
  return blended_shape_test::run_parts(argc, argv, "test_blended_shape", {
    {"core", [] {
       blended_shape_test::for_each_kernel([](auto kernel, const char* name) { run<decltype(kernel)>(name); });
     }},
    {"quotient_domain", quotient_domain_checks::run_all},
    {"io", blended_shape_io_checks::run_all},
    {"mesh_io", blended_shape_mesh_io_checks::run_all},
    {"hierarchy", blending_hierarchy_checks::run_all},
    {"hole_component", hole_component_checks::run_all},
    {"blending_region", blending_region_checks::run_all}});
}
