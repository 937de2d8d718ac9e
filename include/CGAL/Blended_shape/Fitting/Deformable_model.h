// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_DEFORMABLE_MODEL_H
#define CGAL_BLENDED_SHAPE_FITTING_DEFORMABLE_MODEL_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>
#include <CGAL/Blended_shape/Fitting/internal/Rigid_pose.h>

#include <Eigen/Core>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeFitting

The deformable model of sec. 5.1, eq. 5: `x(u) = c + R s(u)`, with `s` a
shape (any model of `BlendedShapePrimitive`), `c` a translation and `R` the
rotation of a quaternion. Its parameter vector is
`q = (cx, cy, cz, qw, qx, qy, qz, q_s)` (`q_s` the shape's parameters) and its
Jacobian `L = dx/dq` (eq. 6) is the 3 x (7 + P) matrix
`[ I | (dR/dq_theta) s | R ds/dq_s ]`.

The rotation is that of `q_theta / |q_theta|` (`q_theta = (qw, qx, qy, qz)`), so no unit-norm
constraint is needed while fitting; set_parameters() stores the quaternion
normalized (the geometry does not change).

\tparam Shape a model of `BlendedShapePrimitive`.
*/
template <class Shape>
class Deformable_model
{
public:
  typedef Shape Shape_type;                         ///< the primitive
  typedef typename Shape::Geom_traits Geom_traits;  ///< the kernel
  typedef typename Geom_traits::Point_3 Point_3;    ///< the point type
  typedef typename Geom_traits::Vector_3 Vector_3;  ///< the vector type
  /// The model Jacobian `L = dx/dq`, 3 x number_of_parameters().
  typedef Eigen::Matrix<double, 3, Eigen::Dynamic> Jacobian;
  /// The chart Jacobian of the model point (3 x 2): its derivatives with
  /// respect to the two chart coordinates of `u`.
  typedef Eigen::Matrix<double, 3, 2> Chart_jacobian;

  /// The translation (3) and the quaternion (4), first in the parameter vector.
  static constexpr int number_of_pose_parameters = internal::Rigid_pose::number_of_parameters;
  /// The shape's parameters, after the pose.
  static constexpr int number_of_shape_parameters = Shape::number_of_parameters;

  /// The shape at the origin, unrotated.
  explicit Deformable_model(const Shape& shape = Shape()) : m_shape(shape) {}

  /// \throws std::invalid_argument if `quaternion` is zero or not finite.
  Deformable_model(const Shape& shape, const Eigen::Vector3d& translation, const Eigen::Vector4d& quaternion)
    : m_shape(shape)
  {
    Eigen::VectorXd q(number_of_parameters());
    q << translation, quaternion, shape.parameters();
    set_parameters(q);
  }

  /// The shape, in its own frame.
  const Shape& shape() const { return m_shape; }
  /// The translation `c`.
  const Eigen::Vector3d& translation() const { return m_pose.c; }
  /// The rotation as a unit quaternion (w, x, y, z).
  const Eigen::Vector4d& quaternion() const { return m_pose.quaternion; }
  /// The rotation matrix `R`.
  const Eigen::Matrix3d& rotation() const { return m_pose.R; }

  /// \name Parameters
  /// @{

  /// `7 + P`, with `P` the number of parameters of the shape.
  std::size_t number_of_parameters() const { return number_of_pose_parameters + number_of_shape_parameters; }

  /// The name of parameter `i`: "cx", "cy", "cz", "qw", "qx", "qy", "qz", then the shape's names.
  std::string parameter_name(std::size_t i) const
  {
    return i < number_of_pose_parameters ? internal::Rigid_pose::parameter_name(i)
                                         : Shape::parameter_name(int(i) - number_of_pose_parameters);
  }
  /// The smallest allowed value of parameter `i` (`-HUGE_VAL` for the pose).
  double parameter_lower_bound(std::size_t i) const
  {
    return i < number_of_pose_parameters ? -HUGE_VAL : Shape::parameter_lower_bound(int(i) - number_of_pose_parameters);
  }
  /// The largest allowed value of parameter `i` (`HUGE_VAL` for the pose).
  double parameter_upper_bound(std::size_t i) const
  {
    return i < number_of_pose_parameters ? HUGE_VAL : Shape::parameter_upper_bound(int(i) - number_of_pose_parameters);
  }
  /// The kind of parameter `i`; the translation counts as a length, the quaternion as dimensionless.
  Parameter_kind parameter_kind(std::size_t i) const
  {
    if(i < number_of_pose_parameters) return internal::Rigid_pose::parameter_kind(i);
    return Shape::parameter_info(int(i) - number_of_pose_parameters).kind;
  }
  /// Whether parameter `i` belongs to the rigid placement (translation, rotation).
  bool is_pose_parameter(std::size_t i) const { return i < number_of_pose_parameters; }
  /// Whether parameter `i` places a component relative to another: never (one primitive).
  bool is_placement_parameter(std::size_t) const { return false; }
  /// Whether parameter `i` places a blending region: never (one primitive).
  bool is_blending_region_parameter(std::size_t) const { return false; }

  /// The parameter vector `q` (the quaternion is stored normalized).
  Eigen::VectorXd parameters() const { return m_pose.model_parameters(m_shape.parameters()); }

  /// \throws std::invalid_argument if a shape parameter is out of bounds or
  /// the quaternion is zero or not finite.
  void set_parameters(const Eigen::VectorXd& q)
  {
    m_pose.set_model_parameters(
      q, number_of_parameters(), [&](const auto& shape_q) { m_shape.set_parameters(shape_q); }, "Deformable_model");
  }

  /// @}

  /// \name Charts (those of the shape)
  /// @{

  /// The number of charts of the shape.
  std::size_t number_of_charts() const { return m_shape.number_of_charts(); }
  /// The domain of chart `c` of the shape.
  Chart_domain chart_domain(std::size_t c) const { return m_shape.chart_domain(c); }
  /// The shape's canonical chart point of `u`.
  Chart_point canonical_chart_point(const Chart_point& u) const { return m_shape.canonical_chart_point(u); }
  /// Whether `u` is in its chart's domain (every such point is on the surface of a primitive).
  bool is_on_surface(const Chart_point& u) const
  {
    return u.chart < number_of_charts() && chart_domain(u.chart).contains(u.x, u.y);
  }
  /// The other chart points of the same surface point: none needed (the
  /// charts overlap, so a projection never meets a chart's edge while on
  /// the surface; see Deformable_blended_model::alternative_chart_points()).
  std::vector<Chart_point> alternative_chart_points(const Chart_point&) const { return {}; }
  /// The canonical chart point of `u` in `canonical`, if `u` is in its chart's domain; otherwise false.
  bool canonical_surface_point(const Chart_point& u, Chart_point& canonical) const
  {
    if(!is_on_surface(u))
      return false;
    canonical = canonical_chart_point(u);
    return true;
  }
  /// canonical_surface_point() and, where it is true, point_and_chart_jacobian()
  /// at the canonical point in `x` and `D` (see Deformable_blended_model).
  bool canonical_surface_point_and_chart_jacobian(const Chart_point& u, Chart_point& canonical, Point_3& x,
                                                  Chart_jacobian& D) const
  {
    if(!canonical_surface_point(u, canonical))
      return false;
    x = point_and_chart_jacobian(canonical, D);
    return true;
  }
  /// @}

  /// \name Evaluation
  /// @{

  /// The model point `x(u) = c + R s(u)`.
  Point_3 point(const Chart_point& u) const { return place(m_shape.point(u)); }

  /// The unit outward normal at `u`: `R` times the shape's normal.
  Vector_3 normal(const Chart_point& u) const
  {
    const Vector_3 n = m_shape.normal(u);
    const Eigen::Vector3d r = m_pose.R * Eigen::Vector3d(n.x(), n.y(), n.z());
    return Vector_3(r[0], r[1], r[2]);
  }

  /// x(u) and L(u) = dx/dq (eq. 6); `L` is resized to 3 x number_of_parameters().
  Point_3 point_and_jacobian(const Chart_point& u, Jacobian& L) const
  {
    typename Shape::Jacobian Js;
    const Point_3 s = m_shape.point_and_jacobian(u, Js);
    const Eigen::Vector3d sv(s.x(), s.y(), s.z());
    L.resize(3, Eigen::Index(number_of_parameters()));
    m_pose.jacobian(sv, L.template leftCols<number_of_pose_parameters>());
    L.template rightCols<number_of_shape_parameters>().noalias() = m_pose.R * Js;
    return place(s);
  }

  /// x(u), the same as point(), and the chart Jacobian `D = R ds/du`, from
  /// the shape's point_and_chart_jacobian() (the pose does not depend on `u`).
  Point_3 point_and_chart_jacobian(const Chart_point& u, Chart_jacobian& D) const
  {
    typename Shape::Chart_jacobian Ds;
    const Point_3 s = m_shape.point_and_chart_jacobian(u, Ds);
    D.noalias() = m_pose.R * Ds;
    return place(s);
  }
  /// @}

  /// c + R s: a point of the shape's frame placed in space.
  Point_3 place(const Point_3& s) const
  {
    const Eigen::Vector3d x = m_pose.place(Eigen::Vector3d(s.x(), s.y(), s.z()));
    return Point_3(x[0], x[1], x[2]);
  }

private:
  Shape m_shape;
  internal::Rigid_pose m_pose;
};

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_DEFORMABLE_MODEL_H
