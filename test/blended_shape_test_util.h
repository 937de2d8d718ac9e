// SPDX-License-Identifier: LGPL-3.0-or-later
// Helpers shared by the blended-shape test programs: setting one named
// parameter, moving and reshaping a component a little, opening a pole hole.
#ifndef CGAL_BLENDED_SHAPE_BLENDED_SHAPE_TEST_UTIL_H
#define CGAL_BLENDED_SHAPE_BLENDED_SHAPE_TEST_UTIL_H

#include <Eigen/Core>

#include <cstddef>
#include <stdexcept>
#include <string>

namespace blended_shape_test {

// The index of the named parameter ("c1.a1", "b0.h", ...) of a Blended_shape.
// \throws std::logic_error if there is no such parameter.
template <class Shape>
std::size_t parameter_index(const Shape& s, const std::string& name)
{
  for(std::size_t i = 0; i < s.number_of_parameters(); ++i)
    if(s.parameter_name(i) == name)
      return i;
  throw std::logic_error("no parameter " + name);
}

// Sets one named parameter ("c1.a1", "b0.h", ...) of a Blended_shape through
// set_parameters(). \throws std::logic_error if there is no such parameter.
template <class Shape>
void set_parameter(Shape& s, const std::string& name, double value)
{
  Eigen::VectorXd q = s.parameters();
  q[Eigen::Index(parameter_index(s, name))] = value;
  s.set_parameters(q);
}

// Moves and reshapes non-root component c a little (so that blends join
// different shapes): its translation, a small rotation (quaternion x) and
// its first two shape parameters.
template <class Shape>
void perturb_component(Shape& s, std::size_t c, double amount)
{
  Eigen::VectorXd q = s.parameters();
  const std::size_t o = s.component_offset(c);
  q[Eigen::Index(o)] += 0.07 * amount;
  q[Eigen::Index(o + 1)] -= 0.05 * amount;
  q[Eigen::Index(o + 4)] += 0.08 * amount; // quaternion x: a small rotation
  const std::size_t so = s.shape_offset(c);
  q[Eigen::Index(so)] *= 1. + 0.15 * amount;
  q[Eigen::Index(so + 1)] *= 1. - 0.1 * amount;
  s.set_parameters(q);
}

// Opens the closed hole of a sphere with one hole from pole to pole (its
// blends b0 and b1, its tube component c1): both blends down to h = 0, the
// hole switched to its tube, which is then widened: the tunnel of a genus-1
// test shape.
template <class Shape>
void open_pole_hole(Shape& s)
{
  set_parameter(s, "b0.h", 0.);
  set_parameter(s, "b1.h", 0.);
  s.switch_hole_to_tube(0);
  set_parameter(s, "b0.w", 0.9);
  set_parameter(s, "b1.w", 0.8);
  set_parameter(s, "c1.a4", 1.3);
  set_parameter(s, "c1.a5", 1.25);
  set_parameter(s, "c1.e1", 0.9);
}

} // namespace blended_shape_test

#endif
