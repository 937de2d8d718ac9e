// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_INTERNAL_PARAMETER_TABLE_H
#define CGAL_BLENDED_SHAPE_INTERNAL_PARAMETER_TABLE_H

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace CGAL {
namespace Blended_shapes {

/// \ingroup PkgBlendedShapePrimitives
/// Whether a parameter is a length (it scales with the shape) or a pure number.
enum class Parameter_kind
{
  Length,        ///< scales with the shape (semi-axes): bounded by the data's size when fitting
  Dimensionless  ///< exponents, ratios, tapers: invariant under scaling
};

/// \ingroup PkgBlendedShapePrimitives
/// The lower bound of the sizes of primitives (semi-axes): the smallest positive
/// normal double, so that a model of data of any scale can be held; fits keep
/// sizes above a fraction of the data's size instead (see Deformable_model_fitter).
constexpr double smallest_size = std::numeric_limits<double>::min();

/// \ingroup PkgBlendedShapePrimitives
/// Name, bounds, default value and kind of one primitive parameter.
struct Parameter_info
{
  const char* name;
  double lower_bound;
  double upper_bound;
  double default_value;
  Parameter_kind kind;
};

namespace internal {

/// Throws std::invalid_argument naming the first parameter of `q` that is
/// not finite or lies outside its bounds: the one check every primitive's
/// `set_parameters()` shares.
template <int P>
void validate_parameters(const char* owner,
                         const std::array<Parameter_info, P>& table,
                         const Eigen::Matrix<double, P, 1>& q)
{
  for(int i = 0; i < P; ++i)
  {
    const Parameter_info& info = table[std::size_t(i)];
    if(std::isfinite(q[i]) && q[i] >= info.lower_bound && q[i] <= info.upper_bound)
      continue;
    std::ostringstream msg;
    msg.precision(17);
    msg << owner << ": parameter " << info.name << " = " << q[i]
        << " is not in [" << info.lower_bound << ", " << info.upper_bound
        << "]; pass a finite value inside the bounds (see parameter_lower_bound()"
           " and parameter_upper_bound())";
    throw std::invalid_argument(msg.str());
  }
}

template <int P>
Eigen::Matrix<double, P, 1> default_parameters(const std::array<Parameter_info, P>& table)
{
  Eigen::Matrix<double, P, 1> q;
  for(int i = 0; i < P; ++i)
    q[i] = table[std::size_t(i)].default_value;
  return q;
}

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_INTERNAL_PARAMETER_TABLE_H
