// SPDX-License-Identifier: LGPL-3.0-or-later
// The force analysis of sec. 5.4 (eq. 12, 13, Fig. 16) and the split it
// proposes. On the unit sphere pulled by forces F = x (known flux: +-pi over
// the half spheres, whose boundary crosses the chart seam twice): the
// regions, their fluxes against a sum over the faces and against the
// integral, the areas, the measured noise, the interpolation weights. On a
// body with a part sticking out (inside one chart, and across the chart
// seam) fitted by one superquadric: the best boundary goes around the part's
// base, the split there has its region's centre on the part's axis and the
// part inside, moves no point, and fitting on explains the part. Bad input.
// Part evolution (Part_evolution): single superquadrics stay one part, an
// undone split restores the model bit for bit, the visitor hears of every
// event, the abort callback and the part limit leave a valid model, bad
// settings are refused. Both supported kernels. The crease segments of the
// data (a cylinder on a box: the box and the cylinder; a superellipsoid: one).
#ifndef BLENDED_SHAPE_EVOLUTION_CHECKS_H
#define BLENDED_SHAPE_EVOLUTION_CHECKS_H
// Part of test_fitting (one program, one compilation of the fitter and the
// evolution for each kernel; CTest runs the force analysis as
// `test_fitting_regions`, part evolution's steps and limits as
// `test_fitting_evolution`, the crease and branch segments as
// `test_fitting_segments`, the whole runs on scans as
// `test_fitting_evolution_epick` and `test_fitting_evolution_cartesian`).
#include "test_kernels.h"
#include "test_util.h"

#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Blending/Quotient_domain.h>
#include <CGAL/Blended_shape/Evolution/Branch_segments.h>
#include <CGAL/Blended_shape/Evolution/Crease_segments.h>
#include <CGAL/Blended_shape/Evolution/Force_regions.h>
#include <CGAL/Blended_shape/Evolution/Part_evolution.h>
#include <CGAL/Blended_shape/Evolution/Split_proposal.h>
#include <CGAL/Blended_shape/Evolution/fit_blended_shape.h>
#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>
#include <blended_shape_testing/equivariance.h>
#include <blended_shape_testing/same_bits.h>
#include <blended_shape_testing/synthetic_scans.h>
#include <CGAL/Blended_shape/Fitting/Deformable_blended_model.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model_fitter.h>
#include <CGAL/Blended_shape/Fitting/sample_model.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/generators.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace evolution_checks {

namespace BS = CGAL::Blended_shapes;

using blended_shape_test::reduced;

const int resolution = 16;

template <class K>
Eigen::Vector3d eig(const typename K::Point_3& p)
{
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

// Forces on the unit sphere at random chart points: normal distance x + noise.
template <class K>
std::vector<BS::Normal_force> sphere_forces(const BS::Blended_shape<K>& sphere, std::size_t n, double noise)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1., 1.);
  std::normal_distribution<double> g(0., noise);
  std::vector<BS::Normal_force> forces;
  while(forces.size() < n)
  {
    const double x = u(rng), y = u(rng);
    if(x * x + y * y > 1.)
      continue;
    const BS::Shape_point p(0, BS::Chart_point(forces.size() % 2, x, y));
    forces.push_back(BS::Normal_force{p, eig<K>(sphere.point(p)).x() + g(rng), 1.});
  }
  return forces;
}

template <class K>
void test_sphere()
{
  const BS::Blended_shape<K> sphere(BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1.));
  const BS::Blended_shape_pieces<K> pieces(sphere, resolution);
  const BS::Quotient_domain<K> domain(sphere, pieces, 1);
  const double noise = 0.01;
  // Forces are cheap (no fit): as many in sanitizer builds, where fewer
  // would make the leave-one-out noise estimate noisier.
  const BS::Force_regions<K> regions(domain, sphere_forces<K>(sphere, 30000, noise));

  // Interpolation weights: non-negative, summing to 1, reproducing the surface within an edge.
  for(const BS::Normal_force& f : sphere_forces<K>(sphere, 200, 0.01))
  {
    const auto w = domain.interpolation_weights(f.point);
    double sum = 0.;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for(std::size_t k = 0; k < w.count; ++k)
    {
      BS_CHECK(w.weights[k] >= 0., "negative interpolation weight");
      sum += w.weights[k];
      x += w.weights[k] * eig<K>(domain.node(w.nodes[k]).position);
    }
    BS_CHECK(w.count > 0 && std::abs(sum - 1.) < 1e-12, w.count << " weights adding up to " << sum);
    BS_CHECK((x - eig<K>(sphere.point(f.point))).norm() < domain.max_edge_length(),
             "the interpolated position is " << (x - eig<K>(sphere.point(f.point))).norm() << " from the point");
  }

  double area = 0.;
  for(std::size_t v = 0; v < domain.number_of_nodes(); ++v)
    area += regions.node_area(v);
  BS_CHECK(std::abs(area - 4. * M_PI) < 0.02 * 4. * M_PI, "the nodes' areas add up to " << area << ", not 4 pi");
  BS_CHECK(std::abs(regions.noise() - noise) < 0.15 * noise,
           "measured noise " << regions.noise() << " for " << noise);

  // One view (the forces of the points with z > 0 only): the regions grow
  // over the unseen half, which their covered area leaves out. It equals a
  // sum over the nodes that forces reach, and adds up to the seen half.
  {
    std::vector<BS::Normal_force> seen;
    for(const BS::Normal_force& f : sphere_forces<K>(sphere, 30000, noise))
      if(eig<K>(sphere.point(f.point)).z() > 0.)
        seen.push_back(f);
    const BS::Force_regions<K> one_view(domain, seen);
    double covered = 0., total = 0.;
    for(const auto& r : one_view.regions())
    {
      double brute = 0.;
      for(std::size_t v : r.nodes)
        brute += one_view.node_class(v) != BS::Force_class::Untouched ? one_view.node_area(v) : 0.;
      BS_CHECK(std::abs(r.covered_area - brute) <= 1e-12 * r.area && r.covered_area <= r.area,
               "covered area " << r.covered_area << " of a region of area " << r.area << ", by its nodes " << brute);
      covered += r.covered_area;
      total += r.area;
    }
    // The nodes reached are those of the faces the seen half's points land
    // on: the half, and at most one edge's band (area 2 pi h) beyond the equator.
    const double band = 2. * M_PI * domain.max_edge_length();
    BS_CHECK(covered > 0.98 * 2. * M_PI && covered < 2. * M_PI + band && std::abs(total - 4. * M_PI) < 0.02 * 4. * M_PI,
             "one view of the sphere: covered area " << covered << " (2 pi, plus at most " << band << "), area " << total
                                                     << " (4 pi)");
    std::cout << "  one view of the sphere: " << one_view.regions().size() << " regions, covered area " << covered
              << ", area " << total << std::endl;
  }

  // Two regions: x > 0 and x < 0, each across both charts (the seam is the equator).
  const auto& R = regions.regions();
  BS_CHECK(R.size() == 2, R.size() << " regions instead of 2");
  for(const auto& r : R)
  {
    BS_CHECK(std::abs(r.flux - r.sign * M_PI) < 0.03 * M_PI, "flux " << r.flux << " of a region of sign " << r.sign
                                                                     << ", not " << r.sign << " pi");
    BS_CHECK(std::abs(r.area - 2. * M_PI) < 0.03 * 2. * M_PI, "area " << r.area << " of a half sphere");
    bool both_charts[2] = {false, false};
    for(std::size_t v : r.nodes)
    {
      both_charts[domain.node(v).canonical.u.chart] = true;
      const double x = eig<K>(domain.node(v).position).x();
      BS_CHECK(r.sign * x > -0.1, "node at x = " << x << " in the region of sign " << r.sign);
    }
    BS_CHECK(both_charts[0] && both_charts[1], "a half sphere's region is in one chart only");
  }

  // Eq. 13 against a sum over the faces: F interpolated linearly over each
  // face whose centroid is canonically in its own chart, a third of the
  // area to each corner on the surface, added to the corner's region.
  std::vector<double> flux(R.size(), 0.);
  for(std::size_t k = 0; k < pieces.pieces().size(); ++k)
  {
    const auto& cm = pieces.pieces()[k].mesh;
    for(auto f : cm.mesh().faces())
    {
      const auto corners = cm.face_vertices(f);
      const auto centre = sphere.canonical_point(
        BS::Shape_point(0, sphere.component(0).shape().canonical_chart_point(cm.chart_point(f, {{1. / 3, 1. / 3, 1. / 3}}))));
      if(!centre || centre->u.chart != cm.chart_index())
        continue;
      const Eigen::Vector3d p0 = eig<K>(cm.mesh().point(corners[0])), p1 = eig<K>(cm.mesh().point(corners[1])),
                            p2 = eig<K>(cm.mesh().point(corners[2]));
      const double a = 0.5 * (p1 - p0).cross(p2 - p0).norm();
      for(auto c : corners)
      {
        const std::size_t v = domain.node_of(k, c);
        flux[regions.node_region(v)] += a / 3. * regions.node_force(v);
      }
    }
  }
  for(std::size_t i = 0; i < R.size(); ++i)
    BS_CHECK(std::abs(flux[i] - R[i].flux) <= 1e-12 * std::abs(R[i].flux),
             "region " << i << ": flux " << R[i].flux << ", sum over the faces " << flux[i]);

  // One boundary: the great circle x = 0.
  BS_CHECK(regions.boundaries().size() == 1, regions.boundaries().size() << " boundaries instead of 1");
  if(const auto* b = regions.best_boundary())
  {
    BS_CHECK(b->centroid.norm() < 0.05, "boundary centroid " << b->centroid.transpose());
    BS_CHECK(R[b->regions[0]].sign == 1 && R[b->regions[1]].sign == -1, "the outward region is not first");
    BS_CHECK(std::abs(b->flux_difference - 2. * M_PI) < 0.03 * 2. * M_PI, "flux difference " << b->flux_difference);
    for(const auto& e : b->edges)
      for(std::size_t v : e)
        BS_CHECK(std::abs(eig<K>(domain.node(v).position).x()) < 0.25, "boundary node far from x = 0");
  }
  std::cout << "  sphere: area " << area << " (4 pi = " << 4. * M_PI << "), noise " << regions.noise()
            << ", fluxes " << R[0].flux << " " << (R.size() > 1 ? R[1].flux : 0.) << " (+-pi)" << std::endl;
}

// A body (an ellipsoid) with a round part sticking out along `axis` from the
// body's surface point `foot` (the true region's centre; the part's width
// is its size): noisy samples of the union's surface.
template <class K>
void test_protruding_part(const std::string& name, const Eigen::Vector3d& body_axes, const Eigen::Vector3d& foot,
                          const Eigen::Vector4d& rotation, const Eigen::Vector3d& axis, bool explains_part)
{
  typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Primitive_model;
  const double radius = 0.3;
  const Primitive_model body(BS::Superquadric_ellipsoid<K>(body_axes[0], body_axes[1], body_axes[2], 1., 1.));
  const Primitive_model part(BS::Superquadric_ellipsoid<K>(radius, radius, 0.5, 0.4, 1.), foot + 0.3 * axis, rotation);
  const std::size_t n = reduced ? 3000 : 8000;
  std::mt19937_64 rng(11);
  const double noise = 0.006; // 0.2 % of the body's diagonal, about 3
  const std::vector<typename K::Point_3> points =
    BS::testing::scan_of_union<typename K::Point_3>(body, part, n, noise, rng);
  // One superquadric, fitted robustly (the default) from the body itself, so
  // that its frame stays the body's: it comes to rest on the body and takes
  // the part's points for strays. They pull all the same (weight 1), and the
  // equilibrated rest of the body stays a region of its own.
  typedef BS::Deformable_blended_model<K> Model;
  BS::Deformable_model_fitter<Model> fitter(points, Model(BS::Blended_shape<K>(body.shape())));
  const BS::Fitting_status status = fitter.run();
  const Model& model = fitter.model();
  const BS::Blended_shape_pieces<K> pieces(model.shape(), resolution);
  const BS::Quotient_domain<K> domain(model.shape(), pieces, 1);
  const BS::Force_regions<K> regions(domain, BS::normal_forces(fitter, false),
                                     BS::Force_regions<K>::default_threshold_factor, BS::Equilibrated_regions::Kept);

  // The best boundary goes around the part's base: its centroid within a
  // quarter of the part's width of the part's axis, and within the part's
  // width of the body's surface along it.
  const auto* best = regions.best_boundary();
  BS_CHECK(best != nullptr, name << ": no boundary");
  if(best == nullptr)
    return;
  const Eigen::Vector3d centroid = model.translation() + model.rotation() * best->centroid;
  const double centroid_along = (centroid - foot).dot(axis);
  const double centroid_off = ((centroid - foot) - centroid_along * axis).norm();
  BS_CHECK(centroid_off <= 0.25 * 2. * radius && std::abs(centroid_along) <= 2. * radius,
           name << ": the best boundary's centroid " << centroid.transpose() << " is " << centroid_off
                << " from the part's axis and " << centroid_along << " along it from the body");
  std::cout << "  " << name << ": " << points.size() << " points, rest after " << status.iterations
            << " iterations, noise " << regions.noise() << ", " << regions.regions().size() << " regions, "
            << regions.boundaries().size() << " boundaries; the best one " << centroid_off
            << " from the part's axis" << std::endl;

  // The split there: its region's centre within a quarter of the part's
  // width of the part's axis, the part's side inside it, no point moved.
  const std::optional<BS::Split_proposal> proposal = BS::propose_split(regions);
  BS_CHECK(bool(proposal), name << ": no split proposed along the part's base");
  if(!proposal)
    return;
  const Model split = BS::apply_split(model, *proposal);
  const BS::Chart_point centre(proposal->chart, proposal->region[0], proposal->region[1]);
  const Eigen::Vector3d x = eig<K>(model.point(model.chart_point(BS::Shape_point(proposal->component, centre))));
  const double along = (x - foot).dot(axis), off = ((x - foot) - along * axis).norm();
  BS_CHECK(off <= 0.25 * 2. * radius, name << ": the split region's centre " << x.transpose() << " is " << off
                                            << " from the part's axis");
  auto mean_along_axis = [&](std::size_t region) {
    double sum = 0.;
    for(std::size_t v : regions.regions()[region].nodes)
      sum += (model.translation() + model.rotation() * eig<K>(domain.node(v).position) - foot).dot(axis);
    return sum / double(regions.regions()[region].nodes.size());
  };
  const auto& b = *best;
  const std::size_t other = b.regions[0] == proposal->new_part_region ? b.regions[1] : b.regions[0];
  BS_CHECK(mean_along_axis(proposal->new_part_region) > mean_along_axis(other),
           name << ": the new part's side is not the part's");
  double moved = 0.;
  for(std::size_t g = 0; g < model.number_of_charts(); ++g)
  {
    const BS::Chart_mesh<K> mesh(g, model.chart_domain(g), resolution);
    for(auto v : mesh.mesh().vertices())
      moved = (std::max)(moved, (eig<K>(model.point(mesh.chart_point(v))) - eig<K>(split.point(mesh.chart_point(v)))).norm());
  }
  BS_CHECK(moved <= 1e-12, name << ": the split moved a point by " << moved);

  // Fitting on from the split, by least squares so that the part's points
  // pull the new component out (the robust fit may still take them for
  // strays): where the region could be given its size (`explains_part`),
  // the mean squared distance of all points falls fourfold at least within
  // 20 iterations. (Across the seam the chart's margin shrinks the region to
  // a sliver: see the manual.)
  const double before = fitter.mean_squared_distance(true);
  BS::Fitting_settings least_squares;
  least_squares.robust_weighting = BS::Robust_weighting::None;
  least_squares.maximum_iterations = 20; // the test is where it goes, not where it comes to rest
  BS::Deformable_model_fitter<Model> on(points, split, least_squares);
  on.run();
  const double after = on.mean_squared_distance(true);
  if(explains_part)
    BS_CHECK(after < 0.25 * before, name << ": the mean squared distance went from " << before << " to " << after);
  std::cout << "    split: region " << proposal->region.head<5>().transpose() << " in chart " << proposal->chart
            << ", centre " << off << " from the axis, points moved " << moved << ", mean squared distance " << before
            << " -> " << after << std::endl;
}

template <class K>
void test_bad_input()
{
  const BS::Blended_shape<K> sphere(BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1.));
  const BS::Blended_shape_pieces<K> pieces(sphere, 8);
  const BS::Quotient_domain<K> domain(sphere, pieces, 1);
  const std::vector<BS::Normal_force> good = sphere_forces<K>(sphere, 200, 0.01);
  auto refused = [&](const std::vector<BS::Normal_force>& forces, double factor, const std::string& expected) {
    BS_CHECK_REFUSED(std::invalid_argument, BS::Force_regions<K> r(domain, forces, factor), expected);
  };
  // a split along a boundary that does not exist, and a split the shape refuses
  const BS::Force_regions<K> regions(domain, good);
  bool out_of_range = false;
  try
  {
    BS::propose_split(regions, regions.boundaries().size());
  }
  catch(const std::out_of_range& e)
  {
    out_of_range = std::string(e.what()).find("no boundary") != std::string::npos;
  }
  BS_CHECK(out_of_range, "propose_split() of a boundary that does not exist: no clear std::out_of_range");
  BS::Split_proposal outside;
  outside.region = BS::Ellipse_blending_region::make_parameters(5., 0., 0.3, 0.3, 0.);
  outside.half_width = 0.05;
  BS_CHECK_REFUSED(std::invalid_argument, BS::apply_split(BS::Deformable_blended_model<K>(sphere), outside),
                   "apply_split: the proposed split is refused");

  refused({}, 3., "no forces");
  refused(good, -1., "threshold_factor");
  refused(good, std::nan(""), "threshold_factor");
  for(int kind = 0; kind < 4; ++kind)
  {
    std::vector<BS::Normal_force> bad = good;
    BS::Normal_force& f = bad[17];
    if(kind == 0)
      f.normal_distance = std::nan("");
    else if(kind == 1)
      f.weight = -0.5;
    else if(kind == 2)
      f.point.u.chart = 5;
    else
      f.point.u.x = 3.;
    refused(bad, 3., "force 17");
  }
}

// Counts the evolution events it hears of.
struct Counting_visitor : BS::Default_evolution_visitor
{
  std::size_t splits = 0, undos = 0, removes = 0;
  std::size_t parts = 0; // of the model the last hook saw
  std::size_t phases[3] = {0, 0, 0}; // per Evolution_phase
  void on_evolution_phase(BS::Evolution_phase p, std::size_t) { ++phases[std::size_t(p)]; }
  template <class Model>
  void on_split(const BS::Evolution_event& e, const Model& m)
  {
    splits += e.accepted() ? 1 : 1000;
    parts = m.shape().number_of_components();
  }
  template <class Model>
  void on_undo(const BS::Evolution_event& e, const Model& m)
  {
    undos += e.kind == BS::Evolution_event_kind::Undo || e.kind == BS::Evolution_event_kind::Revert ? 1 : 1000;
    parts = m.shape().number_of_components();
  }
  template <class Model>
  void on_remove(const BS::Evolution_event& e, const Model& m)
  {
    removes += e.kind == BS::Evolution_event_kind::Remove ? 1 : 1000;
    parts = m.shape().number_of_components();
  }
};

// A visitor that writes down the iterations of each fit of the first split
// (from the Split_fit phase of a two-part model to its event) to `fits`
// (shared by its copies).
struct First_split_fits_visitor : BS::Default_evolution_visitor
{
  std::vector<std::size_t>* fits;
  bool in_split = false;
  void on_evolution_phase(BS::Evolution_phase p, std::size_t parts)
  {
    in_split = p == BS::Evolution_phase::Split_fit && parts == 2 && fits->empty();
  }
  void on_iteration(std::size_t iteration, double, std::size_t)
  {
    if(in_split && iteration == 1)
      fits->push_back(0);
    if(in_split && !fits->empty())
      ++fits->back();
  }
  template <class Model>
  void on_split(const BS::Evolution_event&, const Model&) { in_split = false; }
  template <class Model>
  void on_undo(const BS::Evolution_event&, const Model&) { in_split = false; }
};

// A visitor that writes down every hook it hears, with its arguments (the
// energies and description lengths to the bit), to `heard` (shared by its
// copies), to compare what two calls told their visitors.
struct Logging_visitor : BS::Default_evolution_visitor
{
  std::vector<std::string>* heard;
  void on_phase(BS::Fitting_phase p, std::size_t iteration) { log("phase", std::size_t(p), iteration); }
  void on_iteration(std::size_t iteration, double energy, std::size_t points)
  {
    log("iteration", iteration, points, energy);
  }
  void on_evolution_phase(BS::Evolution_phase p, std::size_t parts) { log("evolution phase", std::size_t(p), parts); }
  template <class Model>
  void on_split(const BS::Evolution_event& e, const Model& m) { log_event(e, m); }
  template <class Model>
  void on_undo(const BS::Evolution_event& e, const Model& m) { log_event(e, m); }
  template <class Model>
  void on_remove(const BS::Evolution_event& e, const Model& m) { log_event(e, m); }

private:
  template <class Model>
  void log_event(const BS::Evolution_event& e, const Model& m)
  {
    log("event", std::size_t(e.kind), m.shape().number_of_components(), e.description_length_after,
        m.parameters().sum());
  }
  template <class... T>
  void log(const char* what, const T&... values)
  {
    std::ostringstream out;
    out << what << std::setprecision(17);
    ((out << ' ' << values), ...);
    heard->push_back(out.str());
  }
};

// Settings whose proposals come from `source`; by default the force
// analysis at rest (the paper's rule; crease segments are the default of
// Evolution_settings): the tests of proposals, undo and removal need a
// source that proposes splits on one superquadric.
BS::Evolution_settings splits_from(BS::Split_source source = BS::Split_source::Force_regions)
{
  BS::Evolution_settings s;
  s.split_source = source;
  return s;
}

// The two sources of split proposals, for the tests that run both.
constexpr BS::Split_source each_split_source[] = {BS::Split_source::Force_regions,
                                                   BS::Split_source::Crease_segments};

// Evolution of the fit of one superquadric to `points`.
template <class K>
BS::Part_evolution<K> evolution_of(const std::vector<typename K::Point_3>& points,
                                   const BS::Evolution_settings& settings = splits_from())
{
  const auto first = BS::fit_superquadric(points);
  return BS::Part_evolution<K>(points, BS::make_blended_model(first.model), BS::Fitting_settings(), settings);
}

// Every split proposed holds data: the new part, a copy of its base at
// h = 0, moves only as far as the points on it pull it. On a single view
// the force regions also grow over the unseen side; a region centred on its
// middle by area can fall there, and a nearly straight boundary gives a
// sliver of an ellipse: either holds no point (the split is at rest from
// its start and wastes a try; here the sliver did, before its width was
// floored). The body with a part is seen from one side (the points with
// y > -0.2): every proposal's new component is the closest place of some of
// the points.
template <class K>
void test_proposals_hold_data()
{
  std::vector<typename K::Point_3> points;
  for(const auto& p : BS::testing::body_with_part_scan<K>(reduced ? 1500 : 4000, 3))
    if(CGAL::to_double(p.y()) > -0.2)
      points.push_back(p);
  BS::Part_evolution<K> evolution = evolution_of<K>(points);
  evolution.fit_to_rest();
  const std::vector<BS::Split_proposal> proposals = evolution.propose_splits();
  BS_CHECK(!proposals.empty(), "one view of the body with a part: no split proposed");
  std::vector<typename K::Point_3> kept;
  for(const Eigen::Vector3d& p : evolution.fitter().points())
    kept.emplace_back(p.x(), p.y(), p.z());
  std::ostringstream counts;
  for(const BS::Split_proposal& proposal : proposals)
  {
    typedef BS::Deformable_blended_model<K> Model;
    BS::Deformable_model_fitter<Model> split(kept, BS::apply_split(evolution.model(), proposal),
                                             evolution.fitter().settings());
    split.start_from_foot_points_of(evolution.fitter());
    const std::size_t new_component = split.model().shape().number_of_components() - 1;
    std::size_t on_part = 0;
    for(const auto& f : split.forces())
      on_part += split.model().chart_component(f.chart_point.chart) == new_component ? 1 : 0;
    BS_CHECK(on_part > 0, "one view of the body with a part: the split along boundary " << proposal.boundary
                                                                                      << " holds no point");
    counts << " " << on_part;
  }
  std::cout << "  one view of the body with a part (" << points.size() << " points): points on each proposal's new part:"
            << counts.str() << std::endl;
}

// Seeded scans of single superquadrics (full and single view, noise 0.2 %
// of the diagonal) come out of evolution with one part, splits from force
// regions or from crease segments (the default): every split tried is
// undone, and each undo restores the model at rest bit for bit (its
// parameters and structure). The visitor hears of every undo, of no split.
// (The force analysis proposes splits here, so the undo is tested; the
// crease segments of one superquadric are one piece, nothing to split off.)
template <class K>
void test_no_over_splitting(BS::Split_source source)
{
  std::size_t tried = 0;
  const BS::Evolution_settings settings = splits_from(source);
  const std::string name = BS::split_source_name(source);
  for(bool single_view : {false, true})
  {
    std::mt19937_64 rng(2); // (a seed whose fits at rest give proposals to try)
    const auto truth = BS::testing::random_superellipsoid<K>(rng);
    const auto points = BS::testing::synthetic_scan(truth, reduced ? 1500 : 3000, single_view, 0.002, rng);
    BS::Part_evolution<K> evolution = evolution_of<K>(points, settings);
    evolution.fit_to_rest();
    const Eigen::VectorXd at_rest = evolution.model().parameters();
    Counting_visitor visitor;
    for(const BS::Split_proposal& p : evolution.propose_splits())
    {
      const bool kept = evolution.try_split(p, visitor);
      BS_CHECK(!kept, name << ", " << (single_view ? "single" : "full") << " view: a split of one superquadric was kept");
      if(kept)
        return;
      ++tried;
      BS_CHECK(evolution.model().shape().number_of_components() == 1 && evolution.model().shape().number_of_blends() == 0,
               "an undone split left " << evolution.model().shape().number_of_components() << " components");
      BS_CHECK(BS::testing::same_bits(evolution.model().parameters(), at_rest), "an undone split did not restore the parameters");
    }
    const BS::Evolution_status status = evolution.run(visitor);
    BS_CHECK(evolution.model().shape().number_of_components() == 1,
             name << ", " << (single_view ? "single" : "full") << " view: "
                  << evolution.model().shape().number_of_components() << " parts instead of 1");
    BS_CHECK(!status.aborted && !status.part_limit_reached, "evolution of one superquadric: wrong status");
    std::size_t undone = 0;
    for(const auto& e : evolution.events())
    {
      undone += e.accepted() ? 0 : 1;
      BS_CHECK(e.accepted() == (e.description_length_after < e.description_length_before),
               "an event kept (" << e.accepted() << ") against its description lengths "
                                 << e.description_length_before << " -> " << e.description_length_after);
    }
    // run(): one fit to rest and one analysis with its proposals (no split kept); a split fit per event.
    BS_CHECK(visitor.phases[0] == 1 && visitor.phases[1] == 1 && visitor.phases[2] == evolution.events().size(),
             "evolution phases heard: " << visitor.phases[0] << " fits to rest, " << visitor.phases[1]
                                        << " analyses, " << visitor.phases[2] << " split fits for "
                                        << evolution.events().size() << " events");
    BS_CHECK(visitor.splits == 0 && visitor.undos == undone && (undone == 0 || visitor.parts == 1),
             "the visitor heard of " << visitor.splits << " splits and " << visitor.undos << " undos, not 0 and "
                                     << undone << ", the last of a model of " << visitor.parts << " parts");
    std::cout << "  one superquadric, " << (single_view ? "single" : "full") << " view, " << name << ": "
              << evolution.events().size() << " splits tried and undone, " << status.iterations << " iterations"
              << std::endl;
  }
  // Without a tried split, the restore above is not tested.
  if(source == BS::Split_source::Force_regions)
    BS_CHECK(tried > 0, "no split was proposed on the noisy single superquadrics");
}
template <class K>
void test_no_over_splitting()
{
  for(BS::Split_source source : each_split_source)
    test_no_over_splitting<K>(source);
}

// Parts that no longer pay for their parameters go. On a noisy scan of one
// superquadric, its fit split (the copy at h = 0) and fitted to rest has
// its part merged back into the base: one Remove event whose description
// length does not rise, the visitor's on_remove() with the one-part model.
// merge_split() undoes split() bit for bit and refuses the root and a part
// that others are built on.
template <class K>
void test_remove_unpaid_parts()
{
  std::mt19937_64 rng(2);
  const auto truth = BS::testing::random_superellipsoid<K>(rng);
  const auto points = BS::testing::synthetic_scan(truth, 1500, false, 0.002, rng);
  BS::Part_evolution<K> one = evolution_of<K>(points);
  one.fit_to_rest();
  const std::vector<BS::Split_proposal> proposals = one.propose_splits();
  BS_CHECK(!proposals.empty(), "no split proposed on the noisy superquadric");
  if(proposals.empty())
    return;
  const BS::Deformable_blended_model<K> split = BS::apply_split(one.model(), proposals.front());

  BS::Blended_shape<K> merged = split.shape();
  merged.merge_split(1);
  BS_CHECK(merged.number_of_components() == 1 && merged.number_of_blends() == 0 &&
             BS::testing::same_bits(merged.parameters(), one.model().shape().parameters()),
           "merge_split() did not undo split() exactly");
  auto refused = [&](const char* what, const BS::Blended_shape<K>& shape, std::size_t c, const std::string& expected) {
    BS::Blended_shape<K> s = shape;
    try
    {
      s.merge_split(c);
    }
    catch(const std::logic_error& e)
    {
      BS_CHECK(std::string(e.what()).find(expected) != std::string::npos, what << ": message \"" << e.what() << "\"");
      return;
    }
    BS_CHECK(false, what << ": not refused");
  };
  refused("merge_split of the root", split.shape(), 0, "the root cannot be removed");
  refused("merge_split of a component that does not exist", split.shape(), 2, "no component 2");
  {
    // the copy split again, inside its region (half the ellipse)
    BS::Split_proposal inner = proposals.front();
    inner.region.segment<2>(BS::Ellipse_blending_region::E_1) *= 0.5;
    BS::Blended_shape<K> nested = split.shape();
    nested.split(1, inner.chart, inner.region, 0.5 * inner.half_width);
    refused("merge_split of a part that is split again", nested, 1, "is based on component 1");
  }

  {
    // a part added by a gradual blend is no split's
    BS::Blended_shape<K> with_part = one.model().shape();
    with_part.add_part(0, 0, BS::Ellipse_blending_region::make_parameters(0., 0., 0.3, 0.3, 0., 0.9, 1.), 0.05,
                       BS::Superquadric_ellipsoid<K>(0.2, 0.2, 0.3, 1., 1.), "superquadric_ellipsoid",
                       Eigen::Vector3d(0., 0., 0.5), Eigen::Vector4d(1., 0., 0., 0.), 0,
                       BS::Ellipse_blending_region::make_parameters(0., 0., 0.8, 0.8, 0., 1., 0.), 0.1);
    refused("merge_split of a part added by add_part()", with_part, 1, "is not added by a split");
  }

  BS::Part_evolution<K> evolution(points, split);
  evolution.fit_to_rest();
  BS::Blended_shape<K> expected = evolution.model().shape();
  expected.merge_split(1);
  Counting_visitor visitor;
  const std::size_t removed = evolution.remove_unpaid_parts(visitor);
  BS_CHECK(BS::testing::same_bits(evolution.model().shape().parameters(), expected.parameters()),
           "the model after the removal is not the model before it with its part merged back");
  BS_CHECK(removed == 1 && evolution.model().shape().number_of_components() == 1 &&
             evolution.model().shape().number_of_blends() == 0,
           removed << " parts removed, " << evolution.model().shape().number_of_components() << " left");
  BS_CHECK(evolution.events().size() == removed, evolution.events().size() << " events for " << removed << " removed");
  for(const BS::Evolution_event& e : evolution.events())
  {
    BS_CHECK(e.kind == BS::Evolution_event_kind::Remove && e.component == 1 && !e.accepted() &&
               e.description_length_after <= e.description_length_before,
             "removal event: kind " << BS::evolution_event_name(e.kind) << ", component " << e.component
                                    << ", description length " << e.description_length_before << " -> "
                                    << e.description_length_after);
    std::cout << "  a split part of one superquadric removed: description length " << e.description_length_before
              << " -> " << e.description_length_after << ", RMS " << e.rms_before << " -> " << e.rms_after
              << std::endl;
  }
  BS_CHECK(visitor.removes == 1 && visitor.splits == 0 && visitor.undos == 0 && visitor.parts == 1,
           "the visitor heard of " << visitor.removes << " removals (" << visitor.splits << " splits, "
                                   << visitor.undos << " undos), the last with " << visitor.parts << " parts");
}

// The part limit, the abort callback and bad settings.
template <class K>
void test_evolution_limits()
{
  std::mt19937_64 rng(2); // (a seed whose fit at rest gives proposals)
  const auto truth = BS::testing::random_superellipsoid<K>(rng);
  const auto points = BS::testing::synthetic_scan(truth, 1500, false, 0.002, rng);
  BS::Evolution_settings one_part = splits_from();
  one_part.maximum_number_of_parts = 1;
  BS::Part_evolution<K> limited = evolution_of<K>(points, one_part);
  const BS::Evolution_status s = limited.run();
  BS_CHECK(s.part_limit_reached && limited.events().empty(), "maximum_number_of_parts = 1 tried a split");

  // Stopped at once: no iteration, the model as it was.
  BS::Part_evolution<K> stopped = evolution_of<K>(points);
  const Eigen::VectorXd start = stopped.model().parameters();
  const BS::Evolution_status a = stopped.run(BS::Default_evolution_visitor(), [](double) { return false; });
  BS_CHECK(a.aborted && !a.converged && a.iterations == 0,
           "aborted at once: status aborted " << a.aborted << ", " << a.iterations << " iterations");
  BS_CHECK(BS::testing::same_bits(stopped.model().parameters(), start), "evolution stopped at once moved the model");
  // Stopped while fitting a split: the split is undone, bit for bit.
  stopped.fit_to_rest();
  const Eigen::VectorXd at_rest = stopped.model().parameters();
  const std::vector<BS::Split_proposal> proposals = stopped.propose_splits();
  BS_CHECK(!proposals.empty(), "no proposal to stop in");
  if(!proposals.empty())
  {
    Counting_visitor visitor;
    const bool kept = stopped.try_split(proposals.front(), visitor, [](double) { return false; });
    BS_CHECK(!kept && visitor.undos == 1 && stopped.model().shape().number_of_components() == 1 &&
               BS::testing::same_bits(stopped.model().parameters(), at_rest),
             "a split stopped while fitting was not undone exactly");
  }

  // the default settings with one member set to `value`: refused, the message naming it
  auto refused_member = [&](auto member, auto value, const std::string& expected) {
    BS::Evolution_settings bad;
    bad.*member = value;
    BS_CHECK_REFUSED(std::invalid_argument, evolution_of<K>(points, bad), expected);
  };
  typedef BS::Evolution_settings S;
  refused_member(&S::maximum_number_of_parts, std::size_t(0), "maximum_number_of_parts");
  refused_member(&S::target_accuracy, std::nan(""), "target_accuracy");
  refused_member(&S::maximum_split_tries, std::size_t(0), "maximum_split_tries");
  refused_member(&S::threshold_factor, -1., "threshold_factor");
  refused_member(&S::blend_stages, std::size_t(0), "blend_stages");
  refused_member(&S::intermediate_stage_iterations, std::size_t(0), "intermediate_stage_iterations");
  refused_member(&S::first_split_blend_stages, std::size_t(0), "first_split_blend_stages");
  refused_member(&S::first_split_stage_iterations, std::size_t(0), "first_split_stage_iterations");
  refused_member(&S::evolution_runs, std::size_t(0), "evolution_runs");
  refused_member(&S::split_source, static_cast<BS::Split_source>(7), "split_source");
  for(BS::Split_source source : {BS::Split_source::Force_regions, BS::Split_source::Crease_segments, BS::Split_source::Both})
    BS_CHECK(BS::split_source_from_name(BS::split_source_name(source)) == source,
             "the split source named " << BS::split_source_name(source) << " is not found by its name");
  BS_CHECK(!BS::split_source_from_name("sideways"), "a split source named sideways");
  refused_member(&S::maximum_evolution_points, std::size_t(10),
                 "maximum_evolution_points must be 0 (evolution on all points) or at least 100");
  // a reference mesh without faces, before any fitting (at once: no callback call)
  const CGAL::Surface_mesh<typename K::Point_3> empty;
  std::size_t calls = 0;
  BS_CHECK_REFUSED(std::invalid_argument,
                   BS::fit_blended_shape(points, BS::parameters::reference_mesh(&empty).callback(
                                                   std::function<bool(double)>([&](double) { ++calls; return true; }))),
                   "fit_blended_shape: the reference mesh has no faces");
  BS_CHECK(calls == 0, "an empty reference mesh was refused after " << calls << " fitting iterations");
  // One point repeated and one other: evolution sets the other aside as
  // isolated, and must not then refuse the identical rest ("all points are
  // identical"), a cloud the fit of one superquadric took.
  std::vector<typename K::Point_3> repeated(200, typename K::Point_3(0.1, 0.2, 0.3));
  repeated.emplace_back(1., 1., 1.);
  bool fitted = true;
  std::string message;
  try
  {
    BS::fit_blended_shape(repeated, CGAL::parameters::number_of_iterations(20));
  }
  catch(const std::exception& e)
  {
    fitted = false;
    message = e.what();
  }
  BS_CHECK(fitted, "a repeated point and one other: " << message);
}

// A split model fitted to rest by least squares, from the robust fit of one
// superquadric to a body with a part (where the split's strip once reached
// past its chart's rim between the points the region check samples, and the
// fit stopped with "chart point ... is outside the domain"): it comes to
// rest, and the part's points pull the mean squared distance down. (Whether
// that part then pays for its parameters depends on the rest state reached
// from this poor start, which differs between the kernels: with
// Simple_cartesian the base became an octahedron and the part a flat
// sliver off the data that remove_unpaid_parts() rightly removes. A part
// that pays is kept in test_structure_equivariance(), through run().)
// The robust fit is not mended (mend_missed_surfaces(false)): it leaves
// the part out, the poor start this test is about. (Mended, it holds body
// and part, and the split's region then lies where the foot points of the
// check below, taken over at the same distances, moved by up to 1e-8 in
// chart coordinates, over its 1e-12.)
template <class K>
void test_split_model_fits_to_rest()
{
  typedef BS::Deformable_blended_model<K> Model;
  const auto points = BS::testing::body_with_part_scan<K>(4000, 1);
  const auto first = BS::fit_superquadric(points, BS::parameters::mend_missed_surfaces(false));
  BS::Deformable_model_fitter<Model> robust(points, BS::make_blended_model(first.model));
  robust.run();
  const BS::Blended_shape_pieces<K> pieces(robust.model().shape(), resolution);
  const BS::Quotient_domain<K> domain(robust.model().shape(), pieces, 1);
  const BS::Force_regions<K> regions(domain, BS::normal_forces(robust, false),
                                     BS::Force_regions<K>::default_threshold_factor, BS::Equilibrated_regions::Kept);
  const std::optional<BS::Split_proposal> proposal = BS::propose_split(regions);
  BS_CHECK(bool(proposal), "no split proposed on the body with a part");
  if(!proposal)
    return;
  BS::Fitting_settings least_squares;
  least_squares.robust_weighting = BS::Robust_weighting::None;
  BS::Deformable_model_fitter<Model> on(points, BS::apply_split(robust.model(), *proposal), least_squares);
  const double before = on.mean_squared_distance(true);

  // Started from the foot points of the fitter before the split, the split
  // model's fitter finds them again (the split moves no point): the mean
  // squared distance stays that before the split (to the projections'
  // rounding, 1e-9 relatively), and is no larger than what a search from the
  // tessellation alone finds (which can miss foot points: larger, or the
  // same to rounding). Another cloud's fitter is refused.
  {
    BS::Deformable_model_fitter<Model> inheriting(points, BS::apply_split(robust.model(), *proposal), least_squares);
    inheriting.start_from_foot_points_of(robust);
    const double unsplit = robust.mean_squared_distance(true), inherited = inheriting.mean_squared_distance(true);
    BS_CHECK(inherited <= unsplit * (1. + 1e-9) && inherited <= before * (1. + 1e-9),
             "a split model's fitter from the foot points before the split: mean squared distance " << std::setprecision(17) << inherited
               << ", before the split " << unsplit << ", from the tessellation " << before);
    std::cout << "  mean squared distance after a split: " << inherited << " from the foot points before it ("
              << unsplit << " before it), " << before << " from the tessellation" << std::endl;
    const std::vector<typename K::Point_3> fewer(points.begin(), points.begin() + 100);
    const BS::Deformable_model_fitter<Model> other(fewer, robust.model());
    BS_CHECK_REFUSED(std::invalid_argument, inheriting.start_from_foot_points_of(other),
                     "start_from_foot_points_of: the fitters have other points");
  }
  // The points whose foot points the split moved to the new component (the
  // inside of its region) are found there again, at the same chart points
  // (to 1e-12: taken over, not searched for anew, which finds 6 of these 84
  // that closely and, on a mug scan, misses some by far), when the fitter is
  // told where the split moved them (charts_moved_by_split()), and the mean
  // squared distance is that before the split (1e-9 relatively, both ways).
  // A map that is not of the two models (wrong order, wrong size, a chart
  // the model does not have) is refused.
  {
    const Model split_model = BS::apply_split(robust.model(), *proposal);
    const std::size_t copy = split_model.shape().number_of_components() - 1;
    const std::vector<std::size_t> moved = BS::charts_moved_by_split(robust.model(), split_model, proposal->component);
    BS::Deformable_model_fitter<Model> inheriting(points, split_model, least_squares);
    inheriting.start_from_foot_points_of(robust, moved);
    const auto before_split = robust.forces();
    const auto after_split = inheriting.forces();
    std::size_t in_region = 0, found = 0;
    for(std::size_t i = 0; i < before_split.size() && i < after_split.size(); ++i)
    {
      const BS::Chart_point& u = before_split[i].chart_point;
      if(split_model.is_on_surface(u))
        continue;
      ++in_region;
      const BS::Chart_point& v = after_split[i].chart_point;
      found += after_split[i].index == before_split[i].index && split_model.chart_component(v.chart) == copy &&
                   split_model.local_chart(v.chart) == robust.model().local_chart(u.chart) &&
                   std::abs(v.x - u.x) + std::abs(v.y - u.y) <= 1e-12
                 ? 1
                 : 0;
    }
    const double unsplit = robust.mean_squared_distance(true), inherited = inheriting.mean_squared_distance(true);
    BS_CHECK(in_region > 0 && found == in_region && std::abs(inherited - unsplit) <= 1e-9 * unsplit,
             "a split model's fitter told where the split moved the foot points: "
               << found << " of the " << in_region << " points in the region found at their chart points; mean squared distance "
               << std::setprecision(17) << inherited << ", before the split " << unsplit);
    std::cout << "  foot points moved to the new part by the split: " << found << " of " << in_region
              << " found at the same chart points" << std::endl;
    BS_CHECK_REFUSED(std::invalid_argument, BS::charts_moved_by_split(split_model, robust.model(), proposal->component),
                     "charts_moved_by_split: the second model is not the first");
    const std::vector<std::size_t> one_too_many(moved.size() + 1, std::size_t(-1));
    BS_CHECK_REFUSED(std::invalid_argument, inheriting.start_from_foot_points_of(robust, one_too_many), "moved_to has");
    std::vector<std::size_t> beyond = moved;
    beyond.front() = split_model.number_of_charts();
    BS_CHECK_REFUSED(std::invalid_argument, inheriting.start_from_foot_points_of(robust, beyond),
                     "moved_to names chart");
  }
  BS::Fitting_status status;
  std::string error;
  try
  {
    status = on.run();
  }
  catch(const std::exception& e)
  {
    error = e.what();
  }
  BS_CHECK(error.empty(), "the fit of the split model failed: " << error);
  const double after = on.mean_squared_distance(true);
  BS_CHECK(status.converged && after < before, "the fit of the split model: converged " << status.converged
                                               << ", mean squared distance " << before << " -> " << after);
  std::cout << "  split model fitted to rest in " << status.iterations << " iterations, mean squared distance "
            << before << " -> " << after << std::endl;
}

// The one-call evolving fit, fit_blended_shape(), on a noisy scan of one
// superquadric (1500 points, a seed whose rest states give force splits to
// try; the splits from the force regions, so that there are some):
// - one part, every split tried undone, the RMS at most the first fit's
//   distance of all points;
// - its named parameters reach the settings (a part limit of 1 tries no
//   split; 0 is refused with a message naming it);
// - a callback that stops at once leaves the first fit, aborted, no event;
// - 1 and 2 threads give the same bits (model and events);
// - the input moved by a similarity (rotation, translation, scale) gives one
//   part too, and moved and scaled alone (no rotation) the same relative RMS.
template <class K>
void test_fit_blended_shape()
{
  typedef typename K::Point_3 Point_3;
  namespace BSP = BS::parameters;
  std::mt19937_64 rng(2);
  const auto truth = BS::testing::random_superellipsoid<K>(rng);
  const std::vector<Point_3> points = BS::testing::synthetic_scan(truth, 1500, false, 0.002, rng);
  const auto fit = [](const std::vector<Point_3>& p, std::size_t threads) {
    return BS::fit_blended_shape(p, BSP::number_of_threads(threads, BSP::split_source(BS::Split_source::Force_regions)));
  };
  const auto a = fit(points, 1);
  BS_CHECK(a.model.shape().number_of_components() == 1 && !a.events.empty(),
           "one superquadric: " << a.model.shape().number_of_components() << " parts, " << a.events.size()
                                << " splits tried");
  for(const auto& e : a.events)
    BS_CHECK(!e.accepted() && e.rms_before > 0. && e.rms_before < 2. * a.first_fit.metrics.rms,
             "an event of one superquadric: kept " << e.accepted() << ", RMS before " << e.rms_before
                                                   << " against the first fit's " << a.first_fit.metrics.rms);
  // No split kept: fit_superquadric() (robust), bit for bit, with its
  // figures and strays; evolution started from the least-squares fit.
  const auto single = BS::fit_superquadric(points, BSP::number_of_threads(1));
  const auto robust = BS::make_blended_model(single.model);
  BS_CHECK(BS::testing::same_bits(a.model.parameters(), robust.parameters()) &&
             a.metrics.rms == single.metrics.rms && a.stray_points == single.stray_points &&
             a.metrics.iterations == a.first_fit.metrics.iterations + a.status.iterations + single.metrics.iterations,
           "one superquadric: the result is not fit_superquadric()'s");
  const auto least_squares = BS::fit_superquadric(points, BSP::robust_weighting(BS::Robust_weighting::None));
  BS_CHECK(BS::testing::same_bits(a.first_fit.model.parameters(), least_squares.model.parameters()),
           "evolution did not start from the least-squares fit");
  std::cout << "  fit_blended_shape, one superquadric: " << a.events.size() << " splits tried and undone, RMS "
            << a.metrics.rms << " (" << a.metrics.rms_over_bbox_diagonal << " of the diagonal)" << std::endl;

  const auto limited = BS::fit_blended_shape(points, BSP::maximum_number_of_parts(std::size_t(1)));
  BS_CHECK(limited.events.empty() && limited.status.part_limit_reached &&
             BS::testing::same_bits(limited.model.parameters(), robust.parameters()) &&
             BS::testing::same_bits(limited.first_fit.model.parameters(), single.model.parameters()),
           "maximum_number_of_parts(1): a split tried, or not the fit of fit_superquadric()");

  // Evolution on a sample (500 of the 1500 points) starts from the
  // least-squares fit of the sample alone; with one part at the end, the
  // result is still fit_superquadric()'s of all the points, bit for bit.
  const auto on_sample = BS::fit_blended_shape(
    points, BSP::maximum_evolution_points(std::size_t(500), BSP::split_source(BS::Split_source::Force_regions)));
  BS_CHECK(on_sample.number_of_parts() == 1 && on_sample.first_fit.metrics.number_of_points <= 500 &&
             BS::testing::same_bits(on_sample.model.parameters(), robust.parameters()) &&
             on_sample.metrics.rms == single.metrics.rms && on_sample.stray_points == single.stray_points,
           "evolution on a sample of one superquadric: " << on_sample.number_of_parts() << " parts, first fit of "
                                                         << on_sample.first_fit.metrics.number_of_points
                                                         << " points, or not the result of fit_superquadric()");

  const auto b = fit(points, 2);
  bool same = BS::testing::same_bits(a.model.parameters(), b.model.parameters()) && a.events.size() == b.events.size();
  for(std::size_t i = 0; same && i < a.events.size(); ++i)
    same = BS::testing::same_bits(a.events[i].description_length_after, b.events[i].description_length_after);
  BS_CHECK(same, "fit_blended_shape at 1 and 2 threads: different results");

  BS::testing::Similarity T = BS::testing::random_similarity(rng, 3.7, 10.);
  for(bool rotated : {true, false})
  {
    if(!rotated)
      T.R = Eigen::Matrix3d::Identity();
    std::vector<Point_3> moved;
    for(const Point_3& p : points)
      moved.push_back(T(p));
    const auto c = fit(moved, 1);
    BS_CHECK(c.model.shape().number_of_components() == 1,
             (rotated ? "rotated" : "scaled and moved") << " input: " << c.model.shape().number_of_components() << " parts");
    if(!rotated)
      BS_CHECK(std::abs(c.metrics.rms_over_bbox_diagonal / a.metrics.rms_over_bbox_diagonal - 1.) <= 1e-6,
               "scaled and moved input: RMS/diagonal " << c.metrics.rms_over_bbox_diagonal << " instead of "
                                                       << a.metrics.rms_over_bbox_diagonal);
  }

  // Stopped at once: in the first fit, which the result holds, with no event.
  const auto stopped =
    BS::fit_blended_shape(points, CGAL::parameters::callback(std::function<bool(double)>([](double) { return false; })));
  BS_CHECK(stopped.status.aborted && stopped.events.empty() && stopped.model.shape().number_of_components() == 1 &&
             stopped.model.parameters().allFinite(),
           "fit_blended_shape stopped at once: aborted " << stopped.status.aborted << ", " << stopped.events.size()
                                                         << " events");

  BS_CHECK_REFUSED(std::invalid_argument, BS::fit_blended_shape(points, BSP::maximum_number_of_parts(std::size_t(0))),
                   "fit_blended_shape: maximum_number_of_parts");
}

// The structure of a blended model: per blend, its kind and which component
// it adds to which ("split 1 on 0; ...").
template <class K>
std::string structure_of(const BS::Blended_shape<K>& shape)
{
  std::ostringstream s;
  for(std::size_t b = 0; b < shape.number_of_blends(); ++b)
    s << int(shape.blend(b).kind()) << ":" << shape.blend(b).added_component() << " on "
      << shape.blend(b).base_component() << "; ";
  return s.str();
}

// Evolution on data made of parts is equivariant: the body with a part
// (two parts at most) comes out as a body and a part split off it (a split
// blend from the force regions, a part blend from the crease segments); the
// input moved by a similarity (rotation, translation, scale 3.7) gives the
// same structure (parts, blends, which is added to which). (Not the same
// RMS: the fits reach rest states that differ with rounding, by several %
// of the RMS here, as the manual says; the RMS ratio is printed.) Seed 2,
// where the force split kept lowers the description length by 78 (Simple_cartesian)
// and 42 (Epick): a decision by so narrow a margin that rounding can flip it
// cannot be equivariant. With seed 1 the best split's margin is -0.15 with
// Simple_cartesian (undone) and +22 with Epick (kept), see the manual.
template <class K>
void test_structure_equivariance(BS::Split_source source)
{
  const auto points = BS::testing::body_with_part_scan<K>(1500, 2);
  std::mt19937_64 rng(1);
  const auto np = BS::parameters::maximum_number_of_parts(std::size_t(2), BS::parameters::split_source(source));
  const std::string name = BS::split_source_name(source);
  const auto a = BS::fit_blended_shape(points, np);
  const std::string structure = structure_of(a.model.shape());
  const BS::Blend_kind kind = source == BS::Split_source::Force_regions ? BS::Blend_kind::Split : BS::Blend_kind::Part;
  BS_CHECK(a.number_of_parts() == 2 && a.model.shape().number_of_blends() == 1 && a.model.shape().blend(0).kind() == kind,
           name << ", body with a part: " << a.number_of_parts() << " parts, structure " << structure);
  // The part kept pays for its parameters: run() checked it after the split.
  for(const auto& e : a.events)
    BS_CHECK(e.kind != BS::Evolution_event_kind::Remove, "body with a part: the part split off was removed");
  const BS::testing::Similarity T = BS::testing::random_similarity(rng, 3.7, 10.);
  std::vector<typename K::Point_3> moved;
  for(const auto& p : points)
    moved.push_back(T(p));
  const auto c = BS::fit_blended_shape(moved, np);
  const double rms_ratio = c.metrics.rms / (T.scale * a.metrics.rms);
  BS_CHECK(structure_of(c.model.shape()) == structure,
           name << ", body with a part, moved by a similarity: structure " << structure_of(c.model.shape())
                << " instead of " << structure);
  std::cout << "  body with a part (" << points.size() << " points), " << name << ": " << a.number_of_parts()
            << " parts (" << structure << "), RMS " << a.metrics.rms << "; moved by a similarity: RMS ratio "
            << rms_ratio << std::endl;
}
template <class K>
void test_structure_equivariance()
{
  for(BS::Split_source source : each_split_source)
    test_structure_equivariance<K>(source);
}

// Evolution on a sample (Evolution_settings::maximum_evolution_points) of
// the body with a part (seed 2, 1500 points, two parts at most, force splits):
// - a maximum of 0 (all points) or of the number of points changes nothing:
//   the same bits as the default, which does not sample 1500 points;
// - with a sample of 500 points the part is split off, the split test
//   counts all the points in its description lengths, and the evolved model
//   is fitted to rest on all of them (the figures are of all points);
// - start_from_chart_points(): a fitter of the same points started from the
//   foot points of a fitter at rest measures the same distances; a wrong
//   number of chart points is refused.
template <class K>
void test_sampled_evolution()
{
  namespace BSP = BS::parameters;
  const auto points = BS::testing::body_with_part_scan<K>(1500, 2);
  const auto forces = BSP::split_source(BS::Split_source::Force_regions);
  const auto a = BS::fit_blended_shape(points, BSP::maximum_number_of_parts(std::size_t(2), forces));
  for(std::size_t maximum : {std::size_t(0), points.size()})
  {
    const auto b = BS::fit_blended_shape(
      points, BSP::maximum_evolution_points(maximum, BSP::maximum_number_of_parts(std::size_t(2), forces)));
    BS_CHECK(BS::testing::same_bits(a.model.parameters(), b.model.parameters()) && a.events.size() == b.events.size() &&
               a.metrics.rms == b.metrics.rms,
             "maximum_evolution_points(" << maximum << ") changed the result");
  }
  const auto c = BS::fit_blended_shape(
    points, BSP::maximum_evolution_points(std::size_t(500), BSP::maximum_number_of_parts(std::size_t(2), forces)));
  const std::size_t fitted = points.size() - c.stray_points.size();
  BS_CHECK(c.number_of_parts() == 2 && c.metrics.number_of_points == fitted && c.status.converged,
           "evolution on 500 points: " << c.number_of_parts() << " parts, figures of " << c.metrics.number_of_points
                                       << " points (" << fitted << " not isolated), converged " << c.status.converged);
  // the final fit on all points holds the regions' curves; the result has them released
  for(std::size_t b = 0; b < c.model.shape().number_of_blends(); ++b)
    for(std::size_t j = BS::Ellipse_blending_region::E_U; j <= BS::Ellipse_blending_region::E_THETA; ++j)
      BS_CHECK(!c.model.shape().is_fixed_parameter(c.model.shape().blend_offset(b) + j),
               "evolution on 500 points: the result's region parameter " << j << " of blend " << b << " is still held");
  for(const auto& e : c.events)
  {
    if(e.kind == BS::Evolution_event_kind::Remove)
      continue;
    // L = (n/2) ln(MSD) + (k/2) ln(n): the difference of two events' L
    // before, at the same model, is 0; the split's gain in (n/2) ln(MSD)
    // is that of all n points, not of the 500.
    const double n = double(fitted);
    const double gain = 0.5 * n * std::log(CGAL::square(e.rms_after / e.rms_before));
    const double dL = e.description_length_after - e.description_length_before;
    const double k_term = dL - gain; // (k_after - k_before)/2 ln(n): a whole number of parameters
    const double k = 2. * k_term / std::log(n);
    BS_CHECK(std::abs(k - std::round(k)) < 1e-6 && std::round(k) > 0.,
             "evolution on 500 points: the split test does not count " << fitted << " points (parameters added: " << k
                                                                         << ")");
  }
  typedef BS::Deformable_model_fitter<BS::Deformable_blended_model<K>> Fitter;
  BS::Fitting_settings least_squares;
  least_squares.robust_weighting = BS::Robust_weighting::None;
  least_squares.subset_size = 0;
  Fitter rest(points, c.model, least_squares);
  rest.run();
  std::vector<BS::Chart_point> starts;
  for(const auto& f : rest.forces())
    starts.push_back(f.chart_point);
  Fitter started(points, rest.model(), least_squares);
  started.start_from_chart_points(starts);
  const double expected = rest.mean_squared_distance(true), measured = started.mean_squared_distance(true);
  BS_CHECK(measured <= expected * (1. + 1e-9),
           "start_from_chart_points: mean squared distance " << measured << " instead of " << expected);
  starts.pop_back();
  BS_CHECK_REFUSED(std::invalid_argument, started.start_from_chart_points(starts), "one per point");
  std::cout << "  evolution on 500 of " << points.size() << " points: " << c.number_of_parts() << " parts, RMS "
            << c.metrics.rms << " (on all points: " << a.metrics.rms << ")" << std::endl;
}

// When evolution keeps no split and the robust fit of one superquadric
// takes more than half of the points for strays, fit_blended_shape()
// returns the least-squares fit, not that robust fit. On the body with a
// part (seed 2, no stray point at all) the robust fit takes about 90 % of
// the points for strays; a target accuracy of 50 % of the diagonal ends
// evolution before any split.
template <class K>
void test_broken_down_robust_fit_not_returned()
{
  const auto points = BS::testing::body_with_part_scan<K>(1500, 2);
  const auto robust = BS::fit_superquadric(points);
  BS_CHECK(2 * robust.stray_points.size() > points.size(),
           "the case does not test the rule: the robust fit takes only " << robust.stray_points.size() << " of "
                                                                          << points.size() << " points for strays");
  const auto a = BS::fit_blended_shape(points, BS::parameters::target_accuracy(0.5));
  BS_CHECK(a.status.target_reached && a.events.empty() && a.number_of_parts() == 1, "no split expected");
  BS_CHECK(BS::testing::same_bits(a.model.parameters(), BS::make_blended_model(a.first_fit.model).parameters()) &&
             a.stray_points.empty() && a.first_fit.stray_points.empty(),
           "a robust fit that took " << robust.stray_points.size() << " of " << points.size()
                                     << " points for strays was returned instead of the least-squares fit");
  // The same with evolution on a sample: the least-squares fit of all the
  // points, not the first fit, which was of the sample.
  const auto s = BS::fit_blended_shape(
    points, BS::parameters::target_accuracy(0.5, BS::parameters::maximum_evolution_points(std::size_t(500))));
  const auto least_squares = BS::fit_superquadric(points, BS::parameters::robust_weighting(BS::Robust_weighting::None));
  BS_CHECK(s.number_of_parts() == 1 && s.first_fit.metrics.number_of_points <= 500 &&
             s.metrics.number_of_points == points.size() && s.stray_points.empty() &&
             BS::testing::same_bits(s.model.parameters(), BS::make_blended_model(least_squares.model).parameters()),
           "evolution on a sample: the result is not the least-squares fit of all the points");
  std::cout << "  body with a part: the robust fit takes " << robust.stray_points.size() << " of " << points.size()
            << " points for strays; the least-squares fit is returned" << std::endl;
}

// A proposal whose region meets an earlier split's region is shrunk about
// its centre until the shape accepts it; one that already fits is kept as it
// is; one centred where an earlier split cut the surface away is dropped.
template <class K>
void test_shrink_to_fit()
{
  typedef BS::Ellipse_blending_region Region;
  BS::Blended_shape<K> shape(BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1.));
  shape.split(0, 0, Region::make_parameters(0., 0., 0.3, 0.3, 0.), 0.06);
  BS::Split_proposal p;
  p.component = 0;
  p.chart = 0;
  p.half_width = 0.06;
  p.region = Region::make_parameters(0.55, 0., 0.3, 0.3, 0.); // meets the strip of the first split
  bool refused = false;
  try
  {
    BS::Blended_shape<K> copy = shape;
    copy.split(p.component, p.chart, p.region, p.half_width);
  }
  catch(const std::invalid_argument&)
  {
    refused = true;
  }
  BS_CHECK(refused, "the overlapping proposal is not refused: the test does not test shrink_to_fit()");
  const std::optional<BS::Split_proposal> shrunk = BS::shrink_to_fit(shape, p);
  BS_CHECK(shrunk.has_value(), "shrink_to_fit(): no region accepted about a centre away from the first split");
  if(shrunk)
  {
    BS_CHECK(shrunk->region[Region::E_U] == 0.55 && shrunk->region[Region::E_V] == 0., "the centre moved");
    BS_CHECK(shrunk->region[Region::E_1] < 0.3 && shrunk->region[Region::E_1] >= 0.3 * 0.2401 &&
               shrunk->region[Region::E_1] == shrunk->region[Region::E_2],
             "radii " << shrunk->region[Region::E_1] << ", " << shrunk->region[Region::E_2]);
    BS_CHECK(std::abs(shrunk->half_width / shrunk->region[Region::E_1] - 0.2) < 1e-12, "the strip is not shrunk with the radii");
    BS::Blended_shape<K> copy = shape;
    copy.split(shrunk->component, shrunk->chart, shrunk->region, shrunk->half_width); // throws if refused
  }
  BS::Split_proposal apart = p;
  apart.region = Region::make_parameters(-0.6, 0.2, 0.15, 0.1, 0.3);
  apart.half_width = 0.02;
  const std::optional<BS::Split_proposal> kept = BS::shrink_to_fit(shape, apart);
  BS_CHECK(kept && kept->region == apart.region && kept->half_width == apart.half_width,
           "a proposal the shape accepts is changed");
  BS::Split_proposal cut = p;
  cut.region = Region::make_parameters(0., 0., 0.3, 0.3, 0.); // where the first split cut the surface away
  BS_CHECK(!BS::shrink_to_fit(shape, cut), "a proposal inside an earlier split's region is accepted");
  // proposals that are not of this shape: a clear error, not "nothing"
  auto not_of_shape = [&](BS::Split_proposal bad, const std::string& expected) {
    BS_CHECK_REFUSED(std::invalid_argument, BS::shrink_to_fit(shape, bad), expected);
  };
  BS::Split_proposal bad = apart;
  bad.component = 7;
  not_of_shape(bad, "no component 7");
  bad = apart;
  bad.chart = 5;
  not_of_shape(bad, "has no chart 5");
  bad = apart;
  bad.region[Region::E_2] = std::nan("");
  not_of_shape(bad, "positive and finite");
  bad = apart;
  bad.half_width = -0.01;
  not_of_shape(bad, "positive and finite");
  std::cout << "  shrink_to_fit: radius 0.3 -> " << (shrunk ? shrunk->region[Region::E_1] : 0.) << std::endl;
}

// A cylinder standing on a box, sampled evenly (noise 0.2 % of the
// diagonal): the concave crease runs around the cylinder's foot; the box's
// and the cylinder's own edges are convex. `truth[i]` is 1 on the cylinder.
void box_with_cylinder(std::vector<Eigen::Vector3d>& points, std::vector<Eigen::Vector3d>& outward,
                       std::vector<int>& truth, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1., 1.);
  std::normal_distribution<double> noise(0., 0.002 * std::sqrt(2. * 2. + 2. * 2. + 2. * 2.));
  const double radius = 0.4, spacing = 0.035; // about one point per spacing^2
  auto add = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& n, int part) {
    points.push_back(p + noise(rng) * n);
    outward.push_back(n);
    truth.push_back(part);
  };
  auto count = [&](double area) { return std::size_t(area / (spacing * spacing)); };
  // the box [-1, 1]^2 x [-1, 0]: its top without the cylinder's foot, and its four sides
  for(std::size_t k = 0, n = count(4. - CGAL_PI * radius * radius); k < n;)
  {
    const Eigen::Vector3d p(u(rng), u(rng), 0.);
    if(p.head<2>().norm() > radius)
    {
      add(p, Eigen::Vector3d::UnitZ(), 0);
      ++k;
    }
  }
  for(int side = 0; side < 4; ++side)
    for(std::size_t k = 0, n = count(2.); k < n; ++k)
    {
      const double s = u(rng), z = 0.5 * (u(rng) - 1.), sign = side < 2 ? 1. : -1.;
      if(side % 2 == 0)
        add(Eigen::Vector3d(sign, s, z), sign * Eigen::Vector3d::UnitX(), 0);
      else
        add(Eigen::Vector3d(s, sign, z), sign * Eigen::Vector3d::UnitY(), 0);
    }
  // the cylinder of radius 0.4 from z = 0 to 1: its side and its top
  for(std::size_t k = 0, n = count(2. * CGAL_PI * radius); k < n; ++k)
  {
    const double a = CGAL_PI * u(rng), z = 0.5 * (u(rng) + 1.);
    const Eigen::Vector3d normal(std::cos(a), std::sin(a), 0.);
    add(Eigen::Vector3d(radius * normal.x(), radius * normal.y(), z), normal, 1);
  }
  for(std::size_t k = 0, n = count(CGAL_PI * radius * radius); k < n;)
  {
    const Eigen::Vector3d p(radius * u(rng), radius * u(rng), 1.);
    if(p.head<2>().norm() <= radius)
    {
      add(p, Eigen::Vector3d::UnitZ(), 1);
      ++k;
    }
  }
}

// crease_segments(): a cylinder on a box comes out as the box and the
// cylinder (the concave crease at the cylinder's foot cuts, the convex edges
// do not); with inward directions every convex edge becomes a crease; a
// superellipsoid (convex everywhere) is one segment; the result does not
// depend on anything but the input; bad input is refused.
void test_crease_segments()
{
  std::mt19937 rng(7);
  std::vector<Eigen::Vector3d> points, outward;
  std::vector<int> truth;
  box_with_cylinder(points, outward, truth, rng);
  const std::size_t n = points.size();
  const BS::Crease_segments s = BS::crease_segments(points, outward);
  BS_CHECK(s.label.size() == n && s.size.size() >= 2, s.size.size() << " segments");
  std::size_t sum = 0;
  for(std::size_t m : s.size)
    sum += m;
  BS_CHECK(sum == n && std::is_sorted(s.size.rbegin(), s.size.rend()), "sizes do not count the points in decreasing order");
  // the two largest segments are the box and the cylinder, each nearly pure
  std::size_t in[2][2] = {{0, 0}, {0, 0}}; // [segment][truth]
  for(std::size_t i = 0; i < n; ++i)
    if(s.label[i] < 2)
      ++in[s.label[i]][truth[i]];
  const std::size_t box = std::size_t(std::count(truth.begin(), truth.end(), 0)), cylinder = n - box;
  BS_CHECK(in[0][0] >= 0.98 * double(box) && in[0][1] <= 0.02 * double(cylinder),
           "segment 0 holds " << in[0][0] << " of " << box << " box and " << in[0][1] << " of " << cylinder << " cylinder points");
  BS_CHECK(in[1][1] >= 0.98 * double(cylinder) && in[1][0] <= 0.02 * double(box),
           "segment 1 holds " << in[1][1] << " of " << cylinder << " cylinder and " << in[1][0] << " of " << box << " box points");
  std::cout << "  crease segments of a cylinder on a box: " << s.size.size() << " segments, box " << in[0][0] << "/" << box
            << ", cylinder " << in[1][1] << "/" << cylinder << std::endl;
  // the same input gives the same segments
  BS_CHECK(BS::crease_segments(points, outward).label == s.label, "not deterministic");
  // inward directions turn convex into concave: the box's four sides and the
  // cylinder's top part from the rest (the box's top and the cylinder's side,
  // now joined at a convex fold: 6 of the 11.5 units of area of the box)
  std::vector<Eigen::Vector3d> inward(outward);
  for(Eigen::Vector3d& v : inward)
    v = -v;
  const BS::Crease_segments flipped = BS::crease_segments(points, inward);
  BS_CHECK(flipped.size.size() >= 6 && flipped.size[0] < 0.6 * double(box),
           "inward: " << flipped.size.size() << " segments, the largest " << (flipped.size.empty() ? 0 : flipped.size[0]));

  // directions wrong at a third of the points (a model far from them):
  // oriented by each point's own direction the segments break up; propagated
  // over the edges and voted by piece, they are those of the true directions
  std::vector<Eigen::Vector3d> wrong(outward);
  std::bernoulli_distribution third(1. / 3.);
  for(Eigen::Vector3d& v : wrong)
    if(third(rng))
      v = -v;
  BS::Crease_segment_settings propagated;
  propagated.propagate_orientation = true;
  const BS::Crease_segments own = BS::crease_segments(points, wrong);
  const BS::Crease_segments voted = BS::crease_segments(points, wrong, propagated);
  BS_CHECK(own.size[0] < 0.6 * double(box), "wrong directions, own orientation: the largest segment holds "
                                                << own.size[0] << " of " << box << " box points");
  BS_CHECK(voted.label == s.label, "wrong directions, propagated orientation: "
                                     << voted.size.size() << " segments (" << voted.size[0] << ", "
                                     << (voted.size.size() > 1 ? voted.size[1] : 0) << ", ...), with the true directions "
                                     << s.size.size() << " (" << s.size[0] << ", " << s.size[1] << ", ...)");
  BS_CHECK(BS::crease_segments(points, outward, propagated).label == s.label,
           "true directions: the propagated orientation changes the segments");
  std::cout << "  a third of the directions wrong: " << own.size.size() << " segments by own orientation (largest "
            << own.size[0] << "), propagated: the segments of the true directions" << std::endl;

  // a superellipsoid with flat sides and rounded edges (a1, a2, a3 = 1, 0.8,
  // 0.6, e1 = 0.3, e2 = 0.5): convex, one segment. Points: random directions
  // scaled onto the surface F = 1; normals: the gradient of F.
  auto F = [](const Eigen::Vector3d& x) {
    const double e1 = 0.3, e2 = 0.5;
    return std::pow(std::pow(std::abs(x.x()), 2. / e2) + std::pow(std::abs(x.y() / 0.8), 2. / e2), e2 / e1) +
           std::pow(std::abs(x.z() / 0.6), 2. / e1);
  };
  std::vector<Eigen::Vector3d> blob, normals;
  std::normal_distribution<double> gauss(0., 1.);
  for(int k = 0; k < 6000; ++k)
  {
    const Eigen::Vector3d d = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Eigen::Vector3d p = std::pow(F(d), -0.15) * d; // F(r d) = r^(2 / e1) F(d)
    Eigen::Vector3d g;
    for(int a = 0; a < 3; ++a)
    {
      const Eigen::Vector3d h = 1e-6 * Eigen::Vector3d::Unit(a);
      g[a] = F(p + h) - F(p - h);
    }
    blob.push_back(p);
    normals.push_back(g.normalized());
  }
  const BS::Crease_segments one = BS::crease_segments(blob, normals);
  BS_CHECK(one.size[0] >= 0.99 * double(blob.size()),
           "superellipsoid: the largest of " << one.size.size() << " segments holds " << one.size[0] << " of " << blob.size());

  // bad input
  auto refused = [&](const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& o,
                     const BS::Crease_segment_settings& settings, const std::string& expected) {
    BS_CHECK_REFUSED(std::invalid_argument, BS::crease_segments(p, o, settings), expected);
  };
  const BS::Crease_segment_settings defaults;
  refused(points, std::vector<Eigen::Vector3d>(3), defaults, "one per point");
  BS::Crease_segment_settings bad = defaults;
  bad.neighbours = 0;
  refused(points, outward, bad, "neighbours");
  bad = defaults;
  bad.crease_angle = std::nan("");
  refused(points, outward, bad, "crease_angle");
  bad = defaults;
  bad.edge_factor = -1.;
  refused(points, outward, bad, "edge_factor");
  std::vector<Eigen::Vector3d> broken(points);
  broken[5].x() = std::nan("");
  refused(broken, outward, defaults, "point 5");
  std::vector<Eigen::Vector3d> unoriented(outward);
  unoriented[9] = Eigen::Vector3d::Zero();
  refused(points, unoriented, defaults, "direction 9");
  BS_CHECK(BS::crease_segments({}, {}).size.empty(), "no points: no segments");
}

// The noisy scan of a cross of two bars (the union of two box-like
// superquadrics, scan_of_union(), `n` samples of each).
template <class K>
std::vector<typename K::Point_3> cross_of_two_bars_scan(std::size_t n)
{
  typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Model;
  const Model along_x(BS::Superquadric_ellipsoid<K>(1., 0.2, 0.2, 0.3, 0.3));
  const Model along_y(BS::Superquadric_ellipsoid<K>(0.2, 1., 0.2, 0.3, 0.3));
  std::mt19937_64 rng(11);
  return BS::testing::scan_of_union<typename K::Point_3>(along_x, along_y, n, 0.002, rng);
}

// branch_segments(): a cross of two bars (the union of two box-like
// superquadrics, sampled all around) comes out as its centre and its four
// arms, each arm's tip in a segment of its own that branches from the
// centre's and holds nearly all of that arm; a closed blob has no branch
// (one segment); one view of the cross (its upper half) branches alike;
// the result depends on the input only; bad input is refused.
template <class K>
void test_branch_segments()
{
  typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Model;
  std::vector<Eigen::Vector3d> cross, half;
  for(const auto& p : cross_of_two_bars_scan<K>(6000))
  {
    cross.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    if(cross.back().z() > 0.)
      half.push_back(cross.back());
  }
  // the arm of a point: 0 to 3 for +x, +y, -x, -y beyond `tip` from the centre; -1 nearer
  double tip = 0.;
  auto arm = [&](const Eigen::Vector3d& p) {
    if(std::max(std::abs(p.x()), std::abs(p.y())) < tip)
      return -1;
    return std::abs(p.x()) > std::abs(p.y()) ? (p.x() > 0. ? 0 : 2) : (p.y() > 0. ? 1 : 3);
  };
  auto check_arms = [&](const std::vector<Eigen::Vector3d>& points, const std::string& what) {
    const BS::Crease_segments s = BS::branch_segments(points);
    BS_CHECK(s.label.size() == points.size() && s.parent.size() == s.size.size() && s.size.size() >= 5,
             what << ": " << s.size.size() << " segments");
    std::size_t sum = 0;
    for(std::size_t m : s.size)
      sum += m;
    BS_CHECK(sum == points.size() && std::is_sorted(s.size.rbegin(), s.size.rend()), what << ": sizes");
    // for each arm, the segment holding most of its points, and how many it holds
    std::vector<std::vector<std::size_t>> count(4, std::vector<std::size_t>(s.size.size(), 0));
    std::vector<std::size_t> total(4, 0);
    for(std::size_t i = 0; i < points.size(); ++i)
      if(arm(points[i]) >= 0)
      {
        ++count[std::size_t(arm(points[i]))][s.label[i]];
        ++total[std::size_t(arm(points[i]))];
      }
    std::vector<std::size_t> segment_of(4);
    for(std::size_t a = 0; a < 4; ++a)
    {
      segment_of[a] = std::size_t(std::max_element(count[a].begin(), count[a].end()) - count[a].begin());
      BS_CHECK(count[a][segment_of[a]] >= 0.9 * double(total[a]),
               what << ": arm " << a << " has " << count[a][segment_of[a]] << " of its " << total[a]
                    << " points in its segment");
    }
    std::vector<std::size_t> distinct = segment_of;
    std::sort(distinct.begin(), distinct.end());
    BS_CHECK(std::unique(distinct.begin(), distinct.end()) == distinct.end(), what << ": two arms share a segment");
    for(std::size_t a = 0; a < 4; ++a)
    {
      const std::size_t p = s.parent[segment_of[a]];
      BS_CHECK(p != std::size_t(-1) && std::find(segment_of.begin(), segment_of.end(), p) == segment_of.end(),
               what << ": arm " << a << "'s segment does not branch from the centre's");
    }
    std::cout << "  branch segments of " << what << ": " << s.size.size() << " segments; arms in their segments: "
              << count[0][segment_of[0]] << "/" << total[0] << ", " << count[1][segment_of[1]] << "/" << total[1] << ", "
              << count[2][segment_of[2]] << "/" << total[2] << ", " << count[3][segment_of[3]] << "/" << total[3]
              << std::endl;
    return s;
  };
  // the tips: all around, from a centre on one side, the bands around an
  // arm part from the others only beyond the junction's underside (about
  // 0.8 from the centre: its half-width 0.2 across, 0.4 down its side, 0.2
  // back); seen from one side, nearer (the centre is not exactly at the
  // junction's middle)
  tip = 0.9;
  const BS::Crease_segments s = check_arms(cross, "a cross (all around)");
  tip = 0.75;
  check_arms(half, "a cross (its upper half)");
  BS_CHECK(BS::branch_segments(cross).label == s.label, "not deterministic");
  // a closed blob: the bands about its centre never part
  std::vector<Eigen::Vector3d> blob;
  const Model ellipsoid(BS::Superquadric_ellipsoid<K>(1., 0.7, 0.5, 1., 1.));
  for(const auto& q : BS::sample_model_surface(ellipsoid, 4000, 3))
    blob.emplace_back(CGAL::to_double(q.point.x()), CGAL::to_double(q.point.y()), CGAL::to_double(q.point.z()));
  const BS::Crease_segments one = BS::branch_segments(blob);
  BS_CHECK(one.size.size() == 1 && one.parent.size() == 1 && one.parent[0] == std::size_t(-1),
           "a closed ellipsoid: " << one.size.size() << " segments (the largest " << one.size[0] << ")");
  // bad input
  auto refused = [&](const std::vector<Eigen::Vector3d>& p, const BS::Branch_segment_settings& settings,
                     const std::string& expected) {
    BS_CHECK_REFUSED(std::invalid_argument, BS::branch_segments(p, settings), expected);
  };
  const BS::Branch_segment_settings defaults;
  BS::Branch_segment_settings bad = defaults;
  bad.band_width = 0.;
  refused(blob, bad, "band_width");
  bad = defaults;
  bad.minimum_branch_share = std::nan("");
  refused(blob, bad, "minimum_branch_share");
  bad = defaults;
  bad.neighbours = 0;
  refused(blob, bad, "neighbours");
  std::vector<Eigen::Vector3d> broken(blob);
  broken[7].y() = std::nan("");
  refused(broken, defaults, "point 7");
  BS_CHECK(BS::branch_segments({}).size.empty(), "no points: no segments");
  const BS::Crease_segments single = BS::branch_segments({Eigen::Vector3d(1., 2., 3.)});
  BS_CHECK(single.size == std::vector<std::size_t>{1} && single.label == std::vector<std::size_t>{0},
           "one point: one segment");
}

// add_gradual_part(): the part (a placed superquadric, as a fit to a crease
// segment gives) joins at h = 1, so no point of the surface moves; the part
// is where it was given (its own surface, placed by the model's pose and its
// placement in the base, is the given one); its annulus is around its pole
// farther from the base's centre; a region the shape refuses is refused.
template <class K>
void test_add_gradual_part()
{
  typedef BS::Deformable_blended_model<K> Model;
  typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Part;
  typedef BS::Ellipse_blending_region Region;
  const Eigen::Vector3d t(0.3, -1.2, 2.);
  const Eigen::Vector4d q = Eigen::Vector4d(0.9, 0.2, -0.3, 0.1).normalized();
  const Model body(BS::Blended_shape<K>(BS::Superquadric_ellipsoid<K>(1., 0.9, 1.1, 0.8, 1.1)), t, q);
  // the part below the body's south pole, along the body's z axis, given in world coordinates
  const Eigen::Matrix3d R = BS::internal::rotation_matrix(q);
  const Part part(BS::Superquadric_ellipsoid<K>(0.4, 0.42, 0.5, 0.9, 1.), t + R * Eigen::Vector3d(0., 0., -1.2), q);
  BS::Split_proposal proposal;
  proposal.component = 0;
  proposal.chart = 1; // the southern chart
  proposal.region = Region::make_parameters(0., 0.05, 0.35, 0.33, 0., 1., 0.);
  proposal.half_width = 0.07;
  const Model with_part = BS::add_gradual_part(body, proposal, part);
  BS_CHECK(with_part.shape().number_of_components() == 2 && with_part.shape().blend(0).is_gradual(),
           "no gradual part added");
  // no point moves (h = 1), in the region and out of it
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  double moved = 0.;
  std::size_t compared = 0;
  for(int k = 0; k < 400; ++k)
  {
    const BS::Chart_point c(std::size_t(k % 2), k < 200 ? u(rng) : 0.5 * u(rng), k < 200 ? u(rng) : 0.5 * u(rng));
    moved = (std::max)(moved, (eig<K>(with_part.point(c)) - eig<K>(body.point(c))).norm());
    ++compared;
  }
  BS_CHECK(moved <= 1e-12, "adding the part at h = 1 moved a point by " << moved);
  // the part's own surface is the given one
  double apart = 0.;
  for(int k = 0; k < 100; ++k)
  {
    const BS::Chart_point c(std::size_t(k % 2), u(rng), u(rng));
    const Eigen::Vector3d own = eig<K>(with_part.shape().component_point(BS::Shape_point(1, c)));
    apart = (std::max)(apart, (t + R * own - eig<K>(part.point(c))).norm());
  }
  BS_CHECK(apart <= 1e-12, "the part is " << apart << " from where it was given");
  // its region: around its pole farther from the body's centre (-z: chart 1)
  BS_CHECK(with_part.shape().blend(0).added_side().chart(false) == 1,
           "the part's region is in its chart " << with_part.shape().blend(0).added_side().chart(false));
  std::cout << "  add_gradual_part: " << compared << " points moved at most " << moved << ", the part within " << apart
            << " of where it was given" << std::endl;
  // a region out of its chart
  BS::Split_proposal outside = proposal;
  outside.region = Region::make_parameters(5., 0., 0.35, 0.33, 0., 1., 0.);
  BS_CHECK_REFUSED(std::invalid_argument, BS::add_gradual_part(body, outside, part), "add_gradual_part");
  BS::Split_proposal no_base = proposal;
  no_base.component = 5;
  BS_CHECK_REFUSED(std::invalid_argument, BS::add_gradual_part(body, no_base, part), "component 5 does not exist");
}

// lengthened_into_base(): a part fitted to what sticks out (a cylinder on
// the body's north side from z = 1 to 1.5, its points above the crease at
// z = 1) keeps its exposed end and reaches into the body, its centre 0.4
// times its radius below the crease; with its axis the other way round (the
// exposed end is then its -z pole) the same; a part that deep already is
// returned as it is.
template <class K>
void test_lengthened_into_base()
{
  typedef BS::Deformable_blended_model<K> Model;
  typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Part;
  const Model body(BS::Blended_shape<K>(BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1.)));
  std::vector<typename K::Point_3> members;
  for(int k = 0; k < 50; ++k)
    members.emplace_back(0.3 * std::cos(0.1 * k), 0.3 * std::sin(0.1 * k), 1. + 0.01 * k);
  for(const Eigen::Vector4d& q : {Eigen::Vector4d(1., 0., 0., 0.), Eigen::Vector4d(0., 1., 0., 0.)}) // (w, x, y, z)
  {
    const Part part(BS::Superquadric_ellipsoid<K>(0.3, 0.3, 0.25, 0.1, 1.), Eigen::Vector3d(0., 0., 1.25), q);
    const Part longer = BS::lengthened_into_base(body, 0, part, members);
    const double a3 = longer.shape().parameters()[2], centre = longer.translation().z();
    BS_CHECK(std::abs(centre - (1. - 0.4 * 0.3)) < 1e-12 && std::abs(centre + a3 - 1.5) < 1e-12 &&
               longer.translation().template head<2>().norm() < 1e-15,
             "lengthened: centre " << longer.translation().transpose() << ", a3 " << a3 << " (expected z "
                                   << 1. - 0.4 * 0.3 << ", top at 1.5)");
    const Part again = BS::lengthened_into_base(body, 0, longer, members);
    BS_CHECK(again.translation() == longer.translation() && again.shape().parameters() == longer.shape().parameters(),
             "a part deep enough already was changed");
  }
  std::cout << "  lengthened_into_base: the exposed end kept, the centre below the crease, either axis direction"
            << std::endl;
}

// F(x) of the superquadric `m` (1 on its surface, below 1 inside), at a point of the world.
template <class K>
double implicit_function(const BS::Deformable_model<BS::Superquadric_ellipsoid<K>>& m, const Eigen::Vector3d& x)
{
  const Eigen::Vector3d y = m.rotation().transpose() * (x - m.translation());
  const auto q = m.shape().parameters(); // a1, a2, a3, e1, e2
  return std::pow(std::pow(std::abs(y.x() / q[0]), 2. / q[4]) + std::pow(std::abs(y.y() / q[1]), 2. / q[4]), q[4] / q[3]) +
         std::pow(std::abs(y.z() / q[2]), 2. / q[3]);
}

// pole_towards(): a box-like superquadric with equal exponents gets its z
// axis along the axis nearest the direction, and is the same surface; along
// z already, or with exponents that differ, it is returned as it is; a
// square section taken as a diamond becomes the square.
template <class K>
void test_pole_towards()
{
  typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Part;
  const Eigen::Vector4d q = Eigen::Vector4d(0.8, -0.3, 0.4, 0.2).normalized();
  const Eigen::Vector3d t(0.5, -2., 1.);
  const Part box(BS::Superquadric_ellipsoid<K>(1., 0.7, 0.4, 0.2, 0.2), t, q);
  const Eigen::Matrix3d R = box.rotation();
  for(int axis = 0; axis < 2; ++axis)
  {
    const Part turned = BS::pole_towards(box, -R.col(axis) + 0.2 * R.col(2));
    const double along = std::abs(turned.rotation().col(2).dot(R.col(axis)));
    double off = 0.; // the turned one's surface points on the box's surface
    for(int k = 0; k < 200; ++k)
    {
      const BS::Chart_point c(std::size_t(k % 2), 0.9 * std::cos(0.37 * k) * (k % 7) / 7., 0.9 * std::sin(0.37 * k) * (k % 5) / 5.);
      off = (std::max)(off, std::abs(implicit_function<K>(box, eig<K>(turned.point(c))) - 1.));
    }
    BS_CHECK(along > 1. - 1e-12 && off < 1e-9, "pole_towards x" << axis << ": z axis . x" << axis << " = " << along
                                                                 << ", the surface moved (F - 1 up to " << off << ")");
  }
  const Part same = BS::pole_towards(box, R.col(2) + 0.3 * R.col(0));
  BS_CHECK(same.shape().parameters() == box.shape().parameters() && same.quaternion() == box.quaternion(),
           "pole_towards changed a superquadric whose z axis is the nearest already");
  const Part cylinder(BS::Superquadric_ellipsoid<K>(1., 0.7, 0.4, 0.2, 1.), t, q);
  const Part kept = BS::pole_towards(cylinder, R.col(0));
  BS_CHECK(kept.shape().parameters() == cylinder.shape().parameters() && kept.quaternion() == cylinder.quaternion(),
           "pole_towards exchanged the axes of a superquadric with e1 = 0.2, e2 = 1");
  // a square section taken as a diamond (a1 = a2 = sqrt 2, e2 = 2), the
  // direction along a diagonal of the diamond (an axis of the square): the
  // square of half-side 1 (e2 at its bound), its pole along the direction;
  // along the diamond's own z axis, the square about the same axis
  const Part diamond(BS::Superquadric_ellipsoid<K>(std::sqrt(2.), std::sqrt(2.), 0.5, 0.01, 2.), t, q);
  const Eigen::Vector3d diagonal = (R.col(0) + R.col(1)).normalized();
  const Part square = BS::pole_towards(diamond, diagonal);
  auto sq = square.shape().parameters();
  std::sort(sq.data(), sq.data() + 3);
  BS_CHECK(std::abs(sq[0] - 0.5) < 1e-12 && std::abs(sq[1] - 1.) < 1e-12 && std::abs(sq[2] - 1.) < 1e-12 && sq[3] == 0.01 &&
             sq[4] == 0.01 && std::abs(std::abs(square.rotation().col(2).dot(diagonal)) - 1.) < 1e-12,
           "pole_towards on a diamond section: semi-axes and exponents " << square.shape().parameters().transpose());
  const Part upright = BS::pole_towards(diamond, R.col(2));
  const auto up = upright.shape().parameters();
  BS_CHECK(std::abs(up[0] - 1.) < 1e-12 && std::abs(up[1] - 1.) < 1e-12 && up[2] == 0.5 && up[3] == 0.01 && up[4] == 0.01 &&
             std::abs(upright.rotation().col(2).dot(R.col(2)) - 1.) < 1e-12,
           "pole_towards on a diamond section along its z axis: " << up.transpose());
  std::cout << "  pole_towards: the z axis turned to x or y with the same surface; kept when nearest or e1 != e2;"
               " a diamond section turned into the square" << std::endl;
}

// region_inside_part(): a cylinder standing on the north pole of a sphere:
// the region's curve is where the two meet (0.3 from the axis), wherever in
// the chart the proposal's centre was; a part clear of the base gives none.
template <class K>
void test_region_inside_part()
{
  typedef BS::Deformable_blended_model<K> Model;
  typedef BS::Deformable_model<BS::Superquadric_ellipsoid<K>> Part;
  typedef BS::Ellipse_blending_region Region;
  const Model sphere(BS::Blended_shape<K>(BS::Superquadric_ellipsoid<K>(1., 1., 1., 1., 1.)));
  const Part cylinder(BS::Superquadric_ellipsoid<K>(0.3, 0.3, 0.5, 0.2, 1.), Eigen::Vector3d(0., 0., 1.),
                      Eigen::Vector4d(1., 0., 0., 0.));
  BS::Split_proposal proposal;
  proposal.component = 0;
  proposal.chart = 0; // the northern half
  proposal.region = Region::make_parameters(0.25, -0.1, 0.5, 0.2, 0.4, 1., 0.);
  proposal.half_width = 0.04;
  proposal.segment = 3;
  const std::optional<BS::Split_proposal> p = BS::region_inside_part(sphere, proposal, cylinder);
  BS_CHECK(p.has_value(), "no region under a cylinder standing on the sphere");
  if(!p)
    return;
  const auto& g = p->region;
  double lowest = HUGE_VAL, highest = 0.;
  for(int k = 0; k < 16; ++k)
  {
    const double a = 2. * CGAL_PI * k / 16., c = std::cos(g[Region::E_THETA]), s = std::sin(g[Region::E_THETA]);
    const double x = g[Region::E_1] * std::cos(a), y = g[Region::E_2] * std::sin(a);
    const Eigen::Vector3d on = sphere.shape().component(0).shape().point(
      BS::Chart_point(0, g[Region::E_U] + c * x - s * y, g[Region::E_V] + s * x + c * y));
    lowest = (std::min)(lowest, on.template head<2>().norm());
    highest = (std::max)(highest, on.template head<2>().norm());
  }
  BS_CHECK(lowest > 0.27 && highest < 0.33 && p->segment == 3 && p->component == 0 && p->chart == 0,
           "the region's curve is " << lowest << " to " << highest << " from the cylinder's axis (radius 0.3)");
  std::cout << "  region_inside_part: the curve " << lowest << " to " << highest << " from the axis of a cylinder of radius 0.3"
            << std::endl;
  const Part away(BS::Superquadric_ellipsoid<K>(0.3, 0.3, 0.5, 0.2, 1.), Eigen::Vector3d(0., 0., 3.),
                  Eigen::Vector4d(1., 0., 0., 0.));
  BS_CHECK(!BS::region_inside_part(sphere, proposal, away), "a region under a part clear of the base");
  for(const auto& [component, chart] : {std::pair<std::size_t, std::size_t>(1, 0), {0, 2}})
  {
    BS::Split_proposal bad = proposal;
    bad.component = component;
    bad.chart = chart;
    BS_CHECK_REFUSED(std::invalid_argument, BS::region_inside_part(sphere, bad, cylinder),
                     component == 1 ? "component" : "chart 2");
  }
}

// Evolution_settings::evolution_runs on the points of test_crease_evolution(),
// whose one run gave `one`: two runs give two description lengths, keep the
// shorter (the first on a tie), and keeping the first gives the model of one
// run, bit for bit; the second run stopped by the callback as it starts
// leaves the first run's model and length, the result marked stopped.
template <class Point_3, class Result>
void check_evolution_runs(const std::vector<Point_3>& points, const Result& one)
{
  BS_CHECK(one.run_description_lengths.size() == 1 && one.evolution_run == 0,
           "one run: " << one.run_description_lengths.size() << " lengths, run " << one.evolution_run << " kept");
  // (the runs go on concurrently: on two threads here, on one below)
  std::vector<std::string> heard_two, heard_one;
  const auto two = BS::fit_blended_shape(
    points, BS::parameters::number_of_threads(std::size_t(2), BS::parameters::evolution_runs(std::size_t(2)))
              .visitor(Logging_visitor{{}, &heard_two}));
  const std::vector<double>& L = two.run_description_lengths;
  BS_CHECK(L.size() == 2 && two.evolution_run == (L[1] < L[0] ? 1u : 0u) && L[0] == one.run_description_lengths[0],
           "two runs: " << L.size() << " lengths, run " << two.evolution_run << " kept");
  if(L.size() == 2)
  {
    if(two.evolution_run == 0)
      BS_CHECK(BS::testing::same_bits(two.model.parameters(), one.model.parameters()),
               "two runs, the first kept: not the model of one run");
    std::cout << "  two evolution runs: description lengths " << L[0] << ", " << L[1] << " (run " << two.evolution_run
              << " kept, " << two.number_of_parts() << " parts)" << std::endl;
  }
  // At one thread and at two, the same bits, and the visitor hears the
  // same (every iteration's energy, every event), run 0 first. (Not in
  // sanitizer builds: a repeat of the two runs, about a quarter of
  // `test_fitting evolution` there, whose code paths the runs below take.)
  if(!reduced)
  {
    const auto one_thread = BS::fit_blended_shape(
      points, BS::parameters::number_of_threads(std::size_t(1), BS::parameters::evolution_runs(std::size_t(2)))
                .visitor(Logging_visitor{{}, &heard_one}));
    BS_CHECK(BS::testing::same_bits(one_thread.model.parameters(), two.model.parameters()) &&
               one_thread.metrics.iterations == two.metrics.iterations && one_thread.run_description_lengths == L &&
               !heard_one.empty() && heard_two == heard_one,
             "two runs: one thread and two differ (" << heard_one.size() << " and " << heard_two.size()
                                                     << " hooks heard)");
  }
  // Stopped at once, every run stops, at any number of threads: run 0 is
  // kept as far as it went.
  std::size_t calls = 0;
  const std::size_t first_fit = one.first_fit.metrics.iterations;
  const auto all_stopped = BS::fit_blended_shape(
    points, BS::parameters::number_of_threads(std::size_t(2), BS::parameters::evolution_runs(std::size_t(2))).callback(
              std::function<bool(double)>([&](double) { return ++calls <= first_fit; })));
  BS_CHECK(all_stopped.status.aborted && all_stopped.evolution_run == 0 &&
             all_stopped.run_description_lengths.size() == 1 && all_stopped.model.parameters().allFinite() &&
             calls == first_fit + 1,
           "two runs stopped as evolution starts: aborted " << all_stopped.status.aborted << ", run "
                                                            << all_stopped.evolution_run << " kept, " << calls
                                                            << " calls of the callback, " << first_fit + 1
                                                            << " expected");
  // On one thread the runs go in order: stopped as the second run starts,
  // the first run's model and description length.
  // (the callback is called once an iteration: the first fit's and the first run's pass)
  calls = 0;
  const std::size_t first_run = one.first_fit.metrics.iterations + one.status.iterations;
  const auto stopped = BS::fit_blended_shape(
    points, BS::parameters::number_of_threads(std::size_t(1), BS::parameters::evolution_runs(std::size_t(2))).callback(
              std::function<bool(double)>([&](double) { return ++calls <= first_run; })));
  const bool sampled = one.first_fit.metrics.number_of_points < points.size(); // (then a final fit, not reached here)
  BS_CHECK(stopped.status.aborted && stopped.evolution_run == 0 && stopped.run_description_lengths.size() == 1 &&
             stopped.run_description_lengths[0] == L[0] && stopped.number_of_parts() == one.number_of_parts() &&
             stopped.model.parameters().allFinite() &&
             (sampled || BS::testing::same_bits(stopped.model.parameters(), one.model.parameters())),
           "the second run stopped as it starts: aborted " << stopped.status.aborted << ", run "
                                                           << stopped.evolution_run << " kept, "
                                                           << stopped.run_description_lengths.size() << " lengths");
}

// Evolution from crease segments (Split_source::Crease_segments, the
// default) on the cylinder on a box: one split, the cylinder's segment blended in as a
// gradual part (a Part blend), two parts, the same bits on one thread as
// on all; stopped by the
// callback while the part is blended in, the model is the one before, valid.
template <class K>
void test_crease_evolution()
{
  std::mt19937 rng(7);
  std::vector<Eigen::Vector3d> all, outward;
  std::vector<int> truth;
  box_with_cylinder(all, outward, truth, rng);
  std::vector<typename K::Point_3> points;
  for(std::size_t i = 0; i < all.size(); i += reduced ? 6 : 3)
    points.emplace_back(all[i].x(), all[i].y(), all[i].z());
  BS_CHECK(BS::Evolution_settings().split_source == BS::Split_source::Crease_segments,
           "the default split source is not the crease segments");
  // (with a reference mesh: the box, whose Chamfer distance to the result
  // of two parts is reported, and changes nothing else: the evolved model's
  // description length is, to the bit, that of run 0 without it, in
  // check_evolution_runs())
  CGAL::Surface_mesh<typename K::Point_3> box;
  CGAL::make_hexahedron(typename K::Point_3(-1., -1., -1.), typename K::Point_3(1., -1., -1.),
                        typename K::Point_3(1., 1., -1.), typename K::Point_3(-1., 1., -1.),
                        typename K::Point_3(-1., 1., 0.), typename K::Point_3(-1., -1., 0.),
                        typename K::Point_3(1., -1., 0.), typename K::Point_3(1., 1., 0.), box);
  // (each quad cut in two by hand: CGAL's triangulate_faces() would compile
  // a constrained Delaunay triangulation for each kernel, for six quads)
  std::vector<typename boost::graph_traits<decltype(box)>::face_descriptor> quads(faces(box).begin(), faces(box).end());
  for(const auto f : quads)
    CGAL::Euler::split_face(halfedge(f, box), next(next(halfedge(f, box), box), box), box);
  const auto r = BS::fit_blended_shape(points, BS::parameters::reference_mesh(&box));
  BS_CHECK(r.metrics.chamfer_distance && !r.first_fit.metrics.chamfer_distance &&
             *r.metrics.chamfer_distance == BS::symmetric_chamfer_distance(r.model, box),
           "crease evolution: the Chamfer distance to the reference mesh is not the result's");
  std::size_t kept = 0, from_segment = 0;
  double before = 0., after = 0.; // least-squares RMS of evolution, before and after the split kept
  for(const auto& e : r.events)
    if(e.accepted())
    {
      ++kept;
      from_segment += e.proposal.segment == 1 ? 1 : 0;
      before = e.rms_before;
      after = e.rms_after;
    }
  BS_CHECK(r.number_of_parts() == 2 && kept == 1 && from_segment == 1 &&
             r.model.shape().blend(0).kind() == BS::Blend_kind::Part,
           "crease evolution on a cylinder on a box: " << r.number_of_parts() << " parts, " << kept << " splits kept, "
                                                        << from_segment << " from segment 1");
  // the box and the cylinder near the noise (0.2 % of the diagonal): the base
  // refitted to the box's points with its pole towards the cylinder, the
  // cylinder's region where it meets the box, the part held while h falls
  // (on the scan of this shape in reproduce_paper, without any one of the
  // three the RMS was 0.14 to 1.6 % of the diagonal instead of 0.014 %)
  BS_CHECK(r.metrics.rms_over_bbox_diagonal <= 0.005, // (0.45 % measured: see the manual)
           "crease evolution on a cylinder on a box: RMS " << 100. * r.metrics.rms_over_bbox_diagonal
                                                           << " % of the diagonal, the noise 0.2 %");
  std::cout << "  crease evolution on a cylinder on a box (" << points.size() << " points): " << r.number_of_parts()
            << " parts, least-squares RMS " << before << " -> " << after << ", result's "
            << 100. * r.metrics.rms_over_bbox_diagonal << " % of the diagonal" << std::endl;
  // (the same bits on one thread as on two, the segment's own superquadric
  // fit and the staged fits included: check_evolution_runs())
  // stopped while the part is blended in: the first fit and evolution's
  // first fit to rest pass, the gradual part's stages are stopped
  std::size_t calls = 0;
  const std::size_t stop_at = r.first_fit.metrics.iterations + r.events.front().iteration + 5;
  const auto stopped = BS::fit_blended_shape(
    points, CGAL::parameters::callback(std::function<bool(double)>([&](double) { return ++calls < stop_at; })));
  BS_CHECK(stopped.status.aborted && stopped.number_of_parts() == 1 && stopped.model.shape().number_of_blends() == 0,
           "stopped while blending the part in: aborted " << stopped.status.aborted << ", "
                                                          << stopped.number_of_parts() << " parts");
  // the first split's stages: Evolution_settings::first_split_blend_stages
  // fits, each but the last capped at first_split_stage_iterations
  std::vector<std::size_t> stage_iterations;
  BS::fit_blended_shape(points, BS::parameters::first_split_blend_stages(
                                  std::size_t(3), BS::parameters::first_split_stage_iterations(
                                                    std::size_t(2), BS::parameters::maximum_number_of_parts(std::size_t(2))))
                                  .visitor(First_split_fits_visitor{{}, &stage_iterations}));
  BS_CHECK(stage_iterations.size() == 3 && stage_iterations[0] <= 2 && stage_iterations[1] <= 2,
           "the first split in 3 stages capped at 2 iterations: " << stage_iterations.size() << " fits heard");
  check_evolution_runs(points, r);
}

// Split_source::Branch_segments: the fits see the central branch of the
// points first and join one branch at a time, each offered as a part, so
// that limbs not yet explained never pull the body out of shape. One view
// (z > 0) of a cross of two bars, whose arms meet without a crease: the
// fits start on the central branch alone (a proper subset of the points);
// a fit stopped while a branch joins leaves the model, its points and the
// events as they were; run() tries each branch once, keeps a split, and
// ends with every point fitted, each event kept or undone as its
// description lengths say. On this cross the evolved model is farther
// from the points than the superquadric evolution started from (fitted to
// all of them), which then replaces it: a revert, the last event, to one
// part at rest, no farther from the points than the evolved model (with
// the first split's stages of at most 3 iterations, the default until
// 2026-12-06: with the single step of the default since, this cross's
// evolution keeps 3 parts closer to the points than the superquadric, and
// no revert would be tested). Scans of one superquadric, all around and
// from one side, stay one part.
template <class K>
void test_branch_evolution()
{
  std::vector<typename K::Point_3> points;
  for(const auto& p : cross_of_two_bars_scan<K>(2500))
    if(CGAL::to_double(p.z()) > 0.)
      points.push_back(p);
  BS::Evolution_settings settings = splits_from(BS::Split_source::Branch_segments);
  settings.first_split_stage_iterations = 3;
  BS::Part_evolution<K> evolution = evolution_of<K>(points, settings);
  const std::size_t kept = points.size() - evolution.isolated_points().size();
  const std::size_t central = evolution.joined_points().size();
  BS_CHECK(central > 0 && central < kept && evolution.fitter().number_of_points() == central,
           "branch evolution: the fits start on " << evolution.fitter().number_of_points() << " points, the central branch "
                                                  << central << " of " << kept);
  // stopped in the fit of the join
  const std::vector<BS::Split_proposal> proposals = evolution.propose_splits();
  BS_CHECK(proposals.size() == 1 && proposals.front().segment != BS::Split_proposal::none,
           "branch evolution: " << proposals.size() << " proposals, not the next branch's");
  if(proposals.empty())
    return;
  const Eigen::VectorXd before = evolution.model().parameters();
  Counting_visitor heard;
  const bool split = evolution.try_split(proposals.front(), heard, [](double) { return false; });
  BS_CHECK(!split && evolution.joined_points().size() == central && evolution.fitter().number_of_points() == central &&
             evolution.events().empty() && BS::testing::same_bits(evolution.model().parameters(), before),
           "branch evolution: a join stopped changed the model, its " << evolution.joined_points().size()
                                                                      << " points or its events");
  Counting_visitor visitor;
  const BS::Evolution_status status = evolution.run(visitor);
  std::vector<std::size_t> tried;
  std::size_t splits = 0;
  const auto& events = evolution.events();
  for(std::size_t i = 0; i + 1 < events.size(); ++i)
  {
    const BS::Evolution_event& e = events[i];
    tried.push_back(e.proposal.segment);
    splits += e.accepted() ? 1 : 0;
    BS_CHECK((e.kind == BS::Evolution_event_kind::Split || e.kind == BS::Evolution_event_kind::Undo) &&
               e.accepted() == (e.description_length_after < e.description_length_before),
             "branch evolution: an event against its description lengths");
  }
  std::sort(tried.begin(), tried.end());
  BS_CHECK(std::adjacent_find(tried.begin(), tried.end()) == tried.end(), "branch evolution: a branch tried twice");
  const bool reverted = !events.empty() && events.back().kind == BS::Evolution_event_kind::Revert;
  BS_CHECK(reverted && events.back().description_length_after <= events.back().description_length_before &&
             events.back().rms_after <= events.back().rms_before && visitor.undos == events.size() - splits,
           "branch evolution of one view of a cross: no revert to the superquadric of all the points");
  const std::size_t parts = evolution.model().shape().number_of_components();
  const double rms = std::sqrt(evolution.fitter().mean_squared_distance(true));
  BS_CHECK(!status.aborted && status.converged && splits > 0 && parts == 1 && visitor.parts == 1 &&
             evolution.joined_points().size() == kept && evolution.fitter().number_of_points() == kept,
           "branch evolution of one view of a cross: " << splits << " splits kept, " << parts << " parts at the end, "
                                                       << evolution.fitter().number_of_points() << " of the " << kept
                                                       << " points fitted");
  std::cout << "  branch evolution of one view of a cross (" << points.size() << " points, central branch " << central
            << "): " << events.size() << " events, " << splits << " splits kept, evolved RMS "
            << (events.empty() ? 0. : events.back().rms_before) << ", reverted to " << parts << " part, RMS " << rms
            << std::endl;
  for(bool single_view : {false, true})
  {
    std::mt19937_64 one_rng(2);
    const auto truth = BS::testing::random_superellipsoid<K>(one_rng);
    const auto one = BS::testing::synthetic_scan(truth, reduced ? 1500 : 3000, single_view, 0.002, one_rng);
    BS::Part_evolution<K> single = evolution_of<K>(one, settings);
    single.run();
    BS_CHECK(single.model().shape().number_of_components() == 1 &&
               single.joined_points().size() == one.size() - single.isolated_points().size(),
             "branch evolution of one superquadric (" << (single_view ? "single" : "full") << " view): "
                                                      << single.model().shape().number_of_components() << " parts");
  }
}

// fit_blended_shape()'s whole path on a small scan, also in sanitizer builds
// (which leave out the whole runs on scans below and the tools): a body with
// a part, evolved on all its points and on a sample (then fitted on all),
// with two runs on two threads and on one, and stopped by the callback
// (check_evolution_runs()).
template <class K>
void test_small_evolution()
{
  const auto points = BS::testing::body_with_part_scan<K>(600, 2);
  const auto one = BS::fit_blended_shape(points);
  check_evolution_runs(points, one);
  const auto sampled = BS::fit_blended_shape(points, BS::parameters::maximum_evolution_points(std::size_t(300)));
  // (the figures of the final fit of several parts are of the points not
  // isolated; those of one superquadric, of all the points)
  const std::size_t fitted = points.size() - sampled.stray_points.size();
  BS_CHECK(sampled.model.parameters().allFinite() && std::isfinite(sampled.metrics.rms) && !sampled.status.aborted &&
             sampled.metrics.number_of_points == (sampled.number_of_parts() > 1 ? fitted : points.size()),
           "evolution on 300 of 600 points: figures of " << sampled.metrics.number_of_points << " points ("
                                                         << fitted << " not isolated), RMS " << sampled.metrics.rms);
  std::cout << "  small scan: " << one.number_of_parts() << " parts; on a sample of 300, " << sampled.number_of_parts()
            << std::endl;
}

// Part evolution's steps and limits (`evolution`).
template <class K>
void run_part_evolution(const char* kernel)
{
  const int before = blended_shape_test::failures();
  test_shrink_to_fit<K>();
  test_add_gradual_part<K>();
  test_lengthened_into_base<K>();
  test_pole_towards<K>();
  test_region_inside_part<K>();
  test_proposals_hold_data<K>();
  test_no_over_splitting<K>();
  test_remove_unpaid_parts<K>();
  test_evolution_limits<K>();
  test_small_evolution<K>();
  blended_shape_test::report(std::string("part evolution with ") + kernel, before);
}

// Part evolution's whole runs on scans (`evolution_epick`, `evolution_cartesian`: not
// in sanitizer builds, whose checks they do not add to: they are about
// geometry, and slow there). Apart from run_part_evolution(), so that CTest
// runs them side by side: together they were the longest test, alone at the
// end of the Release tests (the whole runs about 85 % of it).
template <class K>
void run_whole_evolution_runs(const char* kernel)
{
  const int before = blended_shape_test::failures();
  test_split_model_fits_to_rest<K>();
  test_fit_blended_shape<K>();
  test_structure_equivariance<K>();
  test_broken_down_robust_fit_not_returned<K>();
  test_crease_evolution<K>();
  // With the second kernel, not the two runs whose own logic is kernel-free
  // (the sample of the points, the branches found on Eigen vectors) and whose
  // fits the runs above already take through that kernel (they were about
  // 60 % of the second kernel's whole runs: perf, 2026-12-07).
  if(std::is_same<K, CGAL::Exact_predicates_inexact_constructions_kernel>::value)
  {
    test_sampled_evolution<K>();
    test_branch_evolution<K>();
  }
  blended_shape_test::report(std::string("whole evolution runs with ") + kernel, before);
}

template <class K>
void run_force_regions(const char* kernel)
{
  std::cout << "kernel " << kernel << std::endl;
  const int before = blended_shape_test::failures();
  test_sphere<K>();
  // the part along -z from the south pole of a round body: the fit's long
  // axis goes through the part, which is inside one chart
  test_protruding_part<K>("part at the pole", Eigen::Vector3d(1., 0.9, 0.8), Eigen::Vector3d(0., 0., -0.8),
                          Eigen::Vector4d(0., 1., 0., 0.), Eigen::Vector3d(0., 0., -1.), true);
  // the part along +x from the equator of a body long in z: the fit keeps
  // its long axis in z, and the part is across the seam of the two charts
  test_protruding_part<K>("part across the seam", Eigen::Vector3d(0.8, 0.7, 1.6), Eigen::Vector3d(0.8, 0., 0.),
                          Eigen::Vector4d(std::sqrt(0.5), 0., std::sqrt(0.5), 0.), Eigen::Vector3d(1., 0., 0.),
                          false);
  test_bad_input<K>();
  blended_shape_test::report(std::string("force regions with ") + kernel, before);
}

// evolution_settings_from_named_parameters(): no parameter gives the
// defaults of Evolution_settings, and each named parameter reaches its member.
void test_evolution_settings_from_named_parameters()
{
  namespace BSP = BS::parameters;
  const BS::Evolution_settings d, none = BS::evolution_settings_from_named_parameters();
  BS_CHECK(none.maximum_number_of_parts == d.maximum_number_of_parts && none.target_accuracy == d.target_accuracy &&
             none.maximum_split_tries == d.maximum_split_tries && none.threshold_factor == d.threshold_factor &&
             none.analysis_resolution == d.analysis_resolution &&
             none.maximum_evolution_points == d.maximum_evolution_points && none.split_source == d.split_source &&
             none.blend_stages == d.blend_stages &&
             none.intermediate_stage_iterations == d.intermediate_stage_iterations &&
             none.first_split_blend_stages == d.first_split_blend_stages &&
             none.first_split_stage_iterations == d.first_split_stage_iterations &&
             none.evolution_runs == d.evolution_runs && d.evolution_runs == 1,
           "evolution settings without named parameters differ from the defaults");
  const BS::Evolution_settings s = BS::evolution_settings_from_named_parameters(
    BSP::maximum_number_of_parts(std::size_t(5), BSP::target_accuracy(0.01, BSP::maximum_split_tries(std::size_t(2),
    BSP::threshold_factor(2.5, BSP::analysis_resolution(12, BSP::maximum_evolution_points(std::size_t(500),
    BSP::split_source(BS::Split_source::Both, BSP::blend_stages(std::size_t(3),
    BSP::intermediate_stage_iterations(std::size_t(7), BSP::first_split_blend_stages(std::size_t(5),
    BSP::first_split_stage_iterations(std::size_t(6), BSP::evolution_runs(std::size_t(3))))))))))))));
  BS_CHECK(s.maximum_number_of_parts == 5 && s.target_accuracy == 0.01 && s.maximum_split_tries == 2 &&
             s.threshold_factor == 2.5 && s.analysis_resolution == 12 && s.maximum_evolution_points == 500 &&
             s.split_source == BS::Split_source::Both && s.blend_stages == 3 && s.intermediate_stage_iterations == 7 &&
             s.first_split_blend_stages == 5 && s.first_split_stage_iterations == 6 && s.evolution_runs == 3,
           "a named parameter did not reach its member of Evolution_settings");
}

// The parts of test_fitting that are evolution's.
inline void run_regions()
{
  blended_shape_test::for_each_kernel([](auto kernel, const char* name) { run_force_regions<decltype(kernel)>(name); });
}

inline void run_segments()
{
  test_evolution_settings_from_named_parameters();
  test_crease_segments(); // (no kernel: points as Eigen vectors)
  test_branch_segments<CGAL::Exact_predicates_inexact_constructions_kernel>(); // (the kernel samples the shapes only)
}

inline void run_evolution()
{
  blended_shape_test::for_each_kernel([](auto kernel, const char* name) { run_part_evolution<decltype(kernel)>(name); });
}

// The whole runs on scans, one kernel each (two tests that CTest runs side
// by side); not in sanitizer builds (see run_whole_evolution_runs()).
inline void add_whole_runs(std::vector<blended_shape_test::Test_part>& parts)
{
  if(reduced)
    return;
  parts.push_back({"evolution_epick", [] {
                     run_whole_evolution_runs<CGAL::Exact_predicates_inexact_constructions_kernel>("Epick");
                   }});
#ifndef BLENDED_SHAPE_ONE_KERNEL
  parts.push_back({"evolution_cartesian", [] {
                     run_whole_evolution_runs<CGAL::Simple_cartesian<double>>("Simple_cartesian<double>");
                   }});
#endif
}

} // namespace evolution_checks

#endif
