// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_EVOLUTION_SPLIT_PROPOSAL_H
#define CGAL_BLENDED_SHAPE_EVOLUTION_SPLIT_PROPOSAL_H

#include <CGAL/Blended_shape/Blending/Ellipse_blending_region.h>
#include <CGAL/Blended_shape/Evolution/Force_regions.h>
#include <CGAL/Blended_shape/Fitting/Deformable_blended_model.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model.h>
#include <CGAL/Blended_shape/Fitting/Superquadric_multistart_search.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Primitives/internal/superquadric_radial_projection.h>
#include <CGAL/Blended_shape/internal/quaternion.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapeEvolution
/// Where to split a model (sec. 4.1, 5.4): the blending region of a split
/// (`Blended_shape::split()`) made from a boundary curve of `Force_regions`.
struct Split_proposal
{
  /// No boundary curve or segment (see `boundary`, `segment`).
  static constexpr std::size_t none = std::size_t(-1);
  /// The boundary curve it comes from (index in Force_regions::boundaries()), or `none`.
  std::size_t boundary = 0;
  /// The segment of crease_segments() it comes from (propose_segment_split()), or `none`.
  std::size_t segment = none;
  std::size_t component = 0; ///< the component to split
  std::size_t chart = 0;     ///< the component's chart that holds the region
  /// The ellipse region (eq. 29): centre, radii and angle in the chart, `w = 1`, `h = 0`.
  Ellipse_blending_region::Parameter_vector region = Ellipse_blending_region::make_parameters(0., 0., 0.5, 0.5, 0.);
  double half_width = 0.;       ///< the strip half-width `r`, in chart units
  std::size_t new_part_region = 0; ///< the force region inside the ellipse: the side that becomes the new part (`none` for a segment's)
};

namespace internal {

// The node of region `part` nearest to the centre of its misfit: the mean
// position of its nodes weighted by `A(v) |F(v)|` (their share of the flux,
// eq. 13), among the nodes with a force (reached by forces, or glued to a
// place that is). Nothing for a region that no force reaches.
template <class GeomTraits>
std::optional<std::size_t> middle_node(const Force_regions<GeomTraits>& regions, std::size_t part)
{
  const auto& nodes = regions.regions()[part].nodes;
  const auto position = [&](std::size_t v) { return internal::to_eigen(regions.domain().node(v).position); };
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double weight = 0.;
  for(std::size_t v : nodes)
  {
    const double w = regions.node_area(v) * std::abs(regions.node_force(v)); // 0 where no force reaches
    mean += w * position(v);
    weight += w;
  }
  if(!(weight > 0.))
    return std::nullopt;
  mean /= weight;
  std::optional<std::size_t> middle;
  for(std::size_t v : nodes)
    if(regions.node_force(v) != 0. &&
       (!middle || (position(v) - mean).squaredNorm() < (position(*middle) - mean).squaredNorm()))
      middle = v;
  return middle;
}

// The second moments, about `centre`, of the midpoints of the edges between
// the regions of boundary `b` (of all their curves: one region meets another
// along several curves where a chart seam or an uncovered place cuts it)
// whose ends the centre's chart covers; nothing if fewer than three.
template <class GeomTraits>
std::optional<Eigen::Matrix2d> curve_moments(const Force_regions<GeomTraits>& regions,
                                             const typename Force_regions<GeomTraits>::Boundary& b,
                                             const Shape_point& centre)
{
  const auto& domain = regions.domain();
  const auto& primitive = domain.shape().component(centre.component).shape();
  auto in_chart = [&](std::size_t v, Eigen::Vector2d& x) {
    const Shape_point& c = domain.node(v).canonical;
    Chart_point q;
    if(c.component != centre.component || !primitive.to_chart(c.u, centre.u.chart, q))
      return false;
    x = Eigen::Vector2d(q.x, q.y);
    return true;
  };
  Eigen::Matrix2d moments = Eigen::Matrix2d::Zero();
  std::size_t count = 0;
  for(const auto& curve : regions.boundaries())
    if(curve.regions == b.regions)
      for(const auto& e : curve.edges)
      {
        Eigen::Vector2d x0, x1;
        if(!in_chart(e[0], x0) || !in_chart(e[1], x1))
          continue;
        const Eigen::Vector2d d = 0.5 * (x0 + x1) - Eigen::Vector2d(centre.u.x, centre.u.y);
        moments += d * d.transpose();
        ++count;
      }
  if(count < 3)
    return std::nullopt;
  return Eigen::Matrix2d(moments / double(count));
}

// Shrinks the ellipse (down to a quarter) and then moves its centre toward
// the chart's centre until the ellipse and its strip (half-width 0.2 e2 <=
// 0.2 e1) lie within 97 % of the disk chart's radius; false if they cannot.
inline bool fit_into_disk(double radius, Eigen::Vector2d& centre, double& e1, double& e2)
{
  const double room = 0.97 * radius;
  const double scale = std::clamp((room - centre.norm()) / (1.2 * e1), 0.25, 1.);
  e1 *= scale;
  e2 *= scale;
  const double distance = room - 1.2 * e1;
  if(!(distance > 0.))
    return false;
  if(centre.norm() > distance)
    centre *= distance / centre.norm();
  return true;
}

// The proposal whose region (eq. 29) covers the chart points `x` of chart
// `chart` of component `component` (a crease segment's, or a part's
// footprint): the ellipse centred at their mean, radii `e_i = 2
// sqrt(lambda_i)` from the eigenvalues of their covariance (for points
// spread evenly over an ellipse of radii `e_1, e_2` the variances along its
// axes are `e_i^2 / 4`), the minor at least a quarter of the major; strip
// half-width `r = 0.2 e_2`; on a disk chart fitted into it (fit_into_disk()).
// Nothing for fewer than 3 points or an ellipse that does not fit.
inline std::optional<Split_proposal> proposal_covering(std::size_t component, std::size_t chart,
                                                       const Chart_domain& chart_domain,
                                                       const std::vector<Eigen::Vector2d>& x)
{
  if(x.size() < 3)
    return std::nullopt;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for(const Eigen::Vector2d& v : x)
    centre += v;
  centre /= double(x.size());
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for(const Eigen::Vector2d& v : x)
    covariance += (v - centre) * (v - centre).transpose();
  covariance /= double(x.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance); // eigenvalues increasing
  double e1 = 2. * std::sqrt((std::max)(eigen.eigenvalues()[1], 0.));
  double e2 = (std::max)(2. * std::sqrt((std::max)(eigen.eigenvalues()[0], 0.)), 0.25 * e1);
  if(!(e2 > 0.))
    return std::nullopt;
  const Eigen::Vector2d major = eigen.eigenvectors().col(1);
  if(chart_domain.kind == Chart_kind::Disk && !fit_into_disk(chart_domain.radius, centre, e1, e2))
    return std::nullopt;
  Split_proposal p;
  p.boundary = Split_proposal::none;
  p.component = component;
  p.chart = chart;
  p.region = Ellipse_blending_region::make_parameters(centre.x(), centre.y(), e1, e2,
                                                      std::atan2(major.y(), major.x()), 1., 0.);
  p.half_width = 0.2 * e2;
  p.new_part_region = Split_proposal::none;
  return p;
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeEvolution

The split along boundary curve `boundary` of `regions` (the best one, of
the largest flux difference, by default), or nothing if no ellipse can be
made of it. The paper leaves the details open; here:

- <b>Side</b>: of the curve's two regions, the one that covers less of
  the data becomes the new part (`new_part_region`): the protrusion or the
  dent, not the body. The area compared is the covered area
  (Force_regions::Region::covered_area, the nodes that forces reach): on a
  single view the regions also grow over the unseen side, whose area says
  nothing about the data.
- <b>Centre and chart</b>: the node of the new part's region, among those
  with a force (`Force_regions::node_force()` not 0), nearest to the
  centre of the region's misfit: the mean
  position of its nodes weighted by their share `A(v) |F(v)|` of the flux
  (eq. 13). The new part starts as a copy of its base, so it moves only as
  far as the data it is made of pull it: centred where the data lie
  farthest from the model, it takes them; centred on the region's middle
  by area, it can fall where no data are (the unseen side of one view, the
  inside of a ring-shaped region) and feel no force at all. The region goes
  in the chart of that node's canonical point.
- <b>Radii and angle</b> (eq. 29): from the second moments, about the centre,
  of the edge midpoints that the chart covers (`to_chart()`) of all the
  curves between the same two regions (a chart seam or an uncovered place
  cuts one border into several curves; the ellipse is fitted to it whole): for
  points spread evenly along an ellipse of radii `e_1, e_2` they are
  `e_1^2 / 2` and `e_2^2 / 2` along its axes, so `e_i = sqrt(2 lambda_i)`.
  They need not be exact: the fit moves and reshapes the region after the split.
- <b>Strip</b>: half-width `r = 0.2 min(e_1, e_2)`.
- <b>In the chart</b>: on a disk chart the ellipse and its strip must lie in
  the chart (the design notes' deviation from A.2.1): the ellipse shrinks
  (down to a quarter of its size) and then, if that is not enough, the
  centre moves toward the chart's centre, until `|centre| + max(e_1, e_2) + r`
  is at most 97 % of the chart's radius.

`Blended_shape::split()` gives the inside of the ellipse to the new component.

\throws std::out_of_range if there is no such boundary.
*/
template <class GeomTraits>
std::optional<Split_proposal> propose_split(const Force_regions<GeomTraits>& regions, std::size_t boundary = 0)
{
  const auto& boundaries = regions.boundaries();
  if(boundary >= boundaries.size())
    throw std::out_of_range("propose_split: no boundary " + std::to_string(boundary) + " (there are " +
                            std::to_string(boundaries.size()) + ")");
  const auto& b = boundaries[boundary];
  const auto& all = regions.regions();
  const std::size_t part =
    all[b.regions[0]].covered_area <= all[b.regions[1]].covered_area ? b.regions[0] : b.regions[1];
  const std::optional<std::size_t> middle = internal::middle_node(regions, part);
  if(!middle)
    return std::nullopt;
  const Shape_point centre_point = regions.domain().node(*middle).canonical;
  Eigen::Vector2d centre(centre_point.u.x, centre_point.u.y);
  const std::optional<Eigen::Matrix2d> moments = internal::curve_moments(regions, b, centre_point);
  if(!moments)
    return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(*moments); // eigenvalues increasing
  double e1 = std::sqrt(2. * (std::max)(eigen.eigenvalues()[1], 0.));
  // A curve that is nearly straight where the chart sees it gives a sliver,
  // which holds no data to pull the new part: at least a quarter as wide as long.
  double e2 = (std::max)(std::sqrt(2. * (std::max)(eigen.eigenvalues()[0], 0.)), 0.25 * e1);
  if(!(e2 > 0.))
    return std::nullopt;
  const Eigen::Vector2d major = eigen.eigenvectors().col(1);
  const Chart_domain chart_domain =
    regions.domain().shape().component(centre_point.component).shape().chart_domain(centre_point.u.chart);
  if(chart_domain.kind == Chart_kind::Disk && !internal::fit_into_disk(chart_domain.radius, centre, e1, e2))
    return std::nullopt;

  Split_proposal p;
  p.boundary = boundary;
  p.component = centre_point.component;
  p.chart = centre_point.u.chart;
  p.region = Ellipse_blending_region::make_parameters(centre.x(), centre.y(), e1, e2,
                                                      std::atan2(major.y(), major.x()), 1., 0.);
  p.half_width = 0.2 * e2;
  p.new_part_region = part;
  return p;
}

/*!
\ingroup PkgBlendedShapeEvolution

The split that gives the points `members` of a segment of the data
(crease_segments(): a part between concave creases) to a new part, or
nothing. `foot_points[i]` is the closest point on `model` of point `i`
(Deformable_model_fitter::forces()), for all points, not only the members.

- <b>Component</b>: the one that holds most of the members' closest
  points. Nothing if the members are 60 % or more of the points of that
  component: it is that part already (split off before).
- <b>Chart</b>: of that component's charts that show 90 % or more of the
  most any chart shows (to_chart()), the one where their mean lies nearest
  the chart's centre: the region has room to move there.
- <b>Region</b> (eq. 29): the ellipse of the members' closest points in that
  chart (those the chart covers, `to_chart()`): centred at their mean, radii
  `e_i = 2 sqrt(lambda_i)` from the eigenvalues of their covariance (for
  points spread evenly over an ellipse of radii `e_1, e_2` the variances
  along its axes are `e_i^2 / 4`), the minor at least a quarter of the major;
  strip half-width `r = 0.2 e_2`; on a disk chart fitted into it as
  propose_split() does.

Part_evolution blends a superquadric fitted to the members into this
region gradually (Evolution_settings::split_source).
*/
template <class GeomTraits>
std::optional<Split_proposal> propose_segment_split(const Deformable_blended_model<GeomTraits>& model,
                                                    const std::vector<Chart_point>& foot_points,
                                                    const std::vector<std::size_t>& members)
{
  const Blended_shape<GeomTraits>& shape = model.shape();
  std::vector<std::size_t> on_component(shape.number_of_components(), 0), members_on(on_component);
  for(const Chart_point& u : foot_points)
    ++on_component[model.chart_component(u.chart)];
  for(std::size_t i : members)
    ++members_on[model.chart_component(foot_points.at(i).chart)];
  const std::size_t component =
    std::size_t(std::max_element(members_on.begin(), members_on.end()) - members_on.begin());
  if(members_on[component] == 0 || 10 * members_on[component] >= 6 * on_component[component])
    return std::nullopt;
  const auto& primitive = shape.component(component).shape();
  std::vector<std::vector<Eigen::Vector2d>> shown(primitive.number_of_charts());
  for(std::size_t i : members)
  {
    const Shape_point p = model.shape_point(foot_points[i]);
    if(p.component != component)
      continue;
    for(std::size_t g = 0; g < shown.size(); ++g)
    {
      Chart_point q;
      if(primitive.to_chart(p.u, g, q))
        shown[g].emplace_back(q.x, q.y);
    }
  }
  std::size_t most = 0;
  for(const auto& x : shown)
    most = (std::max)(most, x.size());
  if(most < 3)
    return std::nullopt;
  std::size_t chart = 0;
  double best = HUGE_VAL;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for(std::size_t g = 0; g < shown.size(); ++g)
  {
    if(10 * shown[g].size() < 9 * most)
      continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for(const Eigen::Vector2d& v : shown[g])
      mean += v;
    mean /= double(shown[g].size());
    const double off = mean.norm() / primitive.chart_domain(g).radius;
    if(off < best)
    {
      best = off;
      chart = g;
      centre = mean;
    }
  }
  return internal::proposal_covering(component, chart, primitive.chart_domain(chart), shown[chart]);
}

/// \ingroup PkgBlendedShapeEvolution
/// `model` split as `proposal` says (Blended_shape::split(), `h = 0`): the
/// same surface, with one more component and one more blend.
/// \throws std::invalid_argument if the split is refused (the region leaves
///         the chart or meets another blend's region); the message says why.
template <class GeomTraits>
Deformable_blended_model<GeomTraits> apply_split(const Deformable_blended_model<GeomTraits>& model,
                                                 const Split_proposal& proposal)
{
  Blended_shape<GeomTraits> shape = model.shape();
  try
  {
    shape.split(proposal.component, proposal.chart, proposal.region, proposal.half_width);
  }
  catch(const std::invalid_argument& e)
  {
    throw std::invalid_argument(std::string("apply_split: the proposed split is refused: ") + e.what());
  }
  return Deformable_blended_model<GeomTraits>(shape, model.translation(), model.quaternion());
}

namespace internal {

// The frame of component `base` of `model` in the model's frame: rotation and translation.
template <class GeomTraits>
std::pair<Eigen::Matrix3d, Eigen::Vector3d> component_frame(const Deformable_blended_model<GeomTraits>& model,
                                                            std::size_t base)
{
  if(base >= model.shape().number_of_components())
    throw std::invalid_argument("component " + std::to_string(base) + " does not exist (the model has " +
                                std::to_string(model.shape().number_of_components()) + " components)");
  const Eigen::Matrix3d R_model = rotation_matrix(model.quaternion());
  return {R_model * model.shape().root_rotation(base),
          model.translation() + R_model * model.shape().root_translation(base)};
}

// The pole of `part` (chart 0: its +z end, chart 1: its -z end) farther from
// the centre of component `base`: the end that sticks out.
template <class GeomTraits>
std::size_t exposed_pole(const Deformable_blended_model<GeomTraits>& model, std::size_t base,
                         const Deformable_model<Superquadric_ellipsoid<GeomTraits>>& part)
{
  const Eigen::Vector3d centre = component_frame(model, base).second;
  const Eigen::Vector3d z = part.shape().parameters()[2] * rotation_matrix(part.quaternion()).col(2);
  return (part.translation() + z - centre).norm() >= (part.translation() - z - centre).norm() ? 0 : 1;
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeEvolution
`part` (a superquadric fitted to the points `members` of a crease segment,
placed in the model's frame) lengthened into component `base` of `model`:
its exposed end (the pole farther from the base's centre) stays, its
other end moves along its axis so that its centre lies below the crease by
0.4 times its mean radius `(a1 + a2) / 2`. The crease is the members'
lowest level along the axis, from the exposed end. A fit to one view of a
part sees only what sticks out and may end at the crease; the gradual
blend joins the part along a curve near its equator (add_gradual_part()),
which must then lie in the base, not halfway up the part. A part whose
centre is already that deep is returned as it is.
\throws std::invalid_argument if `base` is not a component of `model`.
*/
template <class GeomTraits>
Deformable_model<Superquadric_ellipsoid<GeomTraits>>
lengthened_into_base(const Deformable_blended_model<GeomTraits>& model, std::size_t base,
                     const Deformable_model<Superquadric_ellipsoid<GeomTraits>>& part,
                     const std::vector<typename GeomTraits::Point_3>& members)
{
  if(members.empty())
    return part;
  const Eigen::Matrix3d R = internal::rotation_matrix(part.quaternion());
  const Eigen::Vector3d axis = internal::exposed_pole(model, base, part) == 0 ? R.col(2) : Eigen::Vector3d(-R.col(2));
  Eigen::VectorXd q = part.shape().parameters(); // a1, a2, a3, e1, e2
  double crease = HUGE_VAL; // along the axis, from the centre
  for(const auto& p : members)
    crease = (std::min)(crease, (Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())) -
                                 part.translation()).dot(axis));
  const double depth = crease - 0.4 * 0.5 * (q[0] + q[1]); // where the centre goes, along the axis
  if(!(depth < 0.))
    return part; // deep enough already
  q[2] -= depth; // the exposed end stays
  Superquadric_ellipsoid<GeomTraits> shape = part.shape();
  shape.set_parameters(q);
  return Deformable_model<Superquadric_ellipsoid<GeomTraits>>(shape, part.translation() + depth * axis,
                                                              part.quaternion());
}

/// \ingroup PkgBlendedShapeEvolution
/// The largest difference of the exponents `|e1 - e2|` at which
/// pole_towards() exchanges a superquadric's axes: at 0 the exchange is
/// the same surface, at 0.1 close to it.
constexpr double pole_exchange_tolerance = 0.1;

/*!
\ingroup PkgBlendedShapeEvolution
`base` (a superquadric) with its z axis, the axis through the poles of its
two charts, along whichever of its three axes is closest in direction to
`direction`, if its exponents differ by at most pole_exchange_tolerance
(similar_superquadric(): the z axis exchanged with x or y, and `e1` with
`e2`; for equal exponents the same surface, otherwise `base` unchanged).
A square cross-section that the fit took as a diamond (`e2` within
pole_exchange_tolerance of 2, `a1` and `a2` within 10 %) is first turned
into the square (similar_superquadric() with `swap` 2, `e2` replaced by
`2 - e2`, at least its lower bound: for `e2 = 2` and `a1 = a2` the same
surface, up to the rounding of the square's corners at the lower bound),
whichever axis is then the pole: a box has one form (on the box/cylinder
scan with noise of 0.2 % of the diagonal the fit of the box's points is
the diamond, its z axis towards the cylinder, and the split rested at
3.1 % of the diagonal in that form, at the noise in the square's).
A part blended onto the base where its pole is has its region at the
middle of a chart, where the chart is least distorted: a box whose axes a
fit ordered otherwise has that face across the margins of both charts
(on the box/cylinder scan, the cylinder's blend then rested at 0.14 % of
the diagonal against 0.014 %).
*/
template <class GeomTraits>
Deformable_model<Superquadric_ellipsoid<GeomTraits>>
pole_towards(const Deformable_model<Superquadric_ellipsoid<GeomTraits>>& base, const Eigen::Vector3d& direction)
{
  typedef Superquadric_ellipsoid<GeomTraits> Shape;
  Deformable_model<Shape> m = base;
  auto q = base.shape().parameters();
  if(std::abs(q[4] - 2.) <= pole_exchange_tolerance && std::abs(q[0] - q[1]) <= 0.1 * (std::max)(q[0], q[1]))
  {
    // a square section seen as a diamond (e2 = 2, a1 = a2, turned by 45
    // degrees): the square (similar_superquadric(), the exponent 2 - e2)
    m = similar_superquadric(base, 2);
    q = m.shape().parameters();
    q[4] = (std::max)(2. - base.shape().parameters()[4], Shape::parameter_lower_bound(Shape::E2));
    Shape square = m.shape();
    square.set_parameters(q);
    m = Deformable_model<Shape>(square, m.translation(), m.quaternion());
  }
  if(!(std::abs(q[3] - q[4]) <= pole_exchange_tolerance))
    return m;
  const Eigen::Matrix3d R = m.rotation();
  int closest = 2;
  for(int k = 0; k < 2; ++k)
    if(std::abs(R.col(k).dot(direction)) > std::abs(R.col(closest).dot(direction)))
      closest = k;
  return closest == 2 ? m : similar_superquadric(m, closest);
}

/// \ingroup PkgBlendedShapeEvolution
/// The grid of region_inside_part(): `2 n + 1` chart points across the disk's diameter.
constexpr int footprint_grid_half_size = 64;

/*!
\ingroup PkgBlendedShapeEvolution
`proposal` (propose_segment_split() on `model`) with its region replaced by
the footprint of `part` on its chart: the ellipse (eq. 29, radii from the
moments as propose_segment_split() takes them) of the points of a grid of
that chart (footprint_grid_half_size) whose surface points lie inside
`part` (a superquadric placed in the model's frame: the fit to the crease
segment, lengthened_into_base()), the connected piece of them nearest the
proposal's centre: the curve along which base and part meet. The region
of the segment's closest points is not, on one view of a part: its hidden
side has no points (on the box/cylinder scan, the cylinder's region was
off its centre by 40 % of its radius). Nothing if no grid point of the
chart lies inside the part, or the ellipse does not fit the chart.
\throws std::invalid_argument if the proposal's component or chart is not one of `model`.
*/
template <class GeomTraits>
std::optional<Split_proposal> region_inside_part(const Deformable_blended_model<GeomTraits>& model,
                                                 const Split_proposal& proposal,
                                                 const Deformable_model<Superquadric_ellipsoid<GeomTraits>>& part)
{
  const auto [R_base, t_base] = internal::component_frame(model, proposal.component); // (checks the component)
  const Component_shape& primitive = model.shape().component(proposal.component).shape();
  if(proposal.chart >= primitive.number_of_charts())
    throw std::invalid_argument("region_inside_part: chart " + std::to_string(proposal.chart) + " of component " +
                                std::to_string(proposal.component) + " does not exist (it has " +
                                std::to_string(primitive.number_of_charts()) +
                                "); pass a proposal of this model (propose_segment_split())");
  const Chart_domain domain = primitive.chart_domain(proposal.chart);
  if(domain.kind != Chart_kind::Disk)
    return std::nullopt; // (crease segments' proposals are on superquadrics' disk charts)
  const Eigen::Matrix3d R_part = part.rotation();
  const auto a = part.shape().parameters(); // a1, a2, a3, e1, e2
  auto inside_part = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector3d y = R_part.transpose() * (x - part.translation());
    const Eigen::Vector3d v(y.x() / a[0], y.y() / a[1], y.z() / a[2]);
    if(v == Eigen::Vector3d::Zero())
      return true;
    // v is inside where the surface point in its direction is farther
    const internal::Superquadric_radial_projection r(v, a[3], a[4]);
    return r.r * r.scale > 1.;
  };
  const int n = footprint_grid_half_size, side = 2 * n + 1;
  const double step = domain.radius / double(n);
  auto chart_point = [&](int k) { return Eigen::Vector2d(step * (k / side - n), step * (k % side - n)); };
  std::vector<char> inside(std::size_t(side * side), 0);
  const Eigen::Vector2d centre(proposal.region[Ellipse_blending_region::E_U], proposal.region[Ellipse_blending_region::E_V]);
  int nearest = -1;
  for(int k = 0; k < side * side; ++k)
  {
    const Eigen::Vector2d u = chart_point(k);
    if(u.norm() > domain.radius ||
       !inside_part(R_base * primitive.point(Chart_point(proposal.chart, u.x(), u.y())) + t_base))
      continue;
    inside[std::size_t(k)] = 1;
    if(nearest < 0 || (u - centre).norm() < (chart_point(nearest) - centre).norm())
      nearest = k;
  }
  if(nearest < 0)
    return std::nullopt;
  // the connected piece (4-neighbours) of the grid points inside, from the nearest
  std::vector<Eigen::Vector2d> footprint;
  std::vector<int> stack{nearest};
  inside[std::size_t(nearest)] = 2;
  while(!stack.empty())
  {
    const int k = stack.back();
    stack.pop_back();
    footprint.push_back(chart_point(k));
    const int i = k / side, j = k % side;
    for(const auto& [di, dj] : {std::pair<int, int>(1, 0), {-1, 0}, {0, 1}, {0, -1}})
    {
      const int ii = i + di, jj = j + dj, kk = ii * side + jj;
      if(ii >= 0 && jj >= 0 && ii < side && jj < side && inside[std::size_t(kk)] == 1)
      {
        inside[std::size_t(kk)] = 2;
        stack.push_back(kk);
      }
    }
  }
  std::optional<Split_proposal> p = internal::proposal_covering(proposal.component, proposal.chart, domain, footprint);
  if(p)
    p->segment = proposal.segment;
  return p;
}

/*!
\ingroup PkgBlendedShapeEvolution
`model` with the superquadric `part` (placed, in the model's frame: a fit to
a crease segment, lengthened_into_base()) added as a gradual part
(Blended_shape::add_part(), sec. 4.1) in the region of `proposal`
(propose_segment_split()): at `h = 1`, so no point of the surface moves;
lowering `h` expresses the part. The part's placement is taken into the
frame of its base (`proposal.component`); on the part, the annulus region
(radius 0.9, half-width 0.1 in chart units: near its equator) is around
its exposed pole, the one farther from the base's centre.
\throws std::invalid_argument if `proposal.component` is not a component of
        `model` or the shape refuses the region; the message says why.
*/
template <class GeomTraits>
Deformable_blended_model<GeomTraits>
add_gradual_part(const Deformable_blended_model<GeomTraits>& model, const Split_proposal& proposal,
                 const Deformable_model<Superquadric_ellipsoid<GeomTraits>>& part)
{
  const std::size_t base = proposal.component;
  Blended_shape<GeomTraits> shape = model.shape();
  try
  {
    const auto [R_base, t_base] = internal::component_frame(model, base);
    const Eigen::Matrix3d R = R_base.transpose() * internal::rotation_matrix(part.quaternion());
    const Eigen::Vector3d t = R_base.transpose() * (part.translation() - t_base);
    shape.add_part(base, proposal.chart, proposal.region, proposal.half_width, part.shape(), "superquadric_ellipsoid",
                   t, internal::quaternion_from_matrix(R), internal::exposed_pole(model, base, part),
                   Ellipse_blending_region::make_parameters(0., 0., 0.9, 0.9, 0., 1., 0.), 0.1);
  }
  catch(const std::invalid_argument& e)
  {
    throw std::invalid_argument(std::string("add_gradual_part: the part is refused: ") + e.what());
  }
  return Deformable_blended_model<GeomTraits>(shape, model.translation(), model.quaternion());
}

/*!
\ingroup PkgBlendedShapeEvolution
Where the points of `before` that a split moved to its new component are
in `after`, for Deformable_model_fitter::start_from_foot_points_of(): one
entry per chart of `before`, the chart of `after` that shows, at the same
chart coordinates, what chart `g` showed; `std::size_t(-1)` where nothing
moved. `after` is `before` with `component` split (apply_split()): its new
component, the last, is a copy of `component` placed where it is, which
keeps the inside of the region, so the same local chart of the copy has the
same point at the same coordinates.
\throws std::invalid_argument if `after` is not `before` with `component` split:
        no such component, or not one more component with as many charts.
*/
template <class GeomTraits>
std::vector<std::size_t> charts_moved_by_split(const Deformable_blended_model<GeomTraits>& before,
                                               const Deformable_blended_model<GeomTraits>& after,
                                               std::size_t component)
{
  const std::size_t copy = before.shape().number_of_components();
  if(component >= copy || after.shape().number_of_components() != copy + 1 ||
     after.number_of_charts() != before.number_of_charts() + after.shape().component(copy).shape().number_of_charts())
    throw std::invalid_argument("charts_moved_by_split: the second model is not the first with component " +
                                std::to_string(component) + " split; pass the model apply_split() returned");
  std::vector<std::size_t> moved(before.number_of_charts(), std::size_t(-1));
  for(std::size_t g = 0; g < moved.size(); ++g)
    if(before.chart_component(g) == component)
      moved[g] = after.chart_point(Shape_point(copy, Chart_point(before.local_chart(g), 0., 0.))).chart;
  return moved;
}

/*!
\ingroup PkgBlendedShapeEvolution
`proposal`, if `shape` accepts its split (Blended_shape::split()); otherwise
the same ellipse shrunk about its centre (radii and strip half-width times
0.7, up to four times: down to a quarter of its size) until the shape
accepts it; nothing if it never does (e.g. a centre where another blend
cuts the surface away). A proposal's region is fitted to the force
regions' border, which does not know where earlier splits put their regions: on a model
of several parts it often meets one of them, and the split is refused
although a smaller region about the same centre (where the misfit is) is not.
\throws std::invalid_argument if the proposal is not one of `shape`: no
        such component or chart, radii or strip half-width not positive and
        finite, or a centre or angle not finite (shrinking cannot mend these).
*/
template <class GeomTraits>
std::optional<Split_proposal> shrink_to_fit(const Blended_shape<GeomTraits>& shape, Split_proposal proposal)
{
  const auto refuse = [](const std::string& why) {
    throw std::invalid_argument("shrink_to_fit: " + why + "; pass a proposal of this shape (propose_split())");
  };
  if(proposal.component >= shape.number_of_components())
    refuse("no component " + std::to_string(proposal.component));
  if(proposal.chart >= shape.component(proposal.component).shape().number_of_charts())
    refuse("component " + std::to_string(proposal.component) + " has no chart " + std::to_string(proposal.chart));
  const auto& q = proposal.region;
  if(!q.allFinite() || !(q[Ellipse_blending_region::E_1] > 0.) || !(q[Ellipse_blending_region::E_2] > 0.) ||
     !std::isfinite(proposal.half_width) || !(proposal.half_width > 0.))
    refuse("the region's radii and strip half-width must be positive and finite, its centre and angle finite");
  for(int k = 0; k <= 4; ++k)
  {
    try
    {
      Blended_shape<GeomTraits> split = shape;
      split.split(proposal.component, proposal.chart, proposal.region, proposal.half_width);
      return proposal;
    }
    catch(const std::invalid_argument&)
    {
      proposal.region[Ellipse_blending_region::E_1] *= 0.7;
      proposal.region[Ellipse_blending_region::E_2] *= 0.7;
      proposal.half_width *= 0.7;
    }
  }
  return std::nullopt;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_EVOLUTION_SPLIT_PROPOSAL_H
