// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INTERNAL_POINT_NORMALIZATION_H
#define CGAL_BLENDED_SHAPE_FITTING_INTERNAL_POINT_NORMALIZATION_H

#include <CGAL/Blended_shape/Fitting/Fit_metrics.h>
#include <CGAL/Blended_shape/Fitting/initialize_from_moments.h>
#include <CGAL/Blended_shape/IO/check_points.h>
#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>

#include <CGAL/Surface_mesh.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The similarity that brings a point cloud to the origin at about unit size
// before a fit, `p -> (p - center) / scale`, and takes the fit's results
// back. The fit then sees the same numbers whatever the unit and the place
// of the data: its absolute tolerances and bounds (the parameter tables'
// bounds, the floors of the fitter) act relative to the data, no squared
// distance overflows or underflows, and no digits are lost to an offset
// far from the origin (scanner coordinates).
//
// The center is that of the bounding box; the scale is the power of two
// just above half the box's largest side (the normalized points are in
// [-1, 1]^3 with a side of at least 1/2), so that dividing by it, and
// multiplying back, is exact: only the subtraction of the center rounds.
// A `factor` other than 1 multiplies that scale (the runs of
// Evolution_settings::evolution_runs: the same points, rounded otherwise).
template <class GeomTraits>
class Point_normalization
{
public:
  typedef typename GeomTraits::Point_3 Point_3;

  // \throws Input_error if the points are unusable (check_points()), before anything else.
  template <class PointRange, class PointMap>
  Point_normalization(const PointRange& points, PointMap point_map, double factor = 1.)
  {
    check_points(points, point_map);
    Eigen::Vector3d low = Eigen::Vector3d::Constant(HUGE_VAL), high = -low;
    for(const auto& item : points)
    {
      const Eigen::Vector3d p = coordinates(get(point_map, item));
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    m_center = 0.5 * low + 0.5 * high; // halves first: no overflow
    int exponent;
    std::frexp(0.5 * (high - low).maxCoeff(), &exponent); // half the side = m 2^exponent, m in [1/2, 1)
    m_scale = std::ldexp(1., exponent) * factor;
  }

  const Eigen::Vector3d& center() const { return m_center; }
  double scale() const { return m_scale; }

  Eigen::Vector3d to_normalized(const Eigen::Vector3d& p) const { return (p - m_center) / m_scale; }
  Point_3 to_normalized(const Point_3& p) const { return point(to_normalized(coordinates(p))); }
  Eigen::Vector3d from_normalized(const Eigen::Vector3d& p) const { return m_center + m_scale * p; }
  Point_3 from_normalized(const Point_3& p) const { return point(from_normalized(coordinates(p))); }

  template <class PointRange, class PointMap>
  std::vector<Point_3> normalized_points(const PointRange& points, PointMap point_map) const
  {
    std::vector<Point_3> result;
    result.reserve(std::size_t(std::distance(std::begin(points), std::end(points))));
    for(const auto& item : points)
      result.push_back(to_normalized(get(point_map, item)));
    return result;
  }

  // A copy of `mesh` (a CGAL::Surface_mesh), normalized.
  template <class Mesh>
  Mesh to_normalized_mesh(Mesh mesh) const
  {
    for(auto v : mesh.vertices())
      mesh.point(v) = to_normalized(mesh.point(v));
    return mesh;
  }

  // A model fitted to the normalized points, in the frame of the input: its
  // translation (the first parameters, see Rigid_pose::model_parameters())
  // moved and scaled, every other length (Parameter_kind::Length: sizes,
  // the placements of added components relative to their parents) scaled;
  // the rest is invariant. For any model of `DeformableModel`.
  template <class Model>
  Model model_from_normalized(const Model& model) const
  {
    return transformed(model, m_center, m_scale);
  }

  // The inverse: `model`, given in the frame of the input, in the normalized frame.
  template <class Model>
  Model model_to_normalized(const Model& model) const
  {
    return transformed(model, -m_center / m_scale, 1. / m_scale);
  }

  Ellipsoid_fit<GeomTraits> from_normalized(Ellipsoid_fit<GeomTraits> fit) const
  {
    fit.center = from_normalized(fit.center);
    return scaled_axes(fit, m_scale);
  }

  Ellipsoid_fit<GeomTraits> to_normalized(Ellipsoid_fit<GeomTraits> fit) const
  {
    fit.center = to_normalized(fit.center);
    return scaled_axes(fit, 1. / m_scale);
  }

  // The figures of a fit of the normalized points, for the input: the
  // distances scaled, the ratios (relative RMS, RMS over the diagonal) invariant.
  Fit_metrics from_normalized(Fit_metrics metrics) const
  {
    metrics.rms *= m_scale;
    if(metrics.chamfer_distance)
      *metrics.chamfer_distance *= m_scale;
    return metrics;
  }

  // The chart meshes of a fitter of the normalized points positioned by
  // `model`, the fitted model in the frame of the input (model_from_normalized()).
  template <class Model>
  static std::vector<Chart_mesh<GeomTraits>> positioned_meshes(std::vector<Chart_mesh<GeomTraits>> meshes,
                                                                const Model& model)
  {
    for(Chart_mesh<GeomTraits>& cm : meshes)
      cm.set_positions([&](const Chart_point& u) { return model.point(u); });
    return meshes;
  }

private:
  // `model` scaled by `scale` about the origin, then moved by `shift`: the
  // pose's translation (its first three parameters) and every length.
  template <class Model>
  static Model transformed(const Model& model, const Eigen::Vector3d& shift, double scale)
  {
    Eigen::VectorXd q = model.parameters();
    for(std::size_t i = 0; i < model.number_of_parameters(); ++i)
    {
      const Eigen::Index k = Eigen::Index(i);
      if(i < 3)
        q[k] = shift[k] + scale * q[k];
      else if(model.parameter_kind(i) == Parameter_kind::Length)
        q[k] *= scale;
    }
    Model result = model;
    result.set_parameters(q);
    return result;
  }

  static Ellipsoid_fit<GeomTraits> scaled_axes(Ellipsoid_fit<GeomTraits> fit, double scale)
  {
    for(std::size_t i = 0; i < 3; ++i)
    {
      fit.axes[i] *= scale;
      fit.moment_axes[i] *= scale;
    }
    return fit;
  }

  static Eigen::Vector3d coordinates(const Point_3& p)
  {
    return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  }
  static Point_3 point(const Eigen::Vector3d& p) { return Point_3(p[0], p[1], p[2]); }

  Eigen::Vector3d m_center;
  double m_scale;
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INTERNAL_POINT_NORMALIZATION_H
