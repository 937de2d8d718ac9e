// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_DEFORMABLE_BLENDED_MODEL_H
#define CGAL_BLENDED_SHAPE_FITTING_DEFORMABLE_BLENDED_MODEL_H

#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model.h>
#include <CGAL/Blended_shape/Fitting/internal/Rigid_pose.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>

#include <Eigen/Core>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeFitting

The deformable model of sec. 5.1-5.2 for a blended shape: `x(u) = c + R s(u)`
(eq. 5) with `s` a `Blended_shape`, `c` a translation and `R` the rotation
of a quaternion. Its parameter vector is `q = (cx, cy, cz, qw, qx, qy, qz,
q_s)` with `q_s` the blended shape's parameters (eq. 9: the components', in
their order, then the blends'), and its Jacobian `L = dx/dq` (eq. 6, 10, 11)
is `[ I | (dR/dq_theta) s | R ds/dq_s ]`, sparse by component: a point
depends only on the components and blends that reach it (point_and_jacobian()
fills the others with zeros; point_and_sparse_jacobian() leaves them out).

It has the interface Deformable_model_fitter asks of a model, so a blended
shape of fixed structure is fitted the same way as a single superquadric
(Deformable_model). Its charts are those of all the components, numbered in
order: chart `g` of the model is chart `local_chart(g)` of component
`chart_component(g)`. A chart point is on the surface unless it lies in a
discarded part of its component's domain (is_on_surface()).

\tparam GeomTraits a CGAL kernel whose `FT` is `double`.
*/
template <class GeomTraits>
class Deformable_blended_model
{
public:
  typedef Blended_shape<GeomTraits> Shape_type;          ///< the blended shape
  typedef typename Shape_type::Geom_traits Geom_traits; ///< the kernel (the shape's)
  typedef typename Shape_type::Point_3 Point_3;         ///< the point type
  typedef typename Shape_type::Vector_3 Vector_3;       ///< the vector type
  /// The model Jacobian `L = dx/dq`, 3 x number_of_parameters().
  typedef Eigen::Matrix<double, 3, Eigen::Dynamic> Jacobian;
  /// The chart Jacobian of the model point: its derivatives with respect to the two chart coordinates.
  typedef Eigen::Matrix<double, 3, 2> Chart_jacobian;
  /// The translation (3) and the quaternion (4), first in the parameter vector.
  static constexpr int number_of_pose_parameters = internal::Rigid_pose::number_of_parameters;

  /// The shape `s` placed at `translation`, rotated by `quaternion` (w, x, y, z).
  /// \throws std::invalid_argument if the quaternion is zero or not finite or the translation not finite.
  explicit Deformable_blended_model(const Shape_type& shape,
                                    const Eigen::Vector3d& translation = Eigen::Vector3d::Zero(),
                                    const Eigen::Vector4d& quaternion = Eigen::Vector4d(1., 0., 0., 0.))
    : m_shape(shape)
  {
    m_pose.set(translation, quaternion, "Deformable_blended_model");
    index_charts();
  }

  /// The blended shape, in its own frame.
  const Shape_type& shape() const { return m_shape; }
  /// The translation `c`.
  const Eigen::Vector3d& translation() const { return m_pose.c; }
  /// The rotation as a unit quaternion (w, x, y, z).
  const Eigen::Vector4d& quaternion() const { return m_pose.quaternion; }
  /// The rotation matrix `R`.
  const Eigen::Matrix3d& rotation() const { return m_pose.R; }
  /// The point `c + R s` that a point `s` of the shape's own frame is placed at
  /// (e.g. to place the shape's meshes: `Blended_shape_pieces::Placement`).
  Point_3 placed(const Point_3& s) const { return place(to_eigen(s)); }

  /// \name Parameters
  /// @{

  /// `7 + ` the number of parameters of the shape.
  std::size_t number_of_parameters() const { return number_of_pose_parameters + m_shape.number_of_parameters(); }
  /// "cx", "cy", "cz", "qw", "qx", "qy", "qz", then the shape's names ("c0.a1", "b0.h", ...).
  std::string parameter_name(std::size_t i) const
  {
    return i < number_of_pose_parameters ? std::string(internal::Rigid_pose::parameter_name(i))
                                         : m_shape.parameter_name(i - number_of_pose_parameters);
  }
  /// The smallest allowed value of parameter `i` (`-HUGE_VAL` for the pose).
  double parameter_lower_bound(std::size_t i) const
  {
    return i < number_of_pose_parameters ? -HUGE_VAL : m_shape.parameter_lower_bound(i - number_of_pose_parameters);
  }
  /// The largest allowed value of parameter `i` (`HUGE_VAL` for the pose).
  double parameter_upper_bound(std::size_t i) const
  {
    return i < number_of_pose_parameters ? HUGE_VAL : m_shape.parameter_upper_bound(i - number_of_pose_parameters);
  }
  /// The kind of parameter `i`; the translation counts as a length, the quaternion as dimensionless.
  Parameter_kind parameter_kind(std::size_t i) const
  {
    if(i < number_of_pose_parameters)
      return internal::Rigid_pose::parameter_kind(i);
    return m_shape.parameter_kind(i - number_of_pose_parameters);
  }
  /// Whether parameter `i` belongs to the rigid placement `(c, R)` of the whole model.
  bool is_pose_parameter(std::size_t i) const { return i < number_of_pose_parameters; }
  /// Whether parameter `i` places an added component relative to its parent
  /// (sec. 3.5; the fitter holds these by a loose spring to where they started).
  bool is_placement_parameter(std::size_t i) const
  {
    return i >= number_of_pose_parameters && m_shape.is_placement_parameter(i - number_of_pose_parameters);
  }
  /// Whether parameter `i` places a blending region in its chart
  /// (Blended_shape::is_blending_region_parameter()): set_parameters()
  /// refuses a region that leaves its chart.
  bool is_blending_region_parameter(std::size_t i) const
  {
    return i >= number_of_pose_parameters && m_shape.is_blending_region_parameter(i - number_of_pose_parameters);
  }
  /// Whether parameter `i` is held fixed (Blended_shape::is_fixed_parameter()); its Jacobian column is zero.
  bool is_fixed_parameter(std::size_t i) const
  {
    return i >= number_of_pose_parameters && m_shape.is_fixed_parameter(i - number_of_pose_parameters);
  }

  /// The parameter vector `q` (the quaternion is stored normalized).
  Eigen::VectorXd parameters() const { return m_pose.model_parameters(m_shape.parameters()); }

  /// \throws std::invalid_argument on a wrong size, a zero or non-finite
  ///         quaternion, or shape parameters Blended_shape::set_parameters()
  ///         refuses (out of bounds, a fixed parameter changed, regions that
  ///         would leave their charts or meet); the model is then unchanged.
  void set_parameters(const Eigen::VectorXd& q)
  {
    m_pose.set_model_parameters(
      q, number_of_parameters(), [&](const auto& shape_q) { m_shape.set_parameters(shape_q); },
      "Deformable_blended_model");
  }
  /// @}

  /// \name Charts (those of all the components)
  /// @{

  /// The number of charts: the sum over the components.
  std::size_t number_of_charts() const { return m_chart_component.size(); }
  /// The component of chart `g`.
  std::size_t chart_component(std::size_t g) const { return m_chart_component.at(g); }
  /// Chart `g`'s index among its component's charts.
  std::size_t local_chart(std::size_t g) const { return g - m_first_chart.at(m_chart_component.at(g)); }
  /// The domain of chart `g`.
  Chart_domain chart_domain(std::size_t g) const
  {
    return m_shape.component(chart_component(g)).shape().chart_domain(local_chart(g));
  }
  /// The point of the blended shape's domain that chart point `u` of the model is.
  Shape_point shape_point(const Chart_point& u) const
  {
    return Shape_point(chart_component(u.chart), Chart_point(local_chart(u.chart), u.x, u.y));
  }
  /// The model chart point of `p`.
  Chart_point chart_point(const Shape_point& p) const
  {
    return Chart_point(m_first_chart.at(p.component) + p.u.chart, p.u.x, p.u.y);
  }
  /// Whether `u` is in its chart's domain and on the surface (not in a discarded part of the domain).
  bool is_on_surface(const Chart_point& u) const
  {
    return in_chart_domain(u) && m_shape.is_on_surface(shape_point(u));
  }
  /// The canonical representative of `u` (Blended_shape::canonical_point()) in
  /// `canonical`, if `u` is in its chart's domain and on the surface;
  /// otherwise false.
  bool canonical_surface_point(const Chart_point& u, Chart_point& canonical) const
  {
    if(!in_chart_domain(u))
      return false;
    const std::optional<Shape_point> c = m_shape.canonical_point(shape_point(u));
    if(!c)
      return false;
    canonical = chart_point(*c);
    return true;
  }
  /// canonical_surface_point() and, where it is true, point_and_chart_jacobian()
  /// at the canonical point in `x` and `D`, in one pass: the point is located
  /// in the blends once (the closest-point search's step).
  bool canonical_surface_point_and_chart_jacobian(const Chart_point& u, Chart_point& canonical, Point_3& x,
                                                  Chart_jacobian& D) const
  {
    return canonical_surface_point_chart_jacobian_and_normal(u, canonical, x, D, nullptr);
  }
  /// canonical_surface_point_and_chart_jacobian() and, if `n` is not null,
  /// the unit normal at the canonical point from the same evaluation: where
  /// `u` is its own canonical point, exactly what normal() gives there (the
  /// closest-point search takes its normals from here instead of locating
  /// the foot point in the blends once more).
  bool canonical_surface_point_chart_jacobian_and_normal(const Chart_point& u, Chart_point& canonical, Point_3& x,
                                                         Chart_jacobian& D, Vector_3* n) const
  {
    if(!in_chart_domain(u))
      return false;
    Shape_point c;
    Chart_jacobian Ds;
    const std::optional<Point_3> s = m_shape.canonical_point_and_chart_jacobian(shape_point(u), c, Ds);
    if(!s)
      return false;
    canonical = chart_point(c);
    D.noalias() = m_pose.R * Ds;
    x = place(to_eigen(*s));
    if(n != nullptr)
      *n = rotate(Shape_type::normal_of_chart_jacobian(Ds));
    return true;
  }
  /// The other chart points of the surface point at the canonical point `u`
  /// (Blended_shape::other_representatives()): where a closest-point
  /// projection that reached the discarded edge of a strip in `u`'s chart goes on.
  std::vector<Chart_point> alternative_chart_points(const Chart_point& u) const
  {
    std::vector<Chart_point> others;
    for(const Shape_point& p : m_shape.other_representatives(shape_point(u)))
      others.push_back(chart_point(p));
    return others;
  }
  /// @}

  /// \name Evaluation
  /// @{

  /// The model point `x(u) = c + R s(u)` (at points not on the surface, the
  /// component's own point, see Blended_shape::point()).
  Point_3 point(const Chart_point& u) const { return place(to_eigen(m_shape.point(shape_point(u)))); }

  /// The unit outward normal at `u`: `R` times the shape's normal.
  Vector_3 normal(const Chart_point& u) const { return rotate(m_shape.normal(shape_point(u))); }

  /// x(u) and its sparse Jacobian: blocks of consecutive columns of `L`
  /// (eq. 6, 10, 11): the pose, then the blocks of the shape (shifted by the pose's 7 columns).
  /// \throws std::invalid_argument if `u` is not on the surface.
  Point_3 point_and_sparse_jacobian(const Chart_point& u, typename Shape_type::Sparse_jacobian& L) const
  {
    const Point_3 sp = m_shape.point_and_jacobian(shape_point(u), L);
    const Eigen::Vector3d s = to_eigen(sp);
    for(Jacobian_block& b : L)
    {
      b.first_column += number_of_pose_parameters;
      b.columns = m_pose.R * b.columns;
    }
    Jacobian_block pose;
    pose.first_column = 0;
    pose.columns.resize(3, number_of_pose_parameters);
    m_pose.jacobian(s, pose.columns);
    L.insert(L.begin(), std::move(pose));
    return place(s);
  }

  /// x(u) and `L(u) = dx/dq` (eq. 6), dense: 3 x number_of_parameters(),
  /// zero in the columns of what does not reach `u`.
  /// \throws std::invalid_argument if `u` is not on the surface.
  Point_3 point_and_jacobian(const Chart_point& u, Jacobian& L) const
  {
    typename Shape_type::Sparse_jacobian blocks;
    const Point_3 x = point_and_sparse_jacobian(u, blocks);
    L.setZero(3, Eigen::Index(number_of_parameters()));
    for(const Jacobian_block& b : blocks)
      L.block(0, Eigen::Index(b.first_column), 3, b.columns.cols()) += b.columns;
    return x;
  }

  /// x(u) and the chart Jacobian `R ds/du` at `u`, a canonical point on the
  /// surface (canonical_surface_point()): the derivatives are with respect
  /// to `u`'s chart coordinates.
  /// \throws std::invalid_argument if `u` is not on the surface.
  Point_3 point_and_chart_jacobian(const Chart_point& u, Chart_jacobian& D) const
  {
    Chart_jacobian Ds;
    const Point_3 s = m_shape.point_and_chart_jacobian(shape_point(u), Ds);
    D.noalias() = m_pose.R * Ds;
    return place(to_eigen(s));
  }
  /// @}

private:
  bool in_chart_domain(const Chart_point& u) const
  {
    return u.chart < number_of_charts() && chart_domain(u.chart).contains(u.x, u.y);
  }
  static Eigen::Vector3d to_eigen(const Point_3& p)
  {
    return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  }
  Point_3 place(const Eigen::Vector3d& s) const
  {
    const Eigen::Vector3d x = m_pose.place(s);
    return Point_3(x[0], x[1], x[2]);
  }
  // A direction of the shape's frame in the model's: `R n`.
  Vector_3 rotate(const Vector_3& n) const
  {
    const Eigen::Vector3d r =
      m_pose.R * Eigen::Vector3d(CGAL::to_double(n.x()), CGAL::to_double(n.y()), CGAL::to_double(n.z()));
    return Vector_3(r[0], r[1], r[2]);
  }
  void index_charts()
  {
    m_first_chart.clear();
    m_chart_component.clear();
    for(std::size_t c = 0; c < m_shape.number_of_components(); ++c)
    {
      m_first_chart.push_back(m_chart_component.size());
      for(std::size_t k = 0; k < m_shape.component(c).shape().number_of_charts(); ++k)
        m_chart_component.push_back(c);
    }
  }

  Shape_type m_shape;
  internal::Rigid_pose m_pose;
  std::vector<std::size_t> m_first_chart;     // per component: its first model chart
  std::vector<std::size_t> m_chart_component; // per model chart: its component
};

/// \ingroup PkgBlendedShapeFitting
/// The blended model of one component that a fitted superquadric is: the
/// same surface, pose and parameters (e.g. fit_superquadric()'s model,
/// which part evolution starts from).
template <class GeomTraits>
Deformable_blended_model<GeomTraits>
make_blended_model(const Deformable_model<Superquadric_ellipsoid<GeomTraits>>& superquadric)
{
  return Deformable_blended_model<GeomTraits>(Blended_shape<GeomTraits>(superquadric.shape()),
                                              superquadric.translation(), superquadric.quaternion());
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_DEFORMABLE_BLENDED_MODEL_H
