// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_FIT_METRICS_H
#define CGAL_BLENDED_SHAPE_FITTING_FIT_METRICS_H

#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>
#include <CGAL/Blended_shape/Fitting/initialize_from_moments.h>
#include <CGAL/Blended_shape/IO/Input_error.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeMetrics
The figures reported for a fit (DESIGN notes sec. 5; Figure 18 of the paper).
*/
struct Fit_metrics
{
  std::size_t number_of_points = 0;      ///< N, the number of data points
  std::size_t number_of_parameters = 0;  ///< dimension of q
  std::size_t iterations = 0;            ///< iterations of the fit, all phases and starts
  /// Of `iterations`, those whose step used all points; the others used a
  /// subset (the subset phase, the short fits that compare starts), and
  /// cost in proportion to its size.
  std::size_t iterations_on_all_points = 0;
  /// Eq. 14, read as `RMS_j = sqrt( (1/N) sum_i (dhat_j . (p_i - x(u_i)))^2 ) / |d_j|`
  /// with `d_j` the j-th diameter of the initial best-fit ellipsoid (twice its
  /// j-th semi-axis), largest first, and `dhat_j` its direction;
  /// fractions (0.012 = 1.2 %).
  std::array<double, 3> relative_rms = {{0., 0., 0.}};
  double rms = 0.;                       ///< `sqrt( (1/N) sum_i |p_i - x(u_i)|^2 )`
  double rms_over_bbox_diagonal = 0.;    ///< rms / diagonal of the points' bounding box
  /// The points judged stray by the robust loss of the fit at its end
  /// (Robust_loss::is_stray(): with the default `Robust_weighting::Mixture`,
  /// those more likely strays than inliers; with `None`, none). The figures
  /// above (relative_rms, rms, rms_over_bbox_diagonal, and `N` in them) are
  /// over the other points, and the diagonal is theirs; number_of_points
  /// counts all.
  std::size_t number_of_stray_points = 0;
  /// Whether the points lie in a plane or on a line (Ellipsoid_fit::degeneracy
  /// of the initial ellipsoid the relative RMS is taken in): the fit is then
  /// a flat superquadric or a needle, exact to rounding, not a surface the
  /// points describe.
  Point_cloud_degeneracy degeneracy = Point_cloud_degeneracy::None;
  double seconds = 0.;                   ///< wall time of the fit
  std::optional<double> chamfer_distance; ///< to a reference mesh, when one was given
  bool converged = false;  ///< the fit reached steady state on all points
  bool aborted = false;    ///< the callback stopped the fit
};

/// \ingroup PkgBlendedShapeMetrics
/// Relative RMS per principal direction of `initial` (eq. 14 as read above)
/// of the residuals `p_i - x(u_i)`.
template <class GeomTraits>
std::array<double, 3> relative_rms(const std::vector<Eigen::Vector3d>& residuals,
                                   const Ellipsoid_fit<GeomTraits>& initial)
{
  std::array<double, 3> rms = {{0., 0., 0.}};
  if(residuals.empty())
    return rms;
  const Eigen::Matrix3d R = initial.rotation_matrix();
  for(const Eigen::Vector3d& r : residuals)
    for(int j = 0; j < 3; ++j)
      rms[std::size_t(j)] += CGAL::square(R.col(j).dot(r));
  for(int j = 0; j < 3; ++j)
    rms[std::size_t(j)] = std::sqrt(rms[std::size_t(j)] / double(residuals.size())) /
                          (2. * initial.axes[std::size_t(j)]);
  return rms;
}

namespace internal {

// Points spread uniformly by area over triangles given as a range of corner
// triples; deterministic for a seed.
template <class Point_3>
std::vector<Point_3> sample_triangles(const std::vector<std::array<Point_3, 3>>& triangles,
                                      std::size_t count, unsigned int seed)
{
  std::vector<double> cumulative;
  double total = 0.;
  for(const auto& t : triangles)
  {
    total += std::sqrt(CGAL::to_double(CGAL::squared_area(t[0], t[1], t[2])));
    cumulative.push_back(total);
  }
  std::vector<Point_3> samples;
  if(!(total > 0.))
    return samples;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0., 1.);
  for(std::size_t i = 0; i < count; ++i)
  {
    const std::size_t k = std::size_t(std::lower_bound(cumulative.begin(), cumulative.end(), unit(rng) * total) -
                                      cumulative.begin());
    const auto& t = triangles[(std::min)(k, triangles.size() - 1)];
    double a = unit(rng), b = unit(rng);
    if(a + b > 1.) { a = 1. - a; b = 1. - b; }
    samples.push_back(t[0] + a * (t[1] - t[0]) + b * (t[2] - t[0]));
  }
  return samples;
}

template <class Mesh>
std::vector<std::array<typename Mesh::Point, 3>> mesh_triangles(const Mesh& mesh)
{
  std::vector<std::array<typename Mesh::Point, 3>> t;
  for(auto f : faces(mesh))
  {
    const auto h = halfedge(f, mesh);
    t.push_back({{mesh.point(source(h, mesh)), mesh.point(target(h, mesh)), mesh.point(target(next(h, mesh), mesh))}});
  }
  return t;
}

// The mean distance of `samples` to the triangles of `meshes`. A measurement,
// not a decision: the search tree is built in plain double arithmetic
// (Simple_cartesian<double>), whatever the meshes' kernel. With a filtered
// kernel, a query far from every triangle (a reference mesh placed far from
// the points) finds its candidate distances equal within the filter's bounds
// and falls back to exact arithmetic at every node (a run stopped after
// 60 s against 4 s).
template <class Mesh>
double mean_distance_to(const std::vector<typename Mesh::Point>& samples, const std::vector<const Mesh*>& meshes)
{
  typedef CGAL::Simple_cartesian<double> DK;
  typedef std::vector<DK::Triangle_3>::const_iterator Iterator;
  typedef CGAL::AABB_triangle_primitive<DK, Iterator> Primitive;
  const auto to_dk = [](const typename Mesh::Point& p) {
    return DK::Point_3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  };
  std::vector<DK::Triangle_3> triangles;
  for(const Mesh* m : meshes)
    for(const auto& t : mesh_triangles(*m))
      triangles.emplace_back(to_dk(t[0]), to_dk(t[1]), to_dk(t[2]));
  CGAL::AABB_tree<CGAL::AABB_traits<DK, Primitive>> tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  double sum = 0.;
  for(const auto& p : samples)
    sum += std::sqrt(tree.squared_distance(to_dk(p)));
  return samples.empty() ? 0. : sum / double(samples.size());
}

// Refuses a reference mesh a Chamfer distance cannot be measured to: one
// without faces, or with faces that are not triangles.
template <class Mesh>
void check_reference_mesh(const Mesh& reference, const std::string& who)
{
  if(num_faces(reference) == 0)
    throw std::invalid_argument(who + ": the reference mesh has no faces; give a triangle mesh of the scanned object");
  if(!CGAL::is_triangle_mesh(reference))
    throw std::invalid_argument(who + ": the reference mesh has faces that are not triangles; triangulate it first "
                                      "(CGAL::Polygon_mesh_processing::triangulate_faces())");
  for(auto v : vertices(reference))
  {
    const auto& p = reference.point(v);
    if(!internal::has_coordinates_in_range(p))
    {
      std::ostringstream s;
      s << who << ": reference mesh vertex " << std::size_t(v) << " (" << p << ") has a coordinate that is "
        << internal::out_of_range_coordinate_words()
        << "; give the reference in the points' unit and place, with finite coordinates";
      throw std::invalid_argument(s.str());
    }
  }
}

// The symmetric Chamfer distance from the model's samples and the model's
// meshes: the mean of their mean distance to the reference and the mean
// distance of `count` points on the reference (drawn with `seed + 1`) to the model.
template <class Mesh>
double symmetric_chamfer_distance(const std::vector<typename Mesh::Point>& model_samples,
                                  const std::vector<const Mesh*>& model_meshes, const Mesh& reference,
                                  std::size_t count, unsigned int seed)
{
  check_reference_mesh(reference, "symmetric_chamfer_distance");
  const auto from_reference = sample_triangles(mesh_triangles(reference), count, seed + 1);
  return 0.5 * (mean_distance_to(model_samples, std::vector<const Mesh*>{&reference}) +
                mean_distance_to(from_reference, model_meshes));
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeMetrics
Symmetric Chamfer distance between a model (its chart meshes, as positioned)
and a reference triangle mesh: the mean of the two mean closest-point
distances, each over `samples` points spread uniformly by area on one surface
(deterministic for `seed`). The chart meshes overlap near seams, which
samples those bands twice; with the default margin the effect is small.
\throws std::invalid_argument if `reference` has no face, a face that is not a triangle, or a coordinate
that is not finite or beyond `maximum_coordinate_magnitude`.
*/
template <class GeomTraits>
double symmetric_chamfer_distance(const std::vector<Chart_mesh<GeomTraits>>& model,
                                  const CGAL::Surface_mesh<typename GeomTraits::Point_3>& reference,
                                  std::size_t samples = 20000, unsigned int seed = 0)
{
  typedef CGAL::Surface_mesh<typename GeomTraits::Point_3> Mesh;
  std::vector<std::array<typename GeomTraits::Point_3, 3>> model_triangles;
  std::vector<const Mesh*> model_meshes;
  for(const auto& cm : model)
  {
    const auto t = internal::mesh_triangles(cm.mesh());
    model_triangles.insert(model_triangles.end(), t.begin(), t.end());
    model_meshes.push_back(&cm.mesh());
  }
  const auto from_model = internal::sample_triangles(model_triangles, samples, seed);
  return internal::symmetric_chamfer_distance(from_model, model_meshes, reference, samples, seed);
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_FIT_METRICS_H
