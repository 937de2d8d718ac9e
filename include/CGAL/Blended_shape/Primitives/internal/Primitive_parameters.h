// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_PRIMITIVE_PARAMETERS_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_PRIMITIVE_PARAMETERS_H

// The parameter side of the package's primitives (concept
// BlendedShapePrimitive): the queries answered from a table of names, bounds
// and defaults, and the parameter vector checked against it.

#include <CGAL/Blended_shape/internal/Parameter_table.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

/// The `P` parameters of a primitive, in order, and the primitive's name for error messages.
template <int P>
struct Parameter_table
{
  const char* owner;
  std::array<Parameter_info, P> info;
};

/// The static parameter queries of the BlendedShapePrimitive concept, from `table()`.
template <int P, const Parameter_table<P>& (*table)()>
struct Parameter_queries
{
  /// Name, bounds, default value and kind of parameter `i`.
  static const Parameter_info& parameter_info(int i) { return table().info[std::size_t(i)]; }
  /// The name of parameter `i` ("a1", ...).
  static const char* parameter_name(int i) { return parameter_info(i).name; }
  /// The smallest allowed value of parameter `i`.
  static double parameter_lower_bound(int i) { return parameter_info(i).lower_bound; }
  /// The largest allowed value of parameter `i`.
  static double parameter_upper_bound(int i) { return parameter_info(i).upper_bound; }
  /// The default value of parameter `i`.
  static double parameter_default_value(int i) { return parameter_info(i).default_value; }
};

/// The queries, the Eigen types sized by `P`, and the parameter vector itself,
/// checked against the bounds of `table()` on every change.
template <int P, const Parameter_table<P>& (*table)()>
class Checked_parameters : public Parameter_queries<P, table>
{
public:
  /// The dimension of the parameter vector.
  static constexpr int number_of_parameters = P;
  /// The parameter vector (see the primitive's Parameter_index for the order).
  typedef Eigen::Matrix<double, P, 1> Parameter_vector;
  /// The parameter Jacobian ds/dq at one chart point (3 x P).
  typedef Eigen::Matrix<double, 3, P> Jacobian;
  /// The chart Jacobian [ds/dx, ds/dy] at one chart point (3 x 2).
  typedef Eigen::Matrix<double, 3, 2> Chart_jacobian;

  /// The current parameters.
  const Parameter_vector& parameters() const { return m_q; }

  /// \throws std::invalid_argument if a value is not finite or out of bounds.
  void set_parameters(const Parameter_vector& q)
  {
    validate_parameters<P>(table().owner, table().info, q);
    m_q = q;
  }

protected:
  Parameter_vector m_q;
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_INTERNAL_PRIMITIVE_PARAMETERS_H
