// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_COMPONENT_SHAPE_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_COMPONENT_SHAPE_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/internal/Parameter_table.h>

#include <CGAL/number_utils.h>

#include <Eigen/Core>

#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeBlending

A component of a blended shape with its type erased: any model of
`BlendedShapePrimitive` behind one interface with dynamic-size parameter
vectors, so that one blended shape can hold ellipsoids, toroids, hole
components and user primitives side by side (sec. 3.6: the leaves of the
blending hierarchy are primitives of any kind). Points are
`Eigen::Vector3d` in the component's own frame (the kernel's `FT` is
`double` for every supported kernel).

Make one with `make_component_shape()`; recover the primitive with
`primitive<P>()`.
*/
class Component_shape
{
public:
  typedef Eigen::Matrix<double, 3, Eigen::Dynamic> Jacobian; ///< ds/dq, 3 x number_of_parameters()
  typedef Eigen::Matrix<double, 3, 2> Chart_jacobian;        ///< ds/d(x, y) in the chart

  virtual ~Component_shape() = default;
  /// A copy of this component.
  virtual std::unique_ptr<Component_shape> clone() const = 0;
  /// The primitive's type name as stored in model files ("superquadric_ellipsoid", ...).
  virtual std::string type_name() const = 0;

  /// The dimension of the parameter vector.
  virtual std::size_t number_of_parameters() const = 0;
  /// Name, bounds, default and kind of parameter `i`.
  virtual const Parameter_info& parameter_info(std::size_t i) const = 0;
  /// The current parameters.
  virtual Eigen::VectorXd parameters() const = 0;
  /// \throws std::invalid_argument on a wrong size or invalid values (the component is then unchanged).
  virtual void set_parameters(const Eigen::VectorXd& q) = 0;

  /// The number of charts.
  virtual std::size_t number_of_charts() const = 0;
  /// The domain of chart `c`.
  virtual Chart_domain chart_domain(std::size_t c) const = 0;
  /// The same surface point in chart `target`, if that chart holds it.
  virtual bool to_chart(const Chart_point& p, std::size_t target, Chart_point& q) const = 0;
  /// The canonical chart point of the primitive's own quotient (its seams).
  virtual Chart_point canonical_chart_point(const Chart_point& p) const = 0;

  /// s(p).
  virtual Eigen::Vector3d point(const Chart_point& p) const = 0;
  /// s(p) and ds/dq (`J` resized to 3 x number_of_parameters()).
  virtual Eigen::Vector3d point_and_jacobian(const Chart_point& p, Jacobian& J) const = 0;
  /// s(p) and ds/d(x, y): analytic when the primitive provides
  /// `point_and_chart_jacobian()`, central differences otherwise.
  virtual Eigen::Vector3d point_and_chart_jacobian(const Chart_point& p, Chart_jacobian& D) const = 0;
  /// The unit outward normal at `p`.
  virtual Eigen::Vector3d normal(const Chart_point& p) const = 0;

  /// The primitive, if it is a `Primitive`; null otherwise.
  template <class Primitive>
  const Primitive* primitive() const;
  /// The primitive, if it is a `Primitive`; null otherwise.
  template <class Primitive>
  Primitive* primitive();
};

namespace internal {

template <class P, class = void>
struct Has_chart_jacobian : std::false_type
{};
template <class P>
struct Has_chart_jacobian<P, std::void_t<decltype(std::declval<const P&>().point_and_chart_jacobian(
                                 std::declval<const Chart_point&>(), std::declval<Eigen::Matrix<double, 3, 2>&>()))>>
  : std::true_type
{};

template <class Point>
Eigen::Vector3d to_eigen(const Point& p)
{
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

} // namespace internal

/// \ingroup PkgBlendedShapeBlending
/// The `Component_shape` holding a `Primitive` (any model of `BlendedShapePrimitive`).
template <class Primitive>
class Primitive_component : public Component_shape
{
public:
  /// Holds a copy of `p`, stored in files under `type_name`.
  Primitive_component(const Primitive& p, std::string type_name) : m_primitive(p), m_name(std::move(type_name)) {}

  /// The primitive.
  const Primitive& get() const { return m_primitive; }
  /// The primitive.
  Primitive& get() { return m_primitive; }

  std::unique_ptr<Component_shape> clone() const override
  {
    return std::unique_ptr<Component_shape>(new Primitive_component(*this));
  }
  std::string type_name() const override { return m_name; }
  std::size_t number_of_parameters() const override { return std::size_t(Primitive::number_of_parameters); }
  const Parameter_info& parameter_info(std::size_t i) const override { return Primitive::parameter_info(int(i)); }
  Eigen::VectorXd parameters() const override { return m_primitive.parameters(); }
  void set_parameters(const Eigen::VectorXd& q) override
  {
    if(q.size() != Eigen::Index(Primitive::number_of_parameters))
      throw std::invalid_argument("Component_shape::set_parameters: " + m_name + " has " +
                                  std::to_string(Primitive::number_of_parameters) + " parameters, got " +
                                  std::to_string(q.size()));
    m_primitive.set_parameters(typename Primitive::Parameter_vector(q));
  }
  std::size_t number_of_charts() const override { return m_primitive.number_of_charts(); }
  Chart_domain chart_domain(std::size_t c) const override { return m_primitive.chart_domain(c); }
  bool to_chart(const Chart_point& p, std::size_t target, Chart_point& q) const override
  {
    return m_primitive.to_chart(p, target, q);
  }
  Chart_point canonical_chart_point(const Chart_point& p) const override { return m_primitive.canonical_chart_point(p); }
  Eigen::Vector3d point(const Chart_point& p) const override { return internal::to_eigen(m_primitive.point(p)); }
  Eigen::Vector3d point_and_jacobian(const Chart_point& p, Jacobian& J) const override
  {
    typename Primitive::Jacobian Jp;
    const Eigen::Vector3d x = internal::to_eigen(m_primitive.point_and_jacobian(p, Jp));
    J = Jp;
    return x;
  }
  Eigen::Vector3d point_and_chart_jacobian(const Chart_point& p, Chart_jacobian& D) const override
  {
    if constexpr(internal::Has_chart_jacobian<Primitive>::value)
      return internal::to_eigen(m_primitive.point_and_chart_jacobian(p, D));
    else
    {
      const double h = 1e-6;
      D.col(0) = (point(Chart_point(p.chart, p.x + h, p.y)) - point(Chart_point(p.chart, p.x - h, p.y))) / (2. * h);
      D.col(1) = (point(Chart_point(p.chart, p.x, p.y + h)) - point(Chart_point(p.chart, p.x, p.y - h))) / (2. * h);
      return point(p);
    }
  }
  Eigen::Vector3d normal(const Chart_point& p) const override
  {
    const auto n = m_primitive.normal(p);
    return Eigen::Vector3d(CGAL::to_double(n.x()), CGAL::to_double(n.y()), CGAL::to_double(n.z()));
  }

private:
  Primitive m_primitive;
  std::string m_name;
};

template <class Primitive>
const Primitive* Component_shape::primitive() const
{
  const auto* c = dynamic_cast<const Primitive_component<Primitive>*>(this);
  return c ? &c->get() : nullptr;
}

template <class Primitive>
Primitive* Component_shape::primitive()
{
  auto* c = dynamic_cast<Primitive_component<Primitive>*>(this);
  return c ? &c->get() : nullptr;
}

/// \ingroup PkgBlendedShapeBlending
/// A `Component_shape` holding a copy of `p`, named `type_name` in model files.
template <class Primitive>
std::unique_ptr<Component_shape> make_component_shape(const Primitive& p, const std::string& type_name)
{
  return std::unique_ptr<Component_shape>(new Primitive_component<Primitive>(p, type_name));
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_COMPONENT_SHAPE_H
